#include "component.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>

#include "hal_pins_detail.hpp"
#include "io/files.hpp"
#include "nml_link.hpp"

namespace fatc::linuxcnc {

Component::Component(HalPins* pins, Config& config, std::string config_path, std::string state_path,
                     NmlLink* nml)
    : pins_(pins),
      nml_(nml),
      config_(config),
      config_path_(std::move(config_path)),
      state_path_(std::move(state_path)),
      wired_(config.sensors),
      status_file_(state_path_ + ".status") {
  *pins_->units_inch = config.units == Units::inch;
}

bool Component::active() const { return link_.active() || deadline_ || changer_->status().busy(); }

void Component::poll(Clock::time_point now, std::optional<bool> interpreter_idle) {
  now_ = now;
  read_machine(interpreter_idle);
  read_executor(interpreter_idle);
  read_operator();
  if (deadline_ && now >= *deadline_) {
    deadline_.reset();
    changer_->timer_elapsed();
  }
  measure_program_tools();
  start_executor_if_needed();
  sync_linuxcnc_tool();
  write_pins();
  status_file_.write(changer_->status(), changer_->cut_off());
}

void Component::read_machine(std::optional<bool> interpreter_idle) {
  const bool stopped = *pins_->spindle_stopped;
  if (spindle_stopped_ != stopped) {
    spindle_stopped_ = stopped;
    changer_->spindle_stopped(stopped);
  }
  // The optional sensors: only the wired ones, so an unconnected pin never
  // wakes the changer.
  SensorReadings sensors;
  if (wired_.zero_speed) sensors.zero_speed = *pins_->zero_speed;
  if (wired_.tool_present) sensors.tool_present = *pins_->tool_present;
  if (wired_.drawbar_open) sensors.drawbar_open = *pins_->drawbar_open;
  if (wired_.drawbar_closed) sensors.drawbar_closed = *pins_->drawbar_closed;
  if (wired_.air_pressure) sensors.air_pressure_ok = *pins_->air_pressure_ok;
  if (const auto& cover = config_.rack_cover) {
    if (cover->opened_sensor) sensors.rack_cover_opened = *pins_->rack_cover_opened;
    if (cover->closed_sensor) sensors.rack_cover_closed = *pins_->rack_cover_closed;
  }
  for (int i = 0; i < pins_->pocket_count; ++i) {
    const int pocket = pins_->pocket_tools[i];
    if (wired_.pocket(pocket)) sensors.pocket_occupied[pocket] = *pins_->pocket_occupied[i];
  }
  if (sensors_ != sensors) {
    sensors_ = sensors;
    changer_->sensors(sensors);
  }
  // After the sensors: becoming ready compares them with the tool state.
  const bool ready = *pins_->machine_on && *pins_->all_homed;
  if (machine_ready_ != ready) {
    machine_ready_ = ready;
    ready ? changer_->ready() : changer_->not_ready();
  }
  // The operator flows run the executor over MDI: task must be free for it.
  task_free_ = nml_ && interpreter_idle.value_or(false);
  if (!nml_) {
    changer_->task_availability("no connection to LinuxCNC's task (NML)");
  } else if (!task_free_) {
    changer_->task_availability("a program or MDI command is running");
  } else {
    changer_->task_availability(std::nullopt);
  }
  if (abort_.rose(*pins_->abort)) abort("the abort pin was raised");
}

void Component::read_executor(std::optional<bool> interpreter_idle) {
  LinkInputs in;
  in.step_request = *pins_->step_request;
  in.call = static_cast<int>(std::lround(*pins_->executor_call));
  in.number = *pins_->number;
  in.probe_result = *pins_->probe_result;
  in.probe_z = *pins_->probe_z;
  in.tool_prepare = *pins_->tool_prepare;
  in.tool_change = *pins_->tool_change;
  in.interpreter_idle = interpreter_idle;
  for (const LinkEvent& e : link_.read(in, now_)) {
    switch (e.kind) {
      case LinkEvent::Kind::tool_change:
        changer_->tool_change(e.tool);
        break;
      case LinkEvent::Kind::chuck_release:
        changer_->chuck(ChuckRequest::Action::release, machine_position());
        break;
      case LinkEvent::Kind::chuck_clamp:
        changer_->chuck(ChuckRequest::Action::clamp, machine_position());
        break;
      case LinkEvent::Kind::in_position:
        changer_->in_position();
        break;
      case LinkEvent::Kind::command_done:
        changer_->command_done();
        break;
      case LinkEvent::Kind::probe_result:
        changer_->probe_result(e.touched, e.z, e.tripped_before);
        break;
      case LinkEvent::Kind::executor_lost:
        abort(e.reason);
        break;
      case LinkEvent::Kind::refused_call:
        tell(MessageKind::error, e.reason);
        break;
    }
  }
}

void Component::read_operator() {
  if (load_.rose(*pins_->load)) changer_->load(*pins_->tool_number, *pins_->pocket_number);
  if (unload_.rose(*pins_->unload)) changer_->unload(*pins_->tool_number);
  if (measure_all_.rose(*pins_->measure_all)) measure_all();
  if (verify_.rose(*pins_->verify_pocket)) changer_->verify(*pins_->pocket_number);
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
    sync_wanted_ = true;
  }
}

