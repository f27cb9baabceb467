// Unload: its words, its admission and its run. The flow's event dispatch is
// generated here and nowhere else (flow_run_of.hpp): a compiler run reads
// only the tables this flow dispatches.

#include "unload_flow.hpp"
#include "changer.hpp"
#include "flow_run_of.hpp"

namespace fatc::machine {

std::string Unload::name(const UnloadRequest& e) {
  return "unload of tool " + std::to_string(e.tool);
}

std::optional<std::string> Unload::why_not(const Context& c, const UnloadRequest& e) {
  if (auto why = why_not_unload(c, e.tool)) return why;
  return c.rehearse([tool = e.tool](Changer& copy) { copy.unload(tool); });
}

std::string Unload::busy(const Context& c) {
  return "the changer is busy unloading tool " + std::to_string(c.request.tool);
}

std::unique_ptr<FlowRun> Unload::run(Context& c, const UnloadRequest& e) {
  return std::make_unique<FlowRunOf<UnloadFlow_>>(c, e);
}

}  // namespace fatc::machine
