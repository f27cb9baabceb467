#include "step_gate.hpp"

namespace fatc {

void StepGate::end() {
  on_ = false;
  held_.clear();
  rest.clear();
}

void StepGate::hold(Prompt question, std::function<void()> go) {
  held_.push_back({std::move(question), {std::move(go)}});
}

void StepGate::then(std::function<void()> effect) {
  if (holding()) {
    held_.back().effects.push_back(std::move(effect));
  } else {
    effect();
  }
}

void StepGate::release() {
  // Taken out first: an effect may hold the next step.
  const Held first = std::move(held_.front());
  held_.pop_front();
  for (const auto& effect : first.effects) effect();
}

}  // namespace fatc
