#include "step_gate.hpp"

namespace fatc {

void StepGate::end() {
  on_ = false;
  held_.clear();
  rest.clear();
}

void StepGate::hold(Prompt question, std::function<void()> go) {
  question_ = std::move(question);
  held_.push_back(std::move(go));
}

void StepGate::then(std::function<void()> effect) {
  if (holding()) {
    held_.push_back(std::move(effect));
  } else {
    effect();
  }
}

void StepGate::release() {
  // A copy first: an effect may hold the next step.
  const auto effects = std::move(held_);
  held_.clear();
  for (const auto& effect : effects) effect();
}

}  // namespace fatc
