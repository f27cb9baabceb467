#pragma once

// The machine on and homed: idle, or running one flow; the requests and
// their refusals.

#include "changer.hpp"
#include "chuck.hpp"
#include "flow_run.hpp"

namespace fatc::machine {

// ================================================================ requests and refusals
inline std::string request_name(const ToolChange& e) { return "M6 T" + std::to_string(e.tool); }
inline std::string request_name(const LoadRequest& e) {
  return "load of tool " + std::to_string(e.tool) +
         (e.pocket != 0 ? " into pocket " + std::to_string(e.pocket) : std::string());
}
inline std::string request_name(const MeasureRequest& e) {
  return "measure all (" + std::to_string(e.tools.size()) + " tools)";
}
inline std::string request_name(const UnloadRequest& e) {
  return "unload of tool " + std::to_string(e.tool);
}
inline std::string request_name(const VerifyRequest& e) {
  return "verify of pocket " + std::to_string(e.pocket);
}
inline std::string request_name(const ChuckRequest& e) {
  return e.action == ChuckRequest::Action::release ? "chuck release" : "chuck clamp";
}
inline std::string request_name(const ConfigChanged& e) { return e.request; }

// A request the changer could take is rehearsed last: its whole sequence is
// checked with the tools it carries before anything moves.
inline std::optional<std::string> why_not(const Context& c, const ToolChange& e) {
  if (auto why = why_not_change(c, e.tool)) return why;
  return c.rehearse([tool = e.tool](Changer& copy) { copy.tool_change(tool); });
}
inline std::optional<std::string> why_not(const Context& c, const LoadRequest& e) {
  if (auto why = why_not_load(c, e.tool, e.pocket)) return why;
  return c.rehearse([e](Changer& copy) { copy.load(e.tool, e.pocket); });
}
inline std::optional<std::string> why_not(const Context& c, const MeasureRequest& e) {
  if (auto why = why_not_measure(c, e.tools)) return why;
  return c.rehearse([e](Changer& copy) { copy.measure_all(e.tools); });
}
inline std::optional<std::string> why_not(const Context& c, const UnloadRequest& e) {
  if (auto why = why_not_unload(c, e.tool)) return why;
  return c.rehearse([tool = e.tool](Changer& copy) { copy.unload(tool); });
}
inline std::optional<std::string> why_not(const Context& c, const VerifyRequest& e) {
  if (auto why = why_not_verify(c, e.pocket)) return why;
  return c.rehearse([pocket = e.pocket](Changer& copy) { copy.verify(pocket); });
}
inline std::optional<std::string> why_not(const Context& c, const ChuckRequest& e) {
  return why_not_chuck(c, e);
}
inline std::optional<std::string> why_not(const Context& c, const ConfigChanged&) {
  return why_not_reconfigure(c, true, false);
}

/// Refuses a request, saying why `Because` gives. The executor of an M6 or a
/// chuck atom waits for a step: it gets one that fails its program with the
/// same words.
template <class Because>
struct Refuse {
  template <class Request, class Fsm, class Source, class Target>
  void operator()(const Request& e, Fsm& fsm, Source&, Target&) const {
    const std::string text = request_name(e) + " refused: " + Because{}(fsm, e);
    if constexpr (std::is_same_v<Request, ToolChange> || std::is_same_v<Request, ChuckRequest>) {
      Step fail = failure_step(text);
      if constexpr (std::is_same_v<Request, ToolChange>) fail.tool = e.tool;
      // Straight to the executor: the flow running (if any) goes on as it was.
      fsm.ctx->ports.publish(fail);
    }
    fsm.ctx->tell(MessageKind::error, text);
  }
};
struct BecauseNotPossible {
  template <class Fsm, class Request>
  std::string operator()(Fsm& fsm, const Request& e) const {
    return *why_not(*fsm.ctx, e);
  }
};
struct BecauseNotReady {
  template <class Fsm, class Request>
  std::string operator()(Fsm&, const Request&) const {
    return "the machine is not on and homed, or is in estop";
  }
};
struct BecauseFaulted {
  template <class Fsm, class Request>
  std::string operator()(Fsm& fsm, const Request&) const {
    return "the changer is in fault (" + fsm.ctx->fault_reason + "); clear it first";
  }
};
struct BecauseBusy {
  template <class Fsm, class Request>
  std::string operator()(Fsm& fsm, const Request&) const {
    const std::string tool = std::to_string(fsm.ctx->requested_tool);
    if (fsm.template is_flag_active<flag::Loading>())
      return "the changer is busy loading tool " + tool;
    if (fsm.template is_flag_active<flag::Unloading>())
      return "the changer is busy unloading tool " + tool;
    if (fsm.template is_flag_active<flag::Verifying>())
      return "the changer is busy verifying pocket " + std::to_string(fsm.ctx->sequence_pocket());
    if (fsm.template is_flag_active<flag::Chucking>()) return "the changer is busy with the chuck";
    return "the changer is busy changing to tool " + tool;
  }
};
/// A taught config is refused in the same words wherever the changer is not
/// plainly idle (Changer::why_not_teach asks the same before anything is read).
struct BecauseNotIdle {
  template <class Fsm>
  std::string operator()(Fsm& fsm, const ConfigChanged&) const {
    return why_not_reconfigure(*fsm.ctx, fsm.template is_flag_active<flag::Idle>(),
                               fsm.template is_flag_active<flag::AwaitsSensor>())
        .value_or("only while the changer is idle");
  }
};
/// The requests, refused for one reason (a taught config: for not being idle):
/// a state's internal rows. With `Guard`, a request is refused only where it
/// holds (a taught config always).
template <class Because, class Guard = none>
using RefusesRequests =
    boost::mpl::vector<msmf::Internal<ToolChange, Refuse<Because>, Guard>,
                       msmf::Internal<LoadRequest, Refuse<Because>, Guard>,
                       msmf::Internal<UnloadRequest, Refuse<Because>, Guard>,
                       msmf::Internal<MeasureRequest, Refuse<Because>, Guard>,
                       msmf::Internal<VerifyRequest, Refuse<Because>, Guard>,
                       msmf::Internal<ChuckRequest, Refuse<Because>, Guard>,
                       msmf::Internal<ConfigChanged, Refuse<BecauseNotIdle>, none>>;

// ================================================================ operating
/// The machine on and homed: idle, or running one flow.
struct BecauseSensorsDisagree {
  template <class Fsm, class Request>
  std::string operator()(Fsm& fsm, const Request&) const {
    std::string words = "the sensors disagree with the saved tool state";
    for (const auto& disagreement : fsm.ctx->disagreements()) words += "; " + disagreement;
    return words;
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
    const int pocket = c.sequence_pocket();
    c.end_sequence();
    c.tell(MessageKind::info, "verify of pocket " + std::to_string(pocket) + " stopped (" +
                                  why +
                                  "); nothing was recorded. The spindle may be in the rack: jog "
                                  "it out the way it came in before the next change");
  }
};
// The flows, each defined and built in its own files.
struct ChangeFlow_;
struct LoadFlow_;
struct UnloadFlow_;
struct MeasureAllFlow_;
struct VerifyFlow_;
struct ChuckFlow_;

/// A flow running as a machine of its own (flow_run.hpp), started on entry
/// with the request that asked for it and stopped on exit; it carries the
/// flags Busy and the flow's own (Changing, ...). Only the flow's own file
/// reads its table.
template <class Front, class Request, class Flag>
struct Running : msmf::state<> {
  using flow_front = Front;
  using flag_list = boost::mpl::vector2<flag::Busy, Flag>;
  template <class Event, class Fsm>
  void on_entry(const Event& e, Fsm& fsm) {
    // Boost.MSM builds an entry for each event that enters Operating; only
    // the request enters this state.
    if constexpr (std::is_same_v<Event, Request>) fsm.flow = run_flow<Front>(*fsm.ctx, e);
  }
  template <class Event, class Fsm>
  void on_exit(const Event&, Fsm& fsm) {
    fsm.flow->stop();
    fsm.flow.reset();
  }
};
using ChangeFlow = Running<ChangeFlow_, ToolChange, flag::Changing>;
using LoadFlow = Running<LoadFlow_, LoadRequest, flag::Loading>;
using UnloadFlow = Running<UnloadFlow_, UnloadRequest, flag::Unloading>;
using MeasureAllFlow = Running<MeasureAllFlow_, MeasureRequest, flag::Measuring>;
using VerifyFlow = Running<VerifyFlow_, VerifyRequest, flag::Verifying>;
using ChuckFlow = Running<ChuckFlow_, ChuckRequest, flag::Chucking>;

struct Operating_ : Flow<Operating_> {
  /// The flow running, if any (Running<Flow>).
  std::unique_ptr<FlowRun> flow;

