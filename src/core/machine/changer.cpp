#include "changer.hpp"

#include "base/admission.hpp"
#include "engine.hpp"

namespace fatc {

Changer::Changer(const Config& config, Ports& ports, ToolState tools)
    : engine_(std::make_unique<machine::Engine>(config, ports, std::move(tools))) {}

Changer::~Changer() = default;

void Changer::ready() {
  engine_->context.machine.ready = true;
  engine_->take(Ready{});
}

void Changer::not_ready() {
  engine_->context.machine.ready = false;
  engine_->take(NotReady{});
}

void Changer::soft_limits(std::optional<SoftLimits> limits) {
  engine_->context.machine.limits = std::move(limits);
}

void Changer::plan_only() { engine_->context.motion.check_moves = false; }

void Changer::start_at(const Point& at, unsigned known) {
  engine_->context.motion.position = at;
  engine_->context.motion.known_axes = known;
}

void Changer::keepout_lengths(ToolLengths lengths) {
  engine_->context.motion.keepout_lengths = std::move(lengths);
}

const ToolLengths& Changer::keepout_lengths() const {
  return engine_->context.motion.keepout_lengths;
}

void Changer::rehearse_with(const Rehearsal* rehearsal) {
  engine_->context.motion.rehearsal = rehearsal;
}

void Changer::machine_at(std::optional<Point> at) { engine_->context.machine.position = at; }

void Changer::step_by_step(bool on) { engine_->context.steps.switch_to(on); }

void Changer::task_availability(std::optional<std::string> why_busy) {
  engine_->context.machine.task_busy = std::move(why_busy);
}

void Changer::spindle_stopped(bool stopped) {
  engine_->context.machine.spindle_stopped = stopped;
  engine_->take(SensorReport{});
}

void Changer::sensors(const SensorReadings& readings) {
  engine_->context.sensors.read = readings;
  engine_->take(SensorReport{});
}

void Changer::tool_change(int tool) { engine_->take(ToolChange{tool}); }
void Changer::load(int tool, int pocket) { engine_->take(LoadRequest{tool, pocket}); }
void Changer::unload(int tool) { engine_->take(UnloadRequest{tool}); }
void Changer::measure_all(std::vector<int> tools) {
  engine_->take(MeasureRequest{std::move(tools)});
}
void Changer::verify(int pocket) { engine_->take(VerifyRequest{pocket}); }
void Changer::chuck(ChuckRequest::Action action, std::optional<Point> at) {
  engine_->take(ChuckRequest{action, at});
}
void Changer::request(const machine::FlowRequest& request) {
  std::visit([this](const auto& e) { engine_->take(e); }, request);
}

namespace machine {
std::optional<std::string> rehearse(const Context& c, const FlowRequest& request) {
  return c.rehearse([request](Changer& copy) { copy.request(request); });
}
}  // namespace machine
void Changer::in_position() {
  // Within a phase the next waypoint follows (step by step, the next move of
  // a run first); the tables see a phase's end.
  if (engine_->context.hold_next_move() || engine_->context.next_waypoint()) return;
  engine_->take(InPosition{});
}
void Changer::command_done() { engine_->take(CommandDone{}); }

void Changer::probe_result(bool touched, double machine_z, bool tripped_before) {
  engine_->take(ProbeResult{touched, machine_z, tripped_before});
}

void Changer::timer_elapsed() { engine_->take(TimerElapsed{}); }
void Changer::operator_continue() {
  if (engine_->context.continue_step()) return;
  engine_->take(OperatorContinue{});
}
void Changer::operator_cancel() {
  const Context& c = engine_->context;
  if (!c.steps.holding()) {
    engine_->take(OperatorCancel{});
    return;
  }
  // Nothing moves at a held step: the sequence ends there as an abort ends it.
  engine_->take(Abort{"cancelled by the operator before step " +
                      std::to_string(c.steps.question().stop) + " of " +
                      c.steps.question().sequence + " (step by step)"});
}
void Changer::abort(const std::string& reason) { engine_->take(Abort{reason}); }
void Changer::clear_fault(int spindle_tool, std::optional<bool> pocket_holds_tool) {
  engine_->take(ClearFault{spindle_tool, pocket_holds_tool});
}

std::optional<std::string> Changer::clear_datum_drift() {
  Context& c = engine_->context;
  if (status().busy()) return std::string("the changer is busy");
  if (!datum_refusal()) return std::string("the rack datum refuses nothing: nothing to clear");
  c.tools.datum = {};
  c.datum_checked = true;
  c.ports.save(c.tools);
  c.tell(MessageKind::info,
         "rack datum cleared by the operator: M6 is allowed again; the pockets keep their "
         "positions and the changes are counted from 0");
  return std::nullopt;
}

std::optional<std::string> Changer::datum_refusal() const {
  return why_datum_refuses(engine_->context, 0);
}

unsigned Changer::configs_taken() const { return engine_->context.configs_taken(); }

bool Changer::reconfigure(Config config, std::string request) {
  const unsigned taken = engine_->context.configs_taken();
  engine_->take(ConfigChanged{std::move(config), std::move(request)});
  return engine_->context.configs_taken() != taken;
}

namespace {

template <class Flag>
bool active(const machine::Engine& engine) {
  return engine.active<Flag>();
}

Phase phase_of(const machine::Engine& engine) {
  namespace flag = machine::flag;
  if (active<flag::Faulted>(engine)) return Phase::fault;
  std::optional<Phase> running;
  machine::Flows::any([&](auto flow) {
    using Flow = decltype(flow);
    if (!active<Flow>(engine)) return false;
    running = Flow::phase;
    return true;
  });
  if (running) return *running;
  if (active<flag::Idle>(engine)) return Phase::idle;
  return Phase::not_ready;
}

Awaiting awaiting_of(const machine::Engine& engine) {
  namespace flag = machine::flag;
  if (active<flag::AwaitsOperator>(engine) || engine.context.steps.holding()) {
    return Awaiting::operator_choice;
  }
  if (active<flag::AwaitsProbe>(engine)) return Awaiting::probe;
  if (active<flag::AwaitsMotion>(engine)) return Awaiting::motion;
  if (active<flag::AwaitsTimer>(engine)) return Awaiting::timer;
  if (active<flag::AwaitsSpindle>(engine)) return Awaiting::spindle;
  if (active<flag::AwaitsSensor>(engine)) return Awaiting::sensor;
  return Awaiting::nothing;
}

std::string activity_of(const Status& status, const Context& c) {
  switch (status.phase) {
    case Phase::not_ready:
      return "machine off, not homed or in estop";
    case Phase::idle:
      if (status.awaiting == Awaiting::sensor) return c.activity.dwell;
      return why_chuck_held_open(c).value_or("idle");
    case Phase::fault:
      return "fault: " + c.activity.fault_reason;
    default:
      break;
  }
  switch (status.awaiting) {
    case Awaiting::motion:
    case Awaiting::probe:
      if (c.motion.step.kind == StepKind::set_spindle_tool) {
        return "telling LinuxCNC the spindle holds tool " + std::to_string(c.motion.step.tool);
      }
      if (c.motion.step.kind == StepKind::set_tool_length) {
        return "writing the length of tool " + std::to_string(c.motion.step.tool) +
               " to the tool table";
      }
      return std::string(step_kind_name(c.motion.step.kind)) + " to " + c.motion.step.label;
    case Awaiting::timer:
    case Awaiting::spindle:
    case Awaiting::sensor:
      return c.activity.dwell;
    case Awaiting::operator_choice:
      return words(c.activity.prompt);
    case Awaiting::nothing:
      break;
  }
  return "";
}

}  // namespace

const char* phase_word(Phase phase) {
  switch (phase) {
    case Phase::not_ready:
      return "not ready";
    case Phase::idle:
      return "idle";
    case Phase::fault:
      return "fault";
    default:
      break;
  }
  const char* word = "?";
  machine::Flows::any([&](auto flow) {
    using Flow = decltype(flow);
    if (Flow::phase != phase) return false;
    word = Flow::word;
    return true;
  });
  return word;
}

Status Changer::status() const {
  const machine::Engine& engine = *engine_;
  const Context& c = engine_->context;
  Status status;
  status.phase = phase_of(engine);
  status.awaiting = awaiting_of(engine);
  // Inside M6 an operator's answer holds the program, and only Stop ends a probe.
  const bool in_program = c.request.in_program;
  // A step held for Continue holds the executor too, inside a program or over MDI.
  status.holds_program = active<machine::flag::HoldsProgram>(engine) ||
                         (active<machine::flag::AwaitsOperator>(engine) && in_program) ||
                         c.steps.holding();
  status.probe_cancellable =
      active<machine::flag::AwaitsProbe>(engine) && !in_program && !c.steps.holding();
  status.over_mdi = status.busy() && !in_program;
  status.accepting = status.phase == Phase::idle && status.awaiting == Awaiting::nothing &&
                     !c.machine.task_busy && !c.outputs.chuck_open;
  status.chuck_held =
      c.outputs.chuck_open && (status.phase == Phase::idle || status.phase == Phase::chuck);
  status.turns_spindle = c.outputs.spindle_rpm != 0.0;
  status.last_length = c.activity.last_length;
  status.step_number = status.busy() ? c.motion.sequence_step : 0;
  status.pocket = status.busy() ? c.sequence_pocket() : 0;
  if (status.phase == Phase::measuring) {
    const machine::BatchCount batch = engine_->flow()->batch();
    status.batch_done = batch.done;
    status.batch_total = batch.total;
  }
  status.spindle_probe = spindle_probe(c.config, c.tools);
  const int about = status.busy() && c.request.tool != 0 ? c.request.tool : c.tools.spindle;
  if (about != 0) status.rule = "T" + std::to_string(about) + " " + rule_words(c.config, about);
  status.activity = activity_of(status, c);
  return status;
}

const ToolState& Changer::tools() const { return engine_->context.tools; }
const Config& Changer::config() const { return engine_->context.config; }

std::optional<std::string> Changer::why_not_teach(bool linuxcnc_status,
                                                  const std::optional<Point>& at) const {
  // The same words as a ConfigChanged refused, before anything is read or written.
  const Status now = status();
  if (auto why = why_not_reconfigure(engine_->context, now.phase == Phase::idle,
                                     now.awaiting == Awaiting::sensor)) {
    return why;
  }
  if (!now.accepting) return std::string("only while the changer is idle");
  if (!linuxcnc_status) return std::string("no LinuxCNC status to read the machine position from");
  if (!at) return std::string("LinuxCNC's status says nothing of the machine position now");
  return std::nullopt;
}
const std::optional<InProgress>& Changer::cut_off() const {
  return engine_->context.tools.in_progress;
}

}  // namespace fatc
