#include "component.hpp"

#include <cmath>
#include <iostream>

#include "hal_pins_detail.hpp"
#include "io/files.hpp"
#include "nml_link.hpp"

namespace fatc::linuxcnc {
namespace {

/// step-kind 0: nothing to do, ask again (resynchronises after an abort).
constexpr StepKind kResync = static_cast<StepKind>(0);

}  // namespace

Component::Component(HalPins* pins, const Config& config, std::string state_path, NmlLink* nml)
    : pins_(pins), nml_(nml), state_path_(std::move(state_path)) {
  *pins_->units_inch = config.units == Units::inch;
  *pins_->step_ready = 0;
  *pins_->chuck = 0;
}

bool Component::active() const {
  return offered_ || executing_ || pending_ || deadline_ || last_request_ ||
         (changer_ && changer_->status().phase != Phase::idle &&
          changer_->status().phase != Phase::not_ready && changer_->status().phase != Phase::fault);
}

void Component::poll(Clock::time_point now, std::optional<bool> interpreter_idle) {
  now_ = now;
  const bool ready = *pins_->machine_on && *pins_->all_homed;
  if (machine_ready_ != ready) {
    machine_ready_ = ready;
    ready ? changer_->ready() : changer_->not_ready();
  }
  changer_->spindle_stopped(*pins_->spindle_stopped);

  const bool abort_pin = *pins_->abort;
  if (abort_pin && !last_abort_) abort("the abort pin was raised");
  last_abort_ = abort_pin;
  interpreter_idle_ = interpreter_idle;
  watch_for_abort(interpreter_idle);
  serve_operator();

  const bool clear = *pins_->clear_fault;
  if (clear && !last_clear_) changer_->clear_fault(*pins_->linuxcnc_tool);
  last_clear_ = clear;

  if (deadline_ && now >= *deadline_) {
    deadline_.reset();
    changer_->timer_elapsed();
  }

  *pins_->prepared = *pins_->tool_prepare;
  serve_executor();
  start_executor_if_needed();
  // Level handshake, as hal_manualtoolchange: the builtin M6 at the end of the
  // remap raises tool-change only once the sequence is done.
  *pins_->changed = *pins_->tool_change && changer_->status().phase == Phase::idle;
  show_status();
}

void Component::watch_for_abort(std::optional<bool> interpreter_idle) {
  // The executor runs inside the interpreter: an idle interpreter while an
  // executor still expects steps means the program (or MDI) was aborted.
  const Status& status = changer_->status();
  const bool sequence_runs = status.phase == Phase::changing || status.phase == Phase::loading ||
                             status.phase == Phase::unloading;
  if (!interpreter_idle || !*interpreter_idle || !sequence_runs || !executor_attached_) {
    idle_since_.reset();
    return;
  }
  if (!idle_since_) idle_since_ = now_;
  if (now_ - *idle_since_ >= std::chrono::milliseconds(200)) {
    idle_since_.reset();
    abort("LinuxCNC aborted the program during the sequence");
  }
}

void Component::abort(const std::string& reason) {
  changer_->abort(reason);
  drop_executor();
}

void Component::drop_executor() {
  // The executor is gone with the program; nothing it was doing will finish.
  executing_.reset();
  offered_.reset();
  pending_.reset();
  *pins_->step_ready = 0;
  executor_attached_ = false;
  if (*pins_->step_request) {
    // It died asking for a step, and motion keeps that output high. The next
    // executor takes this empty step, drops the request and asks afresh.
    Step resync;
    resync.kind = kResync;
    offer(resync);
  }
}

void Component::serve_operator() {
  auto rising = [](bool now, bool& last) {
    const bool edge = now && !last;
    last = now;
    return edge;
  };
  const bool load = rising(*pins_->load, last_load_);
  const bool unload = rising(*pins_->unload, last_unload_);
  if (load || unload) {
    const std::optional<std::string> why = why_task_busy();
    if (why && changer_->status().phase == Phase::idle) {
      tell(MessageKind::error, std::string(load ? "load" : "unload") + " refused: " + *why);
    } else {
      load ? changer_->load(*pins_->tool_number) : changer_->unload(*pins_->tool_number);
    }
  }
  if (rising(*pins_->continue_, last_continue_)) changer_->operator_continue();
  if (rising(*pins_->cancel, last_cancel_)) {
    if (probe_cancellable(changer_->status()) && nml_) {
      // The probe runs over MDI: stop it before the changer plans the retract,
      // which the next executor run then performs.
      nml_->abort();
      drop_executor();
    }
    changer_->operator_cancel();
  }
}

std::optional<std::string> Component::why_task_busy() const {
  // The operator flows run the executor over MDI: task must be free for it.
  if (!nml_) return std::string("no connection to LinuxCNC's task (NML)");
  if (!interpreter_idle_ || !*interpreter_idle_) return std::string("a program or MDI command is running");
  return std::nullopt;
}

void Component::start_executor_if_needed() {
  // Operator flows start from an idle machine: a step waiting with no
  // executor to take it means the executor must be run over MDI.
  const Phase phase = changer_->status().phase;
  if (!pending_ || executing_ || offered_ || *pins_->step_request || !nml_) return;
  if (phase != Phase::loading && phase != Phase::unloading) return;
  if (starting_until_ && now_ < *starting_until_) return;
  if (why_task_busy()) return;
  nml_->run_mdi("o<fixed_atc_probe_execute> call [0]");
  starting_until_ = now_ + std::chrono::seconds(5);
}

void Component::serve_executor() {
  const bool request = *pins_->step_request;
  if (request && !last_request_) {
    starting_until_.reset();
    executor_attached_ = true;
    if (executing_) {
      const Step finished = *executing_;
      executing_.reset();
      if (finished.kind == StepKind::probe) {
        const double result = *pins_->probe_result;
        changer_->probe_result(result > 0.5, *pins_->probe_z, result < -0.5);
      } else {
        changer_->in_position();
      }
    } else if (!offered_ && !pending_ && changer_->status().phase != Phase::loading &&
               changer_->status().phase != Phase::unloading) {
      changer_->tool_change(*pins_->number);
    }
  }
  if (!request && last_request_ && offered_) {
    *pins_->step_ready = 0;
    const StepKind kind = offered_->kind;
    if (kind != StepKind::done && kind != StepKind::fail && kind != StepKind::wait_operator &&
        kind != kResync) {
      executing_ = offered_;
    } else if (kind != kResync) {
      executor_attached_ = false;  // it ends its run after this step
    }
    offered_.reset();
  }
  offer_pending_if_asked();
  last_request_ = request;
}

void Component::offer_pending_if_asked() {
  if (*pins_->step_request && pending_ && !offered_ && !executing_) {
    offer(*pending_);
    pending_.reset();
  }
}

void Component::offer(const Step& step) {
  *pins_->step_kind = static_cast<int>(step.kind);
  *pins_->step_axes = static_cast<int>(step.axes);
  *pins_->step_x = step.target.x;
  *pins_->step_y = step.target.y;
  *pins_->step_z = step.target.z;
  *pins_->step_feed = step.feed;
  *pins_->step_tool = step.tool;
  *pins_->step_value = step.value;
  *pins_->step_ready = 1;
  offered_ = step;
}

void Component::show_status() {
  const Status& status = changer_->status();
  *pins_->state = static_cast<int>(status.phase);
  *pins_->ready = status.phase == Phase::idle;
  *pins_->fault = status.phase == Phase::fault;
  *pins_->busy = status.phase == Phase::changing || status.phase == Phase::loading ||
                 status.phase == Phase::unloading;
  *pins_->tool_in_spindle = changer_->tools().spindle;
  // In the operator flows only once the executor has ended its run: then the
  // GUI and jogging are free. Inside M6 the executor holds the program.
  const bool executor_free = !executor_attached_ && !offered_;
  *pins_->waiting_for_operator = status.awaiting == Awaiting::operator_choice &&
                                 (executor_free || status.phase == Phase::changing);
  *pins_->awaiting = static_cast<int>(status.awaiting);
  *pins_->accepting = status.phase == Phase::idle && !why_task_busy();
  *pins_->can_cancel = *pins_->waiting_for_operator || (probe_cancellable(status) && nml_);
}

void Component::publish(const Step& step) {
  pending_ = step;
  // A step published while the executor already asks goes out this turn.
  offer_pending_if_asked();
}

void Component::set_chuck_open(bool open) { *pins_->chuck = open; }

void Component::start_timer(double seconds) {
  deadline_ = now_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

void Component::cancel_timer() { deadline_.reset(); }

void Component::tell(MessageKind kind, const std::string& text) {
  const char* tag = kind == MessageKind::error ? "error" : kind == MessageKind::prompt ? "operator" : "info";
  std::cerr << "fixed_atc_probe: " << tag << ": " << text << std::endl;
  if (nml_) nml_->tell(kind, text);
}

void Component::save(const ToolState& state) {
  io::save_state_file(state_path_, state);
  for (const auto& [tool, length] : state.lengths) {
    if (!last_lengths_.count(tool) || last_lengths_.at(tool) != length) *pins_->last_length = length;
  }
  last_lengths_ = state.lengths;
}

void Component::unexpected(const std::string& state, const std::string& event) {
  std::cerr << "fixed_atc_probe: internal error: event " << event << " in " << state << std::endl;
}

}  // namespace fatc::linuxcnc
