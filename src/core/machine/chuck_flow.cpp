// ChuckAtom: its words, its admission and its run. The flow's event dispatch is
// generated here and nowhere else (flow_run_of.hpp): a compiler run reads
// only the tables this flow dispatches.

#include "chuck_flow.hpp"
#include "flow_run_of.hpp"

namespace fatc::machine {

int ChuckAtom::tool(const Context& c, const ChuckRequest&) { return c.tools.spindle; }

std::string ChuckAtom::name(const ChuckRequest& e) {
  return e.action == ChuckRequest::Action::release ? "chuck release" : "chuck clamp";
}

std::optional<std::string> ChuckAtom::why_not(const Context& c, const ChuckRequest& e) {
  return why_not_chuck(c, e);
}

std::string ChuckAtom::busy(const Context&) { return "the changer is busy with the chuck"; }

std::unique_ptr<FlowRun> ChuckAtom::run(Context& c, const ChuckRequest& e) {
  return std::make_unique<FlowRunOf<ChuckFlow_>>(c, e);
}

}  // namespace fatc::machine
