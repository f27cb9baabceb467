// Load: its words, its admission and its run. The flow's event dispatch is
// generated here and nowhere else (flow_run_of.hpp): a compiler run reads
// only the tables this flow dispatches.

#include "load_flow.hpp"
#include "changer.hpp"
#include "flow_run_of.hpp"

namespace fatc::machine {

std::string Load::name(const LoadRequest& e) {
  return "load of tool " + std::to_string(e.tool) +
         (e.pocket != 0 ? " into pocket " + std::to_string(e.pocket) : std::string());
}

std::optional<std::string> Load::why_not(const Context& c, const LoadRequest& e) {
  if (auto why = why_not_load(c, e.tool, e.pocket)) return why;
  return c.rehearse([e](Changer& copy) { copy.load(e.tool, e.pocket); });
}

std::string Load::busy(const Context& c) {
  return "the changer is busy loading tool " + std::to_string(c.request.tool);
}

std::unique_ptr<FlowRun> Load::run(Context& c, const LoadRequest& e) {
  return std::make_unique<FlowRunOf<LoadFlow_>>(c, e);
}

}  // namespace fatc::machine
