#include "component.hpp"

#include <iostream>

#include "core/config/quote.hpp"
#include "hal_pins_detail.hpp"
#include "hal_pins_view.hpp"
#include "io/files.hpp"
#include "nml_link.hpp"

namespace fatc::linuxcnc {

Component::Component(HalPins* pins, const Config& config, std::string config_path,
                     std::string state_path, NmlLink* nml, std::optional<std::string> tool_table)
    : pins_(pins),
      nml_(nml),
      teacher_(std::move(config_path), *this),
      state_path_(std::move(state_path)),
      lengths_(tool_table),
      table_pockets_(std::move(tool_table)),
      status_file_(state_path_ + ".status"),
      io_check_(pins) {
  *pins_->units_inch = config.units == Units::inch;
}

bool Component::active() const {
  return link_.active() || deadline_ || changer_->status().busy() || io_check_.timing();
}

void Component::poll(Clock::time_point now, std::optional<bool> interpreter_idle) {
  now_ = now;
  read_machine(interpreter_idle);
  // Before any request: each is rehearsed with the tools' lengths, from
  // where the spindle stands.
  lengths_.poll(*changer_, nml_, *this);
  changer_->machine_at(position());
  read_executor(interpreter_idle);
  read_operator();
  if (deadline_ && now >= *deadline_) {
    deadline_.reset();
    changer_->timer_elapsed();
  }
  measure_all_press_.poll(*changer_, refuse_);
  // Written once the executor's MDI run is over: config.json is taken only then.
  if (accepted_ && changer_->status().phase == Phase::idle && task_free_) {
    teacher_.write_found(*changer_, accepted_->found, accepted_->datum);
    accepted_.reset();
  }
  poll_io_check();
  start_executor_if_needed();
  if (task_free_ && !changer_->status().busy()) {
    // No flow moves a tool meanwhile (off and faulted included: the table
    // shows the rack as the changer has it). Before the spindle tool's M61,
    // which makes task busy for a while.
    table_pockets_.poll(changer_->tools(), *nml_, *this);
  }
  if (task_free_) spindle_tool_.poll(now, *pins_->linuxcnc_tool, *changer_, *nml_, *this);
  keepout_.poll(*pins_, *changer_, machine_ready_.value_or(false), nml_, lengths_.spindle_length(),
                *this);
  const Status status = changer_->status();
  write_link(*pins_, link_.write(status.phase == Phase::idle));
  write_status(*pins_, status, *changer_, link_.attached(), nml_ != nullptr);
  if (io_check_.holds_chuck_open()) *pins_->chuck_held = true;
  status_file_.io_check(io_check_.words());
  status_file_.datum(changer_->datum_refusal().value_or(""));
  status_file_.write(status, changer_->cut_off(), keepout_words(keepout_.state()));
}

void Component::read_machine(std::optional<bool> interpreter_idle) {
  const bool stopped = *pins_->spindle_stopped;
  if (spindle_stopped_ != stopped) {
    spindle_stopped_ = stopped;
    changer_->spindle_stopped(stopped);
  }
  raw_sensors_ = read_sensors(*pins_, changer_->config());
  const SensorReadings sensors = io_check_.seen_by_changer(raw_sensors_);
  if (sensors_ != sensors) {
    sensors_ = sensors;
    changer_->sensors(sensors);
  }
  // After the sensors: becoming ready compares them with the tool state.
  const bool ready = *pins_->machine_on && *pins_->all_homed;
  if (machine_ready_ != ready) {
    machine_ready_ = ready;
    if (ready) {
      changer_->ready();
    } else {
      changer_->not_ready();
      // LinuxCNC ends the program with the machine, the executor with it; a
      // step still offered to it must not wait for kAbortGrace: 2.10 keeps the
      // request output high through an estop and can be on again sooner, and
      // the next M6's executor would take the cut-off change's step.
      link_.drop();
    }
  }
  // The operator flows run the executor over MDI: task must be free for it.
  task_free_ = nml_ && interpreter_idle.value_or(false);
  task_busy_ = !nml_ ? std::optional<std::string>("no connection to LinuxCNC's task (NML)")
               : !interpreter_idle ? std::optional<std::string>(kStatusLost)
               : !task_free_ ? std::optional<std::string>("a program or MDI command is running")
                             : std::nullopt;
  changer_->task_availability(task_busy_);
  if (abort_.rose(*pins_->abort)) abort("the abort pin was raised");
  // fatc-spindle-guard holds the spindle while a probe is in it: what asked for it stops.
  if (spindle_refused_.rose(*pins_->spindle_refused)) {
    if (nml_) nml_->abort();
    tell(MessageKind::error, spindle_held_refusal(changer_->status().spindle_probe));
  }
}

void Component::read_executor(std::optional<bool> interpreter_idle) {
  using Kind = LinkEvent::Kind;
  for (const LinkEvent& e : link_.read(read_link(*pins_, interpreter_idle), now_)) {
    if (e.kind == Kind::tool_change) changer_->tool_change(e.tool);
    if (e.kind == Kind::chuck_release) changer_->chuck(ChuckRequest::Action::release, position());
    if (e.kind == Kind::chuck_clamp) changer_->chuck(ChuckRequest::Action::clamp, position());
    if (e.kind == Kind::in_position) changer_->in_position();
    if (e.kind == Kind::command_done) changer_->command_done();
    if (e.kind == Kind::probe_result) changer_->probe_result(e.touched, e.z, e.tripped_before);
    if (e.kind == Kind::executor_lost) abort(e.reason);
    if (e.kind == Kind::refused_call) tell(MessageKind::error, e.reason);
  }
}

void Component::read_operator() {
  // Before the requests: a sequence takes the switch as it stands at its start.
  changer_->step_by_step(*pins_->step_by_step);
  if (load_.rose(*pins_->load)) changer_->load(*pins_->tool_number, *pins_->pocket_number);
  if (unload_.rose(*pins_->unload)) changer_->unload(*pins_->tool_number);
  if (measure_all_.rose(*pins_->measure_all)) {
    measure_all_press_.press(*pins_->measure_which, nml_ ? nml_->loaded_program() : std::string(),
                             *changer_, refuse_);
  }
  if (verify_.rose(*pins_->verify_pocket)) changer_->verify(*pins_->pocket_number);
  using What = AirAsk::What;
  if (air_change_.rose(*pins_->air_run_change)) fly(What::change);
  if (air_load_.rose(*pins_->air_run_load)) fly(What::load);
  if (air_unload_.rose(*pins_->air_run_unload)) fly(What::unload);
  if (air_verify_.rose(*pins_->air_run_verify)) fly(What::verify);
  using Goal = TouchRequest::Goal;
  if (touch_pockets_.rose(*pins_->touch_pockets)) touch(Goal::pockets);
  if (teach_datum_.rose(*pins_->teach_datum)) touch(Goal::teach_datum);
  if (check_datum_.rose(*pins_->check_datum)) touch(Goal::check_datum);
  if (clear_datum_drift_.rose(*pins_->clear_datum_drift)) {
    if (const auto why = changer_->clear_datum_drift()) {
      tell(MessageKind::error, "clear-datum-drift refused: " + *why);
    }
  }
  if (continue_.rose(*pins_->continue_)) changer_->operator_continue();
  if (cancel_.rose(*pins_->cancel)) {
    if (changer_->status().probe_cancellable && nml_) {
      // The probe runs over MDI: stop it before the changer plans the retract,
      // which the next executor run then performs.
      nml_->abort();
      link_.drop();
    }
    changer_->operator_cancel();
  }
  using Kind = TeachTarget::Kind;
  if (teach_pocket_.rose(*pins_->teach_pocket)) teach({Kind::pocket, *pins_->pocket_number});
  if (teach_loading_.rose(*pins_->teach_loading)) teach({Kind::loading, 0});
  if (teach_safe_.rose(*pins_->teach_safe)) teach({Kind::safe, 0});
  if (teach_sensor_.rose(*pins_->teach_sensor)) teach({Kind::sensor, 0});
  if (clear_.rose(*pins_->clear_fault)) {
    const int tool = *pins_->confirm_tool >= 0 ? *pins_->confirm_tool : *pins_->linuxcnc_tool;
    const int pocket = *pins_->confirm_pocket;
    changer_->clear_fault(tool, pocket < 0 ? std::nullopt : std::optional<bool>(pocket == 1));
    spindle_tool_.want();
  }
}

void Component::teach(const TeachTarget& target) {
  teacher_.teach(*changer_, target, nml_ != nullptr, position());
}

void Component::touch(TouchRequest::Goal goal) {
  TouchRequest request;
  request.goal = goal;
  if (goal == TouchRequest::Goal::pockets && *pins_->pocket_number > 0) {
    request.pockets = {*pins_->pocket_number};
  }
  changer_->request(request);
}

void Component::fly(AirAsk::What what) {
  AirAsk ask;
  ask.what = what;
  ask.tool = *pins_->tool_number;
  if (*pins_->air_from_tool >= 0) ask.from = *pins_->air_from_tool;
  ask.pocket = *pins_->pocket_number;
  ask.air = {*pins_->air_height, *pins_->air_feed};
  const AirPlan plan = plan_air_run(*changer_, ask, position());
  if (plan.request) {
    changer_->request(*plan.request);
  } else {
    tell(MessageKind::error, plan.refused);
  }
}

std::optional<Point> Component::position() const {
  const auto mm = nml_ ? nml_->machine_position_mm() : std::nullopt;
  if (!mm) return std::nullopt;
  const double scale = changer_->config().units == Units::inch ? 1.0 / 25.4 : 1.0;
  return Point{mm->x * scale, mm->y * scale, mm->z * scale};
}

void Component::abort(const std::string& reason) {
  changer_->abort(reason);
  // The executor is gone with the program; nothing it was doing will finish.
  link_.drop();
}

void Component::start_executor_if_needed() {
  // An operator flow starts from an idle machine: a step waiting with no
  // executor to take it means the executor must be run over MDI.
  if (!changer_->status().over_mdi || !task_free_ || !link_.needs_run(now_)) return;
  nml_->run_mdi("o<fixed_atc_probe_execute> call [" +
                std::to_string(static_cast<int>(ExecutorCall::operator_flow)) + "]");
  link_.run_started(now_);
}

void Component::poll_io_check() {
  const Status status = changer_->status();
  IoFacts facts;
  facts.tools = changer_->tools();
  facts.spindle_stopped = *pins_->spindle_stopped;
  facts.machine_on = *pins_->machine_on;
  facts.homed = *pins_->all_homed;
  facts.busy = status.busy() ? std::optional<std::string>(std::string("a sequence is under way (") +
                                                          phase_word(status.phase) + ")")
                             : task_busy_;
  facts.nose = position();
  facts.tool_length = lengths_.spindle_length();
  io_check_.poll(now_, changer_->config(), raw_sensors_, facts, *this);
}

void Component::set_chuck_open(bool open) { io_check_.changer_sets(IoOutput::chuck, open); }
void Component::set_rack_cover_open(bool open) { io_check_.changer_sets(IoOutput::cover, open); }
void Component::set_air_blast(bool on) { io_check_.changer_sets(IoOutput::air_blast, on); }

void Component::start_timer(double seconds) {
  deadline_ =
      now_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

void Component::tell(MessageKind kind, const std::string& said) {
  // A message may name what a file held (a pocket list of a big rack, a path).
  const std::string text = capped_lines(said);
  const char* tag = kind == MessageKind::error    ? "error"
                    : kind == MessageKind::prompt ? "operator"
                                                  : "info";
  std::cerr << "fixed_atc_probe: " << tag << ": " << text << std::endl;
  if (nml_) nml_->tell(kind, text);
  status_file_.said(kind, text);
}

void Component::ask(const Prompt& prompt) { tell(MessageKind::prompt, words(prompt)); }

void Component::save(const ToolState& state) {
  io::save_state_file(state_path_, state, io::kComponentWait);
}

void Component::unexpected(const std::string& state, const std::string& event) {
  std::cerr << "fixed_atc_probe: internal error: event " << event << " in " << state << std::endl;
}

}  // namespace fatc::linuxcnc
