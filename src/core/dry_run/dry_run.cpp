#include "dry_run.hpp"

#include "../machine/base/context.hpp"
#include "simulator.hpp"

namespace fatc {

std::optional<std::string> DryRun::why_not(const Context& ctx,
                                           const std::function<void(Changer&)>& request) const {
  const Point at = ctx.machine.position.value_or(ctx.motion.position);
  const unsigned known = ctx.machine.position ? axis_xyz : ctx.motion.known_axes;
  const Simulator planned = plan_from(ctx.config, ctx.tools, at, known, request);
  const std::vector<Step> steps = planned.steps();
  StepsFrom from{at, known, ctx.motion.keepout_lengths, ctx.tools.lengths};
  const auto violations = check_steps(ctx.config, steps, ctx.machine.limits, from);
  if (violations.empty()) return std::nullopt;
  const Violation& first = violations.front();
  const Step& move = steps[first.step];
  std::string why = "its step " + std::to_string(first.step + 1) + " (" +
                    step_kind_name(move.kind) + " to " + move.label + "): " + first.what;
  if (const std::string counted = keepout_length_words(ctx.config, ctx.motion.keepout_lengths,
                                                       move.held, ctx.tools.lengths);
      !counted.empty()) {
    why += " (" + counted + ")";
  }
  return why + "; nothing moved";
}

}  // namespace fatc
