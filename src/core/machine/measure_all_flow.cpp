// MeasureAll: its words, its admission and its run. The flow's event dispatch is
// generated here and nowhere else (flow_run_of.hpp): a compiler run reads
// only the tables this flow dispatches.

#include "measure_all_flow.hpp"
#include "changer.hpp"
#include "flow_run_of.hpp"

namespace fatc::machine {

int MeasureAll::tool(const Context& c, const MeasureRequest&) { return c.request.tool; }

std::string MeasureAll::name(const MeasureRequest& e) {
  return "measure all (" + std::to_string(e.tools.size()) + " tools)";
}

std::optional<std::string> MeasureAll::why_not(const Context& c, const MeasureRequest& e) {
  if (auto why = why_not_measure(c, e.tools)) return why;
  return c.rehearse([e](Changer& copy) { copy.measure_all(e.tools); });
}

std::string MeasureAll::busy(const Context& c) {
  return "the changer is busy measuring tool " + std::to_string(c.request.tool);
}

std::unique_ptr<FlowRun> MeasureAll::run(Context& c, const MeasureRequest& e) {
  return std::make_unique<FlowRunOf<MeasureAllFlow_>>(c, e);
}

}  // namespace fatc::machine