  struct Idle : msmf::state<> {
    using flag_list = boost::mpl::vector1<flag::Idle>;
  };
  /// The changer is done with the rack: its cover (if any) closes, and
  /// `rack-cover-closed` (if wired) has its own timeout to say so.
  struct SensorOrCoverTimeout {
    double operator()(const Config& c) const {
      return c.rack_cover && c.rack_cover->closed_sensor
                 ? std::max(c.sensor_timeout_seconds, c.rack_cover->timeout_seconds)
                 : c.sensor_timeout_seconds;
    }
  };
  /// The cover this state commanded closed is still on its way, and nothing
  /// else disagrees: a request waits for it (the top machine defers it).
  struct CoverStillClosing {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.ctx->cover_still_closing();
    }
  };
  /// Before the changer takes work (at start, after a fault, after every
  /// flow, and whenever a sensor changes while idle) the wired sensors must
  /// agree with the tool state, or come to within sensor_timeout_seconds.
  /// A request meanwhile is refused, unless it only waits for the cover to close.
  struct ComparingSensors : AwaitingSensor<SensorsAgree, SensorOrCoverTimeout> {
    using flag_list = boost::mpl::vector2<flag::Idle, flag::AwaitsSensor>;
    using internal_transition_table =
        RefusesRequests<BecauseSensorsDisagree, Not<CoverStillClosing>>;
    template <class Event, class Fsm>
    void on_entry(const Event& e, Fsm& fsm) {
      fsm.ctx->close_cover();
      AwaitingSensor::on_entry(e, fsm);
    }
    template <class Event, class Fsm>
    void on_exit(const Event& e, Fsm& fsm) {
      fsm.ctx->cover_closing = false;
      AwaitingSensor::on_exit(e, fsm);
    }
  };
  struct SaySensorsDisagree {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event& e, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->fault_reason = BecauseSensorsDisagree{}(fsm, e);
    }
  };

  struct Refused {
    template <class Request, class Fsm, class Source, class Target>
    bool operator()(const Request& e, Fsm& fsm, Source&, Target&) const {
      return why_not(*fsm.ctx, e).has_value();
    }
  };
  struct AlreadyInSpindle {
    template <class Fsm, class Source, class Target>
    bool operator()(const ToolChange& e, Fsm& fsm, Source&, Target&) const {
      return e.tool == fsm.ctx->tools.spindle;
    }
  };
  struct TakeRequest {
    template <class Request, class Fsm, class Source, class Target>
    void operator()(const Request& e, Fsm& fsm, Source&, Target&) const {
      // What the flow itself needs of the request it takes on entry.
      Context& c = *fsm.ctx;
      c.in_program = std::is_same_v<Request, ToolChange> || std::is_same_v<Request, ChuckRequest>;
      if constexpr (std::is_same_v<Request, VerifyRequest> ||
                    std::is_same_v<Request, ChuckRequest>) {
        c.requested_tool = c.tools.spindle;
      } else if constexpr (!std::is_same_v<Request, MeasureRequest>) {
        c.requested_tool = e.tool;
      }
      c.begin_sequence(request_name(e));
    }
  };
  /// The changer works with the taught config from the next request on.
  struct TakeConfig {
    template <class Fsm, class Source, class Target>
    void operator()(const ConfigChanged& e, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->config = e.config;
      ++fsm.ctx->configs_taken;
    }
  };
  /// The executor's last step: done, with the tool in the spindle.
  static void publish_done(Context& c) {
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
      if (c.chuck_open) {
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
      const std::string why = "M6 T" + std::to_string(c.requested_tool) +
                              " cancelled by the operator; " + c.whereabouts();
      Step fail = failure_step(why);
      fail.tool = c.tools.spindle;
      c.publish(fail);
      c.tell(MessageKind::error, why);
    }
  };

  using initial_state = ComparingSensors;
  // clang-format off
  /// Requests taken while idle: refused with a reason, or their flow started.
  using requests = boost::mpl::vector<
  //    Start                            Event           Next        Action                      Guard
  // +--------------------------------+---------------+-----------+---------------------------+-----------------------------------+
  Row < Idle                           , ToolChange    , none      , Refuse<BecauseNotPossible>, Refused                           >,
  Row < Idle                           , ToolChange    , none      , AnswerDone                , And<Not<Refused>, AlreadyInSpindle> >,
  Row < Idle                           , ToolChange    , ChangeFlow, TakeRequest               , And<Not<Refused>, Not<AlreadyInSpindle>> >,
  Row < Idle                           , LoadRequest   , none      , Refuse<BecauseNotPossible>, Refused                           >,
  Row < Idle                           , LoadRequest   , LoadFlow  , TakeRequest               , Not<Refused>                      >,
  Row < Idle                           , UnloadRequest , none      , Refuse<BecauseNotPossible>, Refused                           >,
  Row < Idle                           , UnloadRequest , UnloadFlow, TakeRequest               , Not<Refused>                      >,
  Row < Idle                           , MeasureRequest, none      , Refuse<BecauseNotPossible>, Refused                           >,
  Row < Idle                           , MeasureRequest, MeasureAllFlow, TakeRequest           , Not<Refused>                      >,
  Row < Idle                           , VerifyRequest , none      , Refuse<BecauseNotPossible>, Refused                           >,
  Row < Idle                           , VerifyRequest , VerifyFlow, TakeRequest               , Not<Refused>                      >,
  Row < Idle                           , ChuckRequest  , none      , Refuse<BecauseNotPossible>, Refused                           >,
  Row < Idle                           , ChuckRequest  , ChuckFlow , TakeRequest               , Not<Refused>                      >,
  Row < Idle                           , ConfigChanged , none      , Refuse<BecauseNotPossible>, Refused                           >,
  Row < Idle                           , ConfigChanged , none      , TakeConfig                , Not<Refused>                      >
  >;
  /// Comparing the sensors before work, and where each flow ends.
  using around_the_flows = boost::mpl::vector<
  //    Start                              Event          Next              Action              Guard
  // +----------------------------------+--------------+-----------------+-------------------+--------------------+
  Row < ComparingSensors                 , SensorReport , Idle            , none              , SensorsAgree       >,
  Row < ComparingSensors                 , TimerElapsed , Failed          , SaySensorsDisagree, none               >,
  Row < Idle                             , SensorReport , ComparingSensors, none              , Not<SensorsAgree>  >,
  Row < ChangeFlow                       , FlowFinished , ComparingSensors, AnswerDone        , none               >,
  Row < ChangeFlow                       , FlowFailed   , Failed          , none              , none               >,
  Row < ChangeFlow                       , FlowCancelled, ComparingSensors, StopProgram       , none               >,
  Row < LoadFlow                         , FlowFinished , ComparingSensors, AnswerDone        , none               >,
  Row < UnloadFlow                       , FlowFinished , ComparingSensors, AnswerDone        , none               >,
  Row < MeasureAllFlow                   , FlowFinished , ComparingSensors, AnswerDone        , none               >,
  Row < VerifyFlow                       , FlowFinished , ComparingSensors, AnswerDone        , none               >,
  Row < VerifyFlow                       , FlowCancelled, ComparingSensors, AnswerDone        , none               >,
  Row < VerifyFlow                       , Abort        , ComparingSensors, StopDryRun        , none               >,
  Row < ChuckFlow                        , FlowFinished , ComparingSensors, AnswerChuckDone   , none               >
  >;
  using transition_table = boost::mpl::joint_view<requests, around_the_flows>;
  // clang-format on
};
using Operating = Machine_of<Operating_>;

}  // namespace fatc::machine