void Component::teach(const TeachTarget& target) {
  const std::string what = "teach " + target_name(target) + " refused: ";
  const Status status = changer_->status();
  // Idle, and nothing running: a position taken while a program or MDI moves
  // the machine is nowhere in particular.
  if (!status.accepting) {
    std::string why = "only while the changer is idle";
    if (status.phase == Phase::idle) {
      // Idle yet not accepting: task is busy, or a release holds the chuck open.
      why = task_free_ ? status.activity
                       : "a program or MDI command is running; teach once it stopped";
    }
    tell(MessageKind::error, what + why);
    return;
  }
  if (!nml_) {
    tell(MessageKind::error, what + "no LinuxCNC status to read the machine position from");
    return;
  }
  std::string error;
  const auto text = io::read_small_file(config_path_, error);
  if (!text) {
    tell(MessageKind::error, what + error);
    return;
  }
  const auto at = machine_position();
  if (!at) {
    tell(MessageKind::error, what + "LinuxCNC's status says nothing of the machine position now");
    return;
  }
  const TeachResult taught = fatc::teach(*text, target, *at, limits_);
  if (!taught.text) {
    tell(MessageKind::error, taught.error);
    return;
  }
  try {
    io::save_config_file(config_path_, *text, *taught.text);
  } catch (const std::exception& e) {
    tell(MessageKind::error, what + e.what());
    return;
  }
  // Validated by teach(): the changer uses the new geometry from the next request on.
  config_ = *parse_config(*taught.text).config;
  tell(MessageKind::info, "taught " + taught.change + "; " + io::shown_path(config_path_) +
                              " written, the previous one kept as " +
                              io::shown_path(config_path_ + ".bak"));
}

std::optional<Point> Component::machine_position() const {
  const auto mm = nml_ ? nml_->machine_position_mm() : std::nullopt;
  if (!mm) return std::nullopt;
  const double scale = config_.units == Units::inch ? 1.0 / 25.4 : 1.0;
  return Point{mm->x * scale, mm->y * scale, mm->z * scale};
}

void Component::measure_all() {
  const ToolState& tools = changer_->tools();
  std::vector<int> asked = tools.rack_tools();
  const int which = *pins_->measure_which;
  if (which == 1) {
    asked.erase(std::remove_if(asked.begin(), asked.end(),
                               [&](int tool) { return tools.lengths.count(tool) != 0; }),
                asked.end());
  } else if (which == 2) {
    const std::string program = nml_ ? nml_->loaded_program() : std::string();
    if (program.empty()) {
      tell(MessageKind::error, "measure all refused: no program is loaded in LinuxCNC");
      return;
    }
    const char* ini = std::getenv("INI_FILE_NAME");
    if (!program_tools_.start(program, ini ? ini : "", config_)) {
      tell(MessageKind::error, "measure all refused: the program's tools are being worked out");
    }
    return;  // measure_program_tools() goes on once the interpreter has them
  } else if (which != 0) {
    tell(MessageKind::error,
         "measure all refused: measure-which must be 0 (every tool in the "
         "rack), 1 (the unmeasured) or 2 (the program's), got " +
             std::to_string(which));
    return;
  }
  changer_->measure_all(asked);
}

void Component::measure_program_tools() {
  auto done = program_tools_.take();
  if (!done) return;
  if (!done->tools) {
    tell(MessageKind::error, "measure all refused: " + done->error);
    return;
  }
  changer_->measure_all(*done->tools);
}

