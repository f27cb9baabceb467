// Verify a pocket: the words of its request, whether it can start (its own
// rule; Operating rehearses it after) and its run. The flow's event dispatch is
// generated here and nowhere else (flow_run_of.hpp): a compiler run reads only
// its tables.

#include "verify_flow.hpp"

#include "../base/admission.hpp"
#include "flow_run_of.hpp"

namespace fatc::machine {

namespace {

std::optional<std::string> why_not_verify(const Context& ctx, int pocket) {
  if (ctx.machine.task_busy) return ctx.machine.task_busy;
  std::vector<int> numbers;
  for (const auto& [number, entry] : ctx.config.pockets) numbers.push_back(number);
  if (!ctx.config.has_pocket(pocket)) {
    return "pocket-number " + std::to_string(pocket) + " is not a pocket of the config (" +
           pocket_list(numbers) + ")";
  }
  if (auto busy = why_not_busy(ctx)) return busy;
  if (auto turning = why_spindle_turning(ctx)) return turning;
  // The spindle goes where the tool would sit: only an empty pocket can be
  // driven into (a wired pocket sensor that disagrees stops all work before this).
  if (ctx.tools.holds(pocket)) {
    const std::string tool = std::to_string(ctx.tools.tool_of(pocket));
    return "pocket " + std::to_string(pocket) + " holds tool " + tool + "; fetch it first (M6 T" +
           tool + ") to verify with it in the spindle";
  }
  return std::nullopt;
}

}  // namespace

int Verify::tool(const Context& c, const VerifyRequest&) { return c.tools.spindle; }

std::string Verify::name(const VerifyRequest& e) {
  return "verify of pocket " + std::to_string(e.pocket);
}

std::optional<std::string> Verify::why_not(const Context& c, const VerifyRequest& e) {
  return why_not_verify(c, e.pocket);
}

std::string Verify::busy(const Context& c) {
  return "the changer is busy verifying pocket " + std::to_string(c.sequence_pocket());
}

std::unique_ptr<FlowRun> Verify::run(Context& c, const VerifyRequest& e) {
  return std::make_unique<FlowRunOf<VerifyFlow_>>(c, e);
}

}  // namespace fatc::machine
