// Load and probe: the words of its request, whether it can start (its own rule;
// Operating rehearses it after) and its run. The flow's event dispatch is
// generated here and nowhere else (flow_run_of.hpp): a compiler run reads only
// its tables.

#include "load_flow.hpp"

#include <algorithm>
#include <cmath>

#include "../base/admission.hpp"
#include "flow_run_of.hpp"

namespace fatc {

LoadPocket choose_load_pocket(const Context& ctx, int tool, int asked) {
  // The pocket the spindle's tool goes back to first is not free for this one.
  const int held = ctx.tools.spindle;
  const int taken = held != 0 && held != tool ? ctx.return_pocket(held).value_or(0) : 0;
  auto free_for_tool = [&](int pocket) {
    const int owner = ctx.tools.tool_of(pocket);
    return pocket != taken && (owner == 0 || owner == tool);
  };
  std::vector<int> free;
  for (const auto& [number, pocket] : ctx.config.pockets) {
    if (free_for_tool(number)) free.push_back(number);
  }
  const std::string free_words =
      free.empty() ? "every pocket holds a tool; unload one first" : "free: " + pocket_list(free);
  if (asked != 0) {
    if (!ctx.config.has_pocket(asked)) {
      return {0, "pocket " + std::to_string(asked) + " is not in the config (" + free_words + ")"};
    }
    if (!free_for_tool(asked)) {
      const int owner = asked == taken ? held : ctx.tools.tool_of(asked);
      return {0,
              "pocket " + std::to_string(asked) + " is " +
                  (asked == taken ? "where tool " + std::to_string(owner) + " in the spindle goes"
                                  : "tool " + std::to_string(owner) + "'s") +
                  " (" + free_words + ")"};
    }
    return {asked, ""};
  }
  if (const auto home = ctx.tools.home_of(tool); home && free_for_tool(*home)) return {*home, ""};
  if (const auto first = ctx.config.first_pocket_of(tool); first && free_for_tool(*first)) {
    return {*first, ""};
  }
  if (free.empty()) return {0, "no pocket for " + tool_name(tool) + ": " + free_words};
  const Point& loading = ctx.config.loading;
  const auto nearest = std::min_element(free.begin(), free.end(), [&](int a, int b) {
    const Point& pa = ctx.config.pockets.at(a).at;
    const Point& pb = ctx.config.pockets.at(b).at;
    return std::hypot(pa.x - loading.x, pa.y - loading.y) <
           std::hypot(pb.x - loading.x, pb.y - loading.y);
  });
  return {*nearest, ""};
}

}  // namespace fatc

namespace fatc::machine {

namespace {

std::optional<std::string> why_not_load(const Context& ctx, int tool, int pocket) {
  if (ctx.machine.task_busy) return ctx.machine.task_busy;
  if (tool <= 0) return "load needs a tool number above 0, got " + std::to_string(tool);
  if (pocket < 0)
    return "pocket-number must be 0 (chosen) or a pocket, got " + std::to_string(pocket);
  if (auto busy = why_not_busy(ctx)) return busy;
  if (ctx.config.screws_nuts() && ctx.config.is_probe(tool)) {
    return tool_name(tool) +
           " is a touch probe: a collet-nut magazine cannot hold it (the spindle would turn it to "
           "screw it); M6 hands it in at loading";
  }
  if (auto turning = why_spindle_turning(ctx)) return turning;
  if (auto air = why_no_air(ctx)) return air;
  if (const auto in_rack = ctx.tools.pocket_holding(tool)) {
    return tool_name(tool) + " is already in pocket " + std::to_string(*in_rack) +
           "; unload it first";
  }
  const LoadPocket chosen = choose_load_pocket(ctx, tool, pocket);
  if (chosen.pocket == 0) return chosen.why;
  if (ctx.tools.spindle == tool) return std::nullopt;
  return why_spindle_cannot_be_emptied(ctx, false);
}

}  // namespace

std::string Load::name(const LoadRequest& e) {
  return "load of tool " + std::to_string(e.tool) +
         (e.pocket != 0 ? " into pocket " + std::to_string(e.pocket) : std::string());
}

std::optional<std::string> Load::why_not(const Context& c, const LoadRequest& e) {
  return why_not_load(c, e.tool, e.pocket);
}

std::string Load::busy(const Context& c) {
  return "the changer is busy loading tool " + std::to_string(c.request.tool);
}

std::unique_ptr<FlowRun> Load::run(Context& c, const LoadRequest& e) {
  return std::make_unique<FlowRunOf<LoadFlow_>>(c, e);
}

}  // namespace fatc::machine
