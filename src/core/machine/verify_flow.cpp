// Verify: its words, its admission and its run. The flow's event dispatch is
// generated here and nowhere else (flow_run_of.hpp): a compiler run reads
// only the tables this flow dispatches.

#include "verify_flow.hpp"
#include "changer.hpp"
#include "flow_run_of.hpp"

namespace fatc::machine {

int Verify::tool(const Context& c, const VerifyRequest&) { return c.tools.spindle; }

std::string Verify::name(const VerifyRequest& e) {
  return "verify of pocket " + std::to_string(e.pocket);
}

std::optional<std::string> Verify::why_not(const Context& c, const VerifyRequest& e) {
  if (auto why = why_not_verify(c, e.pocket)) return why;
  return c.rehearse([pocket = e.pocket](Changer& copy) { copy.verify(pocket); });
}

std::string Verify::busy(const Context& c) {
  return "the changer is busy verifying pocket " + std::to_string(c.sequence_pocket());
}

std::unique_ptr<FlowRun> Verify::run(Context& c, const VerifyRequest& e) {
  return std::make_unique<FlowRunOf<VerifyFlow_>>(c, e);
}

}  // namespace fatc::machine
