#pragma once

#include <deque>
#include <functional>

#include "machine.hpp"

namespace fatc::machine {

/// The machine with its context, behind the Changer. Each event a flow can
/// take goes to the running flow first (a machine of its own, flow_run.hpp), then to the
/// machine above, as Boost.MSM hands a submachine's events on; a flow's end
/// is taken there as FlowFinished, FlowCancelled or FlowFailed.
class Engine {
 public:
  Engine(const Config& config, Ports& ports, ToolState tools);
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  template <class Event>
  void take(const Event& e);
  /// Whether a state of the machine or of the running flow carries `Flag`.
  template <class Flag>
  bool active() const {
    return fsm.is_flag_active<Flag>() || (flow() && flow()->flagged(typeid(Flag)));
  }
  FlowRun* flow() const;

  Context context;
  Machine fsm;

 private:
  void take_flow_end();
  bool taking_ = false;
  /// Events raised while one is in hand: taken after it, in order, as
  /// Boost.MSM queues an event a machine raises while it processes one.
  std::deque<std::function<void()>> later_;
};

template <class Event>
void Engine::take(const Event& e) {
  if (taking_) {
    later_.push_back([this, e] { take(e); });
    return;
  }
  taking_ = true;
  namespace back = boost::msm::back;
  back::HandledEnum by_flow = back::HANDLED_FALSE;
  if constexpr (flow_takes<Event>) {
    if (flow()) by_flow = flow()->take(e);
  }
  take_flow_end();
  if (!(by_flow & (back::HANDLED_TRUE | back::HANDLED_DEFERRED))) {
    fsm.flow_declined = by_flow == back::HANDLED_GUARD_REJECT;
    fsm.process_event(e);
    fsm.flow_declined = false;
    take_flow_end();
  }
  taking_ = false;
  while (!later_.empty()) {
    const auto next = std::move(later_.front());
    later_.pop_front();
    next();
  }
}

}  // namespace fatc::machine
