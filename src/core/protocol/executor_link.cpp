#include "executor_link.hpp"

namespace fatc {

std::vector<LinkEvent> ExecutorLink::read(const LinkInputs& in, Time now) {
  std::vector<LinkEvent> events;
  tool_prepare_ = in.tool_prepare;
  tool_change_ = in.tool_change;
  // A request that rises while the interpreter is idle is a dead executor's,
  // or task has not yet reported the run that raised it: it counts once the
  // interpreter runs, when executor-call is that run's.
  pin_request_ = in.step_request;
  const bool request = in.step_request && (request_ || !in.interpreter_idle.value_or(false));
  const bool rose = request && !request_;
  const bool fell = !request && request_;
  request_ = request;

  if (rose) {
    run_asked_until_.reset();
    if (executing_) {
      // Each request after the first reports the step before it done.
      events.push_back(finished(*executing_, in));
      executing_.reset();
    } else if (!attached_) {
      attached_ = true;
      const auto call = static_cast<ExecutorCall>(in.call);
      const bool atom = call == ExecutorCall::chuck_release || call == ExecutorCall::chuck_clamp;
      std::optional<std::string> refused;
      const bool flow_step_waits =
          pending_ && pending_->kind != StepKind::fail && pending_->kind != StepKind::done;
      if ((atom || call == ExecutorCall::tool_change) && flow_step_waits) {
        // An operator flow's step waits for its own run: it must not be lost.
        const std::string what = call == ExecutorCall::tool_change
                                     ? "M6 T" + std::to_string(in.number)
                                 : call == ExecutorCall::chuck_release ? "chuck release"
                                                                       : "chuck clamp";
        refused = what +
                  " refused: the changer waits to run an operator flow's next step; try once "
                  "the flow is done";
      } else if (call == ExecutorCall::tool_change || atom) {
        // A request from G-code: whatever waited was for no run of it (a
        // fault's fail step, say).
        pending_.reset();
        LinkEvent request;
        request.kind = call == ExecutorCall::tool_change     ? LinkEvent::Kind::tool_change
                       : call == ExecutorCall::chuck_release ? LinkEvent::Kind::chuck_release
                                                             : LinkEvent::Kind::chuck_clamp;
        request.tool = in.number;
        events.push_back(request);
      } else if (call != ExecutorCall::operator_flow) {
        refused = "the step executor was called with executor-call " + std::to_string(in.call) +
                  "; expected 1 (M6), 2 (operator flow), 3 (chuck release) or 4 (chuck clamp): "
                  "check [FIXED_ATC_PROBE]EXECUTOR_CALL_OUT and the calls of "
                  "o<fixed_atc_probe_execute>";
      }
      if (refused) {
        // Its own slot: a step the changer waits to have performed stays.
        refusal_ = failure_step(*refused);
        LinkEvent told;
        told.kind = LinkEvent::Kind::refused_call;
        told.reason = *refused;
        events.push_back(told);
      }
    }
  }
  if (fell && offered_) {
    const StepKind kind = offered_->kind;
    if (kind == StepKind::done || kind == StepKind::fail || kind == StepKind::wait_operator) {
      attached_ = false;  // the executor ends its run with this step
    } else if (kind != StepKind::resync) {
      executing_ = offered_;
    }
    offered_.reset();
  }

  // The executor runs inside the interpreter: idle while it expects steps
  // means the program or the MDI command was aborted.
  if (attached_ && in.interpreter_idle.value_or(false)) {
    if (!idle_since_) idle_since_ = now;
    if (now - *idle_since_ >= kAbortGrace) {
      idle_since_.reset();
      attached_ = false;
      LinkEvent lost;
      lost.kind = LinkEvent::Kind::executor_lost;
      lost.reason = "LinuxCNC aborted the program during the sequence";
      events.push_back(lost);
    }
  } else {
    idle_since_.reset();
  }
  return events;
}

LinkEvent ExecutorLink::finished(const Step& step, const LinkInputs& in) const {
  LinkEvent done;
  if (step.kind == StepKind::probe) {
    done.kind = LinkEvent::Kind::probe_result;
    done.touched = in.probe_result > 0.5;
    done.tripped_before = in.probe_result < -0.5;
    done.z = in.probe_z;
  } else {
    done.kind = is_motion(step.kind) ? LinkEvent::Kind::in_position : LinkEvent::Kind::command_done;
  }
  return done;
}

void ExecutorLink::publish(const Step& step) { pending_ = step; }

LinkOutputs ExecutorLink::write(bool changer_idle) {
  if (attached_ && request_ && !offered_ && !executing_) {
    if (refusal_) {
      offer(*refusal_);
      refusal_.reset();
    } else if (pending_) {
      offer(*pending_);
      pending_.reset();
    }
  }
  out_.step_ready = offered_.has_value();
  out_.prepared = tool_prepare_;
  // Level handshake, as hal_manualtoolchange: the builtin M6 at the end of
  // the remap raises tool-change only once the sequence is done.
  out_.changed = tool_change_ && changer_idle;
  return out_;
}

void ExecutorLink::offer(const Step& step) {
  offered_ = step;
  out_.step = step;
}

void ExecutorLink::drop() {
  executing_.reset();
  offered_.reset();
  pending_.reset();
  refusal_.reset();
  attached_ = false;
  idle_since_.reset();
  // The pin, not the deferred request: a rise not yet counted is stale too.
  if (pin_request_) offer(resync_step());
}

bool ExecutorLink::needs_run(Time now) const {
  return pending_ && !attached_ && !(run_asked_until_ && now < *run_asked_until_);
}

void ExecutorLink::run_started(Time now) { run_asked_until_ = now + kRunStartGrace; }

bool ExecutorLink::active() const {
  // A resync waits for the next run, however long: no reason to hurry.
  const bool handshake = offered_ && offered_->kind != StepKind::resync;
  return attached_ || pending_ || executing_ || handshake || tool_change_;
}

}  // namespace fatc