void Component::sync_linuxcnc_tool() {
  // LinuxCNC starts with an empty spindle, and an operator's confirmation
  // changes what the spindle holds: tell LinuxCNC what the changer knows,
  // once the machine is idle. Nothing is sent while the changer is unsure.
  if (!sync_wanted_ || !task_free_ || changer_->status().phase != Phase::idle) return;
  const int tool = changer_->tools().spindle;
  if (*pins_->linuxcnc_tool == tool) {
    sync_wanted_ = false;  // done only when LinuxCNC says so: task may refuse an MDI
    return;
  }
  if (sync_sent_ && now_ - *sync_sent_ < std::chrono::seconds(5)) return;
  sync_sent_ = now_;
  if (!nml_->run_mdi("M61 Q" + std::to_string(tool))) return;  // again in 5 s
  tell(MessageKind::info,
       "told LinuxCNC the spindle holds " +
           (tool == 0 ? std::string("nothing") : "tool " + std::to_string(tool)) +
           ", as the changer recorded it");
}

void Component::abort(const std::string& reason) {
  changer_->abort(reason);
  // The executor is gone with the program; nothing it was doing will finish.
  link_.drop();
}

void Component::start_executor_if_needed() {
  // Operator flows start from an idle machine: a step waiting with no
  // executor to take it means the executor must be run over MDI.
  const Phase phase = changer_->status().phase;
  if (phase != Phase::loading && phase != Phase::unloading && phase != Phase::measuring &&
      phase != Phase::verifying) {
    return;
  }
  if (!task_free_ || !link_.needs_run(now_)) return;
  nml_->run_mdi("o<fixed_atc_probe_execute> call [" +
                std::to_string(static_cast<int>(ExecutorCall::operator_flow)) + "]");
  link_.run_started(now_);
}

void Component::write_pins() {
  const Status status = changer_->status();
  const LinkOutputs out = link_.write(status.phase == Phase::idle);
  *pins_->step_kind = static_cast<int>(out.step.kind);
  *pins_->step_axes = static_cast<int>(out.step.axes);
  *pins_->step_x = out.step.target.x;
  *pins_->step_y = out.step.target.y;
  *pins_->step_z = out.step.target.z;
  *pins_->step_feed = out.step.feed;
  *pins_->step_tool = out.step.tool;
  *pins_->step_value = out.step.value;
  *pins_->step_ready = out.step_ready;
  *pins_->prepared = out.prepared;
  *pins_->changed = out.changed;

  *pins_->state = static_cast<int>(status.phase);
  *pins_->ready = status.phase == Phase::idle && !status.chuck_held;
  *pins_->chuck_held = status.chuck_held;
  *pins_->fault = status.phase == Phase::fault;
  *pins_->busy = status.busy();
  *pins_->tool_in_spindle = changer_->tools().spindle;
  *pins_->awaiting = static_cast<int>(status.awaiting);
  *pins_->step_number = status.step_number;
  *pins_->pocket_served = status.pocket;
  *pins_->batch_done = status.batch_done;
  *pins_->batch_total = status.batch_total;
  *pins_->accepting = status.accepting;
  if (status.last_length) *pins_->last_length = *status.last_length;
  // An operator flow waits for the operator once its executor run has ended
  // (the GUI and jogging are then free); M6 holds its program meanwhile.
  *pins_->waiting_for_operator =
      status.awaits_operator() && (!link_.attached() || status.holds_program);
  *pins_->can_cancel = *pins_->waiting_for_operator || (status.probe_cancellable && nml_) ||
                       status.phase == Phase::measuring;
  const auto& cut_off = changer_->cut_off();
  // Only a pocket with a tool of its own has a question to answer.
  *pins_->cut_off_pocket =
      cut_off && status.phase == Phase::fault && changer_->tools().tool_of(cut_off->pocket) != 0
          ? cut_off->pocket
          : 0;
  *pins_->heartbeat = !*pins_->heartbeat;
}

void Component::set_chuck_open(bool open) { *pins_->chuck = open; }
void Component::set_rack_cover_open(bool open) { *pins_->rack_cover_open = open; }
void Component::set_air_blast(bool on) { *pins_->air_blast = on; }

void Component::start_timer(double seconds) {
  deadline_ =
      now_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

void Component::tell(MessageKind kind, const std::string& text) {
  const char* tag = kind == MessageKind::error    ? "error"
                    : kind == MessageKind::prompt ? "operator"
                                                  : "info";
  std::cerr << "fixed_atc_probe: " << tag << ": " << text << std::endl;
  if (nml_) nml_->tell(kind, text);
  status_file_.said(kind, text);
}

void Component::save(const ToolState& state) { io::save_state_file(state_path_, state); }

void Component::unexpected(const std::string& state, const std::string& event) {
  std::cerr << "fixed_atc_probe: internal error: event " << event << " in " << state << std::endl;
}

}  // namespace fatc::linuxcnc
