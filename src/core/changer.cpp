#include "changer.hpp"

#include "machine/dot.hpp"
#include "machine/flows.hpp"

namespace fatc {
namespace machine {

class Engine {
 public:
  Engine(const Config& config, Ports& ports, ToolState tools)
      : context(config, ports, std::move(tools)), fsm(&context) {
    fsm.start();
  }
  Context context;
  Machine fsm;
};

}  // namespace machine

Changer::Changer(const Config& config, Ports& ports, ToolState tools)
    : engine_(std::make_unique<machine::Engine>(config, ports, std::move(tools))) {}

Changer::~Changer() = default;

void Changer::ready() {
  engine_->context.machine_ready = true;
  engine_->fsm.process_event(Ready{});
}

void Changer::not_ready() {
  engine_->context.machine_ready = false;
  engine_->fsm.process_event(NotReady{});
}

namespace {

/// Requests are only for an idle changer; anything else gets one message.
bool refuse_unless_idle(Context& ctx, const std::string& request, bool executor_waits) {
  if (ctx.status.phase == Phase::idle) return false;
  std::string why;
  switch (ctx.status.phase) {
    case Phase::not_ready: why = "the machine is not on and homed, or is in estop"; break;
    case Phase::fault: why = "the changer is in fault (" + ctx.fault_reason + "); clear it first"; break;
    default: why = "the changer is busy: " + ctx.status.activity; break;
  }
  // Straight to the ports: a busy flow's activity must not change.
  if (executor_waits) ctx.ports.publish(failure_step(request + " refused: " + why));
  ctx.tell(MessageKind::error, request + " refused: " + why);
  return true;
}

}  // namespace

void Changer::tool_change(int tool) {
  if (refuse_unless_idle(engine_->context, "M6 T" + std::to_string(tool), true)) return;
  engine_->fsm.process_event(ToolChange{tool});
}

void Changer::load(int tool) {
  if (refuse_unless_idle(engine_->context, "load of tool " + std::to_string(tool), false)) return;
  engine_->fsm.process_event(LoadRequest{tool});
}

void Changer::unload(int tool) {
  if (refuse_unless_idle(engine_->context, "unload of tool " + std::to_string(tool), false)) return;
  engine_->fsm.process_event(UnloadRequest{tool});
}

void Changer::in_position() { engine_->fsm.process_event(InPosition{}); }

void Changer::probe_result(bool touched, double machine_z, bool tripped_before) {
  engine_->fsm.process_event(ProbeResult{touched, machine_z, tripped_before});
}

void Changer::timer_elapsed() {
  // A timer that ran out after its state was left is stale, not an event.
  const Awaiting awaiting = engine_->context.status.awaiting;
  if (awaiting != Awaiting::timer && awaiting != Awaiting::spindle) return;
  engine_->fsm.process_event(TimerElapsed{});
}

void Changer::spindle_stopped(bool stopped) {
  engine_->context.spindle_stopped = stopped;
  if (stopped && engine_->context.status.awaiting == Awaiting::spindle) {
    engine_->fsm.process_event(SpindleStopped{});
  }
}

void Changer::operator_continue() {
  if (engine_->context.status.awaiting != Awaiting::operator_choice) {
    engine_->context.tell(MessageKind::info, "Continue: nothing is waiting for the operator");
    return;
  }
  engine_->fsm.process_event(OperatorContinue{});
}

void Changer::operator_cancel() {
  const Status& status = engine_->context.status;
  if (status.awaiting != Awaiting::operator_choice && !probe_cancellable(status)) {
    engine_->context.tell(MessageKind::info, "Cancel: nothing is waiting for the operator");
    return;
  }
  engine_->fsm.process_event(OperatorCancel{});
}

void Changer::abort(const std::string& reason) { engine_->fsm.process_event(Abort{reason}); }

void Changer::clear_fault(int spindle_tool) {
  if (engine_->context.status.phase != Phase::fault) {
    engine_->context.tell(MessageKind::info, "clear fault: there is no fault");
    return;
  }
  engine_->fsm.process_event(ClearFault{spindle_tool});
}

const Status& Changer::status() const { return engine_->context.status; }
const ToolState& Changer::tools() const { return engine_->context.tools; }
bool Changer::is_machine_ready() const { return engine_->context.machine_ready; }

std::string Changer::dot() { return machine::dot_of<machine::Machine_>("fixed_atc_probe"); }

}  // namespace fatc
