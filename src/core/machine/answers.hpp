#pragma once

// How Operating answers a flow's end, as the flows declare it (FlowKind in
// flows/flow_kind.hpp: when_finished, when_cancelled, when_aborted, and the
// request answered at once).

#include <string>
#include <type_traits>

#include "base/chuck.hpp"
#include "flows/flows.hpp"

namespace fatc::machine {

/// The executor's last step: done, with the tool in the spindle.
inline void publish_done(Context& c) {
  Step done;
  done.kind = StepKind::done;
  done.tool = c.tools.spindle;
  done.label = "done";
  c.publish(done);
}
/// The executor's last step: failed, saying `why`, which the operator reads too.
inline void publish_failure(Context& c, const std::string& why) {
  Step fail = failure_step(why);
  fail.tool = c.tools.spindle;
  c.publish(fail);
  c.tell(MessageKind::error, why);
}
struct AnswerDone {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    fsm.ctx->end_sequence();
    publish_done(*fsm.ctx);
  }
};
/// Touching ended: done, or, where it stopped early of its own (a touch
/// found nothing), the executor fails saying why, so that the operator's
/// command ends in that error.
struct AnswerTouchEnd {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    Context& c = *fsm.ctx;
    c.end_sequence();
    if (c.activity.stopped.empty()) {
      publish_done(c);
      return;
    }
    const std::string why = std::move(c.activity.stopped);
    c.activity.stopped.clear();
    publish_failure(c, why);
  }
};
/// An M6 is done: the rack datum counts it (rack_touch.check_every_changes).
struct AnswerChangeDone {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event& e, Fsm& fsm, Source& s, Target& t) const {
    Context& c = *fsm.ctx;
    if (c.config.rack_touch && c.config.rack_touch->check_every_changes > 0) {
      ++c.tools.datum.changes;
      c.ports.save(c.tools);
    }
    AnswerDone{}(e, fsm, s, t);
  }
};
/// A chuck atom is done. A release leaves its sequence recorded until the
/// clamp: a restart or the machine going off meanwhile leaves what the
/// spindle holds for the operator to confirm.
struct AnswerChuckDone {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    Context& c = *fsm.ctx;
    if (c.outputs.chuck_open) {
      c.record_progress(kChuckHeldOpen, 0);
    } else {
      c.end_sequence();
    }
    publish_done(c);
  }
};
/// The operator cancelled an M6: the executor stops the program, saying where
/// the tools are; nothing is uncertain.
struct StopProgram {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    Context& c = *fsm.ctx;
    c.end_sequence();
    publish_failure(c, "M6 T" + std::to_string(c.request.tool) + " cancelled by the operator; " +
                           c.whereabouts());
  }
};
/// A dry run cut off by an abort or the machine going off: nothing to
/// record, no fault; but the spindle stopped somewhere along the approach.
struct StopDryRun {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event& e, Fsm& fsm, Source&, Target&) const {
    Context& c = *fsm.ctx;
    std::string why = "the machine went off, lost homing or entered estop";
    if constexpr (std::is_same_v<Event, Abort>) why = e.reason;
    const std::string sequence = c.tools.in_progress ? c.tools.in_progress->sequence : "dry run";
    c.end_sequence();
    c.tell(MessageKind::info, sequence + " stopped (" + why +
                                  "); nothing was recorded. The spindle may be in the rack: jog "
                                  "it out the way it came in before the next change");
  }
};
/// The request asks for the tool the spindle already holds: answered done at once.
struct AlreadyInSpindle {
  template <class Fsm, class Source, class Target>
  bool operator()(const ToolChange& e, Fsm& fsm, Source&, Target&) const {
    return e.tool == fsm.ctx->tools.spindle;
  }
};

}  // namespace fatc::machine
