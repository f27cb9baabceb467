// A chuck atom: the words of its request, whether it can start (its own rule;
// Operating does not rehearse it) and its run. The flow's event dispatch is
// generated here and nowhere else (flow_run_of.hpp): a compiler run reads only
// its tables.

#include "chuck_flow.hpp"

#include <algorithm>
#include <cmath>

#include "../base/admission.hpp"
#include "flow_run_of.hpp"

namespace fatc::machine {

namespace {

std::optional<std::string> why_not_chuck(const Context& ctx, const ChuckRequest& request) {
  if (auto not_ready = why_not_ready(ctx)) return not_ready;
  if (request.action == ChuckRequest::Action::clamp) return std::nullopt;
  if (ctx.config.screws_nuts()) {
    return std::string(
        "a collet-nut spindle (chuck.kind \"collet_nut\") has no drawbar to release; its nuts "
        "are screwed by hand at loading");
  }
  if (!ctx.machine.spindle_stopped) return std::string("the spindle is on; stop it first (M5)");
  if (auto air = why_no_air(ctx)) return air;
  const int held = ctx.tools.spindle;
  if (held == 0) return std::nullopt;
  const Point& loading = ctx.config.loading;
  const std::string why = tool_name(held) +
                          " is in the spindle and would drop; release it only at loading (" +
                          position_words(ctx.config, loading) + ") or with the spindle empty";
  if (!request.at) return why + " (LinuxCNC does not say where the machine is)";
  const Point& at = *request.at;
  const double tolerance = loading_tolerance(ctx.config);
  if (std::abs(at.x - loading.x) > tolerance || std::abs(at.y - loading.y) > tolerance ||
      std::abs(at.z - loading.z) > tolerance) {
    return why + "; the machine is at " + position_words(ctx.config, at);
  }
  return std::nullopt;
}

}  // namespace

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
