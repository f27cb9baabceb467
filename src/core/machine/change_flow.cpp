// Change: its words, its admission and its run. The flow's event dispatch is
// generated here and nowhere else (flow_run_of.hpp): a compiler run reads
// only the tables this flow dispatches.

#include "change_flow.hpp"
#include "changer.hpp"
#include "flow_run_of.hpp"

namespace fatc::machine {

std::string Change::name(const ToolChange& e) { return "M6 T" + std::to_string(e.tool); }

std::optional<std::string> Change::why_not(const Context& c, const ToolChange& e) {
  if (auto why = why_not_change(c, e.tool)) return why;
  return c.rehearse([tool = e.tool](Changer& copy) { copy.tool_change(tool); });
}

std::string Change::busy(const Context& c) {
  return "the changer is busy changing to tool " + std::to_string(c.request.tool);
}

std::unique_ptr<FlowRun> Change::run(Context& c, const ToolChange& e) {
  return std::make_unique<FlowRunOf<ChangeFlow_>>(c, e);
}

}  // namespace fatc::machine
