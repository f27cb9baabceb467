// The machine behind the Changer, and Operating's event dispatch, generated
// here and nowhere else (favor_compile_time, see Machine_of in common.hpp):
// the flows' tables are dispatched in their own files (flow_run_of.hpp).

#include "engine.hpp"

BOOST_MSM_BACK_GENERATE_PROCESS_EVENT(fatc::machine::Operating)

namespace fatc::machine {

Engine::Engine(const Config& config, Ports& ports, ToolState tools)
    : context(config, ports, std::move(tools)), fsm(&context) {
  context.raise.unsafe_step = [this](const std::string& why) { take(UnsafeStep{why}); };
  context.raise.check_failed = [this](const CheckFailed& e) { take(e); };
  context.raise.sensor_report = [this] { take(SensorReport{}); };
  fsm.start();
}

Engine::~Engine() = default;

FlowRun* Engine::flow() const { return fsm.get_state<const Operating&>().flow.get(); }

/// A flow that reached an end hands it to the machine above, before any
/// event raised meanwhile (a submachine's exit point does so in Boost.MSM).
void Engine::take_flow_end() {
  if (!flow()) return;
  switch (flow()->take_end()) {
    case FlowEnd::finished:
      fsm.process_event(FlowFinished{});
      break;
    case FlowEnd::cancelled:
      fsm.process_event(FlowCancelled{});
      break;
    case FlowEnd::failed:
      fsm.process_event(FlowFailed{flow()->failure()});
      break;
    case FlowEnd::running:
      break;
  }
}

}  // namespace fatc::machine
