// Unload: the words of its request, whether it can start (its own rule;
// Operating rehearses it after) and its run. The flow's event dispatch is
// generated here and nowhere else (flow_run_of.hpp): a compiler run reads only
// its tables.

#include "unload_flow.hpp"

#include "../base/admission.hpp"
#include "flow_run_of.hpp"

namespace fatc::machine {

namespace {

std::optional<std::string> why_not_unload(const Context& ctx, int tool) {
  if (ctx.machine.task_busy) return ctx.machine.task_busy;
  if (tool <= 0) return "unload needs a tool number above 0, got " + std::to_string(tool);
  if (auto busy = why_not_busy(ctx)) return busy;
  if (auto turning = why_spindle_turning(ctx)) return turning;
  if (auto air = why_no_air(ctx)) return air;
  if (ctx.tools.spindle == tool) return std::nullopt;
  if (!ctx.tools.pocket_holding(tool)) return tool_name(tool) + " is not in the rack";
  return why_spindle_cannot_be_emptied(ctx, false);
}

}  // namespace

std::string Unload::name(const UnloadRequest& e) {
  return "unload of tool " + std::to_string(e.tool);
}

std::optional<std::string> Unload::why_not(const Context& c, const UnloadRequest& e) {
  return why_not_unload(c, e.tool);
}

std::string Unload::busy(const Context& c) {
  return "the changer is busy unloading tool " + std::to_string(c.request.tool);
}

std::unique_ptr<FlowRun> Unload::run(Context& c, const UnloadRequest& e) {
  return std::make_unique<FlowRunOf<UnloadFlow_>>(c, e);
}

}  // namespace fatc::machine
