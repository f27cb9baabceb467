// Measure all: the words of its request, whether it can start (its own rule;
// Operating rehearses it after) and its run. The flow's event dispatch is
// generated here and nowhere else (flow_run_of.hpp): a compiler run reads only
// its tables.

#include "measure_all_flow.hpp"

#include <algorithm>
#include <cmath>

#include "../base/admission.hpp"
#include "flow_run_of.hpp"

namespace fatc {

std::vector<int> measurable_tools(const Context& ctx, const std::vector<int>& asked,
                                  std::string& skipped, std::string& never) {
  std::vector<int> tools;
  for (const int tool : asked) {
    if (std::find(tools.begin(), tools.end(), tool) != tools.end()) continue;
    const bool in_spindle = tool != 0 && tool == ctx.tools.spindle && ctx.return_pocket(tool);
    if (ctx.measuring(tool).never) {
      never += (never.empty() ? "" : ", ") + ("T" + std::to_string(tool));
    } else if (ctx.tools.pocket_holding(tool) || in_spindle) {
      tools.push_back(tool);
    } else if (tool != 0) {
      skipped += (skipped.empty() ? "" : ", ") + ("T" + std::to_string(tool));
    }
  }
  return tools;
}

}  // namespace fatc

namespace fatc::machine {

namespace {

std::optional<std::string> why_not_measure(const Context& ctx, const std::vector<int>& asked) {
  if (ctx.machine.task_busy) return ctx.machine.task_busy;
  if (auto busy = why_not_busy(ctx)) return busy;
  if (auto turning = why_spindle_turning(ctx)) return turning;
  if (auto air = why_no_air(ctx)) return air;
  std::string skipped;
  std::string never;
  if (measurable_tools(ctx, asked, skipped, never).empty()) {
    std::string why;
    if (!skipped.empty()) why += "not in the rack: " + skipped;
    if (!never.empty()) why += (why.empty() ? "" : "; ") + ("measured never (\"never\"): " + never);
    return (never.empty() ? std::string("no tool to measure in the rack") : "no tool to measure") +
           (why.empty() ? std::string() : " (" + why + ")");
  }
  return why_spindle_cannot_be_emptied(ctx, false);
}

}  // namespace

int MeasureAll::tool(const Context& c, const MeasureRequest&) { return c.request.tool; }

std::string MeasureAll::name(const MeasureRequest& e) {
  return "measure all (" + std::to_string(e.tools.size()) + " tools)";
}

std::optional<std::string> MeasureAll::why_not(const Context& c, const MeasureRequest& e) {
  return why_not_measure(c, e.tools);
}

std::string MeasureAll::busy(const Context& c) {
  return "the changer is busy measuring tool " + std::to_string(c.request.tool);
}

std::unique_ptr<FlowRun> MeasureAll::run(Context& c, const MeasureRequest& e) {
  return std::make_unique<FlowRunOf<MeasureAllFlow_>>(c, e);
}

}  // namespace fatc::machine
