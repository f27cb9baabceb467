// An air run: the words of its request, whether it can start (its own rule;
// Operating rehearses it after, every move with the tool the spindle really
// holds) and its run. The flow's event dispatch is generated here and nowhere
// else (flow_run_of.hpp).

#include "air_run_flow.hpp"

#include "../base/admission.hpp"
#include "flow_run_of.hpp"

namespace fatc::machine {

int AirRun::tool(const Context& c, const AirRunRequest&) { return c.tools.spindle; }

std::string AirRun::name(const AirRunRequest& e) { return e.name; }

std::optional<std::string> AirRun::why_not(const Context& c, const AirRunRequest& e) {
  if (c.machine.task_busy) return c.machine.task_busy;
  if (auto busy = why_not_busy(c)) return busy;
  if (auto turning = why_spindle_turning(c)) return turning;
  if (e.route.empty()) return std::string("the sequence moves nowhere");
  return std::nullopt;
}

std::string AirRun::busy(const Context& c) {
  return "the changer is busy with " +
         (c.tools.in_progress ? c.tools.in_progress->sequence : std::string("an air run"));
}

std::unique_ptr<FlowRun> AirRun::run(Context& c, const AirRunRequest& e) {
  return std::make_unique<FlowRunOf<AirRunFlow_>>(c, e);
}

}  // namespace fatc::machine
