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
struct AnswerDone {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    fsm.ctx->end_sequence();
    publish_done(*fsm.ctx);
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
    const std::string why =
        "M6 T" + std::to_string(c.request.tool) + " cancelled by the operator; " + c.whereabouts();
    Step fail = failure_step(why);
    fail.tool = c.tools.spindle;
    c.publish(fail);
    c.tell(MessageKind::error, why);
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
