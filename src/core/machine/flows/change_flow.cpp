// M6: the words of its request, whether it can start (its own rule; Operating
// rehearses it after) and its run. The flow's event dispatch is generated here
// and nowhere else (flow_run_of.hpp): a compiler run reads only its tables.

#include "change_flow.hpp"

#include "../base/admission.hpp"
#include "flow_run_of.hpp"

namespace fatc::machine {

namespace {

std::optional<std::string> why_not_change(const Context& ctx, int tool) {
  if (tool < 0) return "T" + std::to_string(tool) + " is not a tool number";
  if (auto busy = why_not_busy(ctx)) return busy;
  if (tool == ctx.tools.spindle) return std::nullopt;
  if (auto datum = why_datum_refuses(ctx, tool)) return datum;
  if (auto air = why_no_air(ctx)) return air;
  const auto home = ctx.tools.home_of(tool);
  if (tool != 0 && !home && !ctx.config.manual_tools) {
    return tool_name(tool) + " is in no pocket of the rack (and manual_tools is off)";
  }
  if (tool != 0 && home && !ctx.tools.holds(*home)) {
    return tool_name(tool) + " belongs in pocket " + std::to_string(*home) +
           " but is not in it; load it first";
  }
  return why_spindle_cannot_be_emptied(ctx, ctx.config.manual_tools);
}

}  // namespace

std::string Change::name(const ToolChange& e) { return "M6 T" + std::to_string(e.tool); }

std::optional<std::string> Change::why_not(const Context& c, const ToolChange& e) {
  return why_not_change(c, e.tool);
}

std::string Change::busy(const Context& c) {
  return "the changer is busy changing to tool " + std::to_string(c.request.tool);
}

std::unique_ptr<FlowRun> Change::run(Context& c, const ToolChange& e) {
  return std::make_unique<FlowRunOf<ChangeFlow_>>(c, e);
}

}  // namespace fatc::machine
