#pragma once

// The flows a machinist starts: M6 (change), load and probe, unload; and the
// top of the machine that holds them.

#include <boost/core/demangle.hpp>
#include <type_traits>

#include "handover.hpp"

namespace fatc::machine {

struct Before {};  ///< the return of whatever the spindle held before
struct PutAway {}; ///< the return of the tool the flow is about

/// Sets the `state` pin's phase when a flow is entered.
template <Phase P>
struct EntersPhase {
  template <class Fsm>
  static void enter(Fsm& fsm) {
    fsm.ctx->status.phase = P;
  }
};

// ================================================================ change (M6)
struct ChangeFlow_ : Flow<ChangeFlow_> {
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    EntersPhase<Phase::changing>::enter(*this);
  }

  struct WaitingForSpindle : msmf::state<> {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      if (fsm.ctx->spindle_stopped) return;  // leaves at once through the anonymous row
      fsm.ctx->wait(fsm.ctx->config.spindle_stop_timeout_seconds, "waiting for the spindle to stop");
      fsm.ctx->status.awaiting = Awaiting::spindle;
    }
  };
  struct SpindleIsStopped {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.ctx->spindle_stopped;
    }
  };
  struct SaySpindleDidNotStop {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->fault_reason = "the spindle did not stop within spindle_stop_timeout_seconds";
    }
  };

  struct ProbesAfterChange {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.ctx->config.probe_after_change != ProbeAfterChange::off;
    }
  };

  using Returning = ReturnLeg<Before>;
  /// Decides, with the spindle empty, how the requested tool gets into it.
  struct Fetching : Choosing {};
  /// Decides whether the tool now in the spindle is measured.
  struct Measuring : Choosing {};
  using initial_state = WaitingForSpindle;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                            Event           Next         Action                Guard
  // +--------------------------------+---------------+------------+---------------------+-------------------------+
  Row < WaitingForSpindle              , none          , Choosing   , CancelTimer         , SpindleIsStopped        >,
  Row < WaitingForSpindle              , SpindleStopped, Choosing   , CancelTimer         , none                    >,
  Row < WaitingForSpindle              , TimerElapsed  , Failed     , SaySpindleDidNotStop, none                    >,
  Row < Choosing                       , none          , Returning  , none                , SpindleHoldsRackTool    >,
  Row < Choosing                       , none          , HandOutLeg , none                , SpindleHoldsManualTool  >,
  Row < Choosing                       , none          , Fetching   , none                , Not<SpindleHoldsTool>   >,
  Row < Returning::exit_pt<Finished>   , LegDone       , Fetching   , none                , none                    >,
  Row < HandOutLeg::exit_pt<Finished>  , LegDone       , Fetching   , none                , none                    >,
  Row < HandOutLeg::exit_pt<Stopped>   , LegDone       , Stopped    , none                , none                    >,
  Row < Fetching                       , none          , RetrieveLeg, none                , RequestedRackTool       >,
  Row < Fetching                       , none          , HandInLeg  , none                , RequestedManualTool     >,
  Row < Fetching                       , none          , Finished   , none                , Not<ToolRequested>      >,
  Row < RetrieveLeg::exit_pt<Finished> , LegDone       , Measuring  , none                , none                    >,
  Row < HandInLeg::exit_pt<Finished>   , LegDone       , Measuring  , none                , none                    >,
  Row < HandInLeg::exit_pt<Stopped>    , LegDone       , Stopped    , none                , none                    >,
  Row < Measuring                      , none          , MeasureLeg , none                , ProbesAfterChange       >,
  Row < Measuring                      , none          , Finished   , none                , Not<ProbesAfterChange>  >,
  Row < MeasureLeg::exit_pt<Finished>  , LegDone       , Finished   , none                , none                    >,
  Row < MeasureLeg::exit_pt<Failed>    , FlowFailed    , Failed     , none                , none                    >
  >;
  // clang-format on
};
using ChangeFlow = msm::back::state_machine<ChangeFlow_>;

// ================================================================ load and probe
struct LoadFlow_ : Flow<LoadFlow_> {
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    EntersPhase<Phase::loading>::enter(*this);
  }

  struct InsertPrompt {
    std::string operator()(const Context& c) const {
      return "Insert tool " + std::to_string(c.requested_tool) +
             " into the spindle, then press Continue (Cancel to stop)";
    }
  };
  struct JogPrompt {
    std::string operator()(const Context& c) const {
      return "Tool " + std::to_string(c.requested_tool) +
             " is in the spindle. Jog it closer to the touch-off sensor if you like, then press "
             "Continue to probe (Cancel to stop)";
    }
  };
  struct AwaitingTool : AskingOperator<InsertPrompt> {};
  struct ReportingTool : Moving<to::SpindleTool> {};
  struct AwaitingProbe : AskingOperator<JogPrompt> {};
  struct ReportingFinalTool : Moving<to::SpindleTool> {};

  struct RecordToolInserted {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->record_in_spindle(fsm.ctx->requested_tool);
    }
  };
  struct SayCancelled {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->tell(MessageKind::info, "load of tool " + std::to_string(fsm.ctx->requested_tool) +
                                           " cancelled, nothing measured; " + fsm.ctx->whereabouts());
    }
  };

  using Returning = ReturnLeg<Before>;
  using PuttingAway = ReturnLeg<PutAway>;
  using initial_state = Choosing;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                              Event            Next                Action              Guard
  // +----------------------------------+----------------+-------------------+-------------------+-----------------------------+
  Row < Choosing                         , none           , Returning         , none              , SpindleHoldsOtherTool       >,
  Row < Choosing                         , none           , ToLoadingZ        , none              , Not<SpindleHoldsOtherTool>  >,
  Row < Returning::exit_pt<Finished>     , LegDone        , ToLoadingZ        , none              , none                        >,
  Row < ToLoadingZ                       , InPosition     , ToLoadingXY       , none              , none                        >,
  Row < ToLoadingXY                      , InPosition     , FlushLeg          , none              , Not<RequestedToolInSpindle> >,
  Row < ToLoadingXY                      , InPosition     , AwaitingProbe     , none              , RequestedToolInSpindle      >,
  Row < FlushLeg::exit_pt<Finished>      , LegDone        , AwaitingTool      , none              , none                        >,
  Row < AwaitingTool                     , OperatorContinue, ReportingTool    , RecordToolInserted, none                        >,
  Row < AwaitingTool                     , OperatorCancel , ReportingFinalTool, SayCancelled      , none                        >,
  Row < ReportingTool                    , InPosition     , AwaitingProbe     , none              , none                        >,
  Row < AwaitingProbe                    , OperatorContinue, ProbingLeg       , none              , none                        >,
  Row < AwaitingProbe                    , OperatorCancel , ReportingFinalTool, SayCancelled      , none                        >,
  Row < ProbingLeg::exit_pt<Finished>    , LegDone        , PuttingAway       , none              , none                        >,
  Row < ProbingLeg::exit_pt<ProbingLeg_::NotMeasured>, LegDone, ReportingFinalTool, none          , none                        >,
  Row < PuttingAway::exit_pt<Finished>   , LegDone        , ReportingFinalTool, none              , none                        >,
  Row < ReportingFinalTool               , InPosition     , Finished          , none              , none                        >
  >;
  // clang-format on
};
using LoadFlow = msm::back::state_machine<LoadFlow_>;

// ================================================================ unload
struct UnloadFlow_ : Flow<UnloadFlow_> {
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    EntersPhase<Phase::unloading>::enter(*this);
  }

  struct RemovePrompt {
    std::string operator()(const Context& c) const {
      return "Unload tool " + std::to_string(c.requested_tool) +
             " now: release and remove it, then press Continue (Cancel keeps it in the spindle)";
    }
  };
  struct ReportingTool : Moving<to::SpindleTool> {};
  struct AwaitingRemoval : AskingOperator<RemovePrompt> {};
  struct ReportingFinalTool : Moving<to::SpindleTool> {};

  struct RecordToolRemoved {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->record_out_of_machine(fsm.ctx->requested_tool);
    }
  };
  struct SayCancelled {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->tell(MessageKind::info, "unload of tool " + std::to_string(fsm.ctx->requested_tool) +
                                           " cancelled; " + fsm.ctx->whereabouts());
    }
  };
  struct SpindleEmpty {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.ctx->tools.spindle == 0;
    }
  };

  using Returning = ReturnLeg<Before>;
  using initial_state = Choosing;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                            Event             Next                Action             Guard
  // +--------------------------------+-----------------+-------------------+------------------+------------------------+
  Row < Choosing                       , none            , ToLoadingZ        , none             , RequestedToolInSpindle >,
  Row < Choosing                       , none            , Returning         , none             , SpindleHoldsOtherTool  >,
  Row < Choosing                       , none            , RetrieveLeg       , none             , SpindleEmpty           >,
  Row < Returning::exit_pt<Finished>   , LegDone         , RetrieveLeg       , none             , none                   >,
  Row < RetrieveLeg::exit_pt<Finished> , LegDone         , ToLoadingZ        , none             , none                   >,
  Row < ToLoadingZ                     , InPosition      , ToLoadingXY       , none             , none                   >,
  Row < ToLoadingXY                    , InPosition      , ReportingTool     , none             , none                   >,
  Row < ReportingTool                  , InPosition      , AwaitingRemoval   , none             , none                   >,
  Row < AwaitingRemoval                , OperatorContinue, FlushLeg          , RecordToolRemoved, none                   >,
  Row < AwaitingRemoval                , OperatorCancel  , ReportingFinalTool, SayCancelled     , none                   >,
  Row < FlushLeg::exit_pt<Finished>    , LegDone         , ReportingFinalTool, none             , none                   >,
  Row < ReportingFinalTool             , InPosition      , Finished          , none             , none                   >
  >;
  // clang-format on
};
using UnloadFlow = msm::back::state_machine<UnloadFlow_>;

// ================================================================ operating
/// The machine on and homed: idle, or running one flow.
struct Operating_ : Flow<Operating_> {
  struct Idle : msmf::state<> {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      fsm.ctx->status = Status{Phase::idle, Awaiting::nothing, "idle"};
    }
  };

  template <class Request>
  struct Refused {
    template <class Fsm, class Source, class Target>
    bool operator()(const Request& e, Fsm& fsm, Source&, Target&) const {
      return reason(*fsm.ctx, e.tool).has_value();
    }
    static std::optional<std::string> reason(const Context& ctx, int tool);
  };
  struct TakeRequest {
    template <class Request, class Fsm, class Source, class Target>
    void operator()(const Request& e, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->requested_tool = e.tool;
    }
  };
  struct AlreadyInSpindle {
    template <class Fsm, class Source, class Target>
    bool operator()(const ToolChange& e, Fsm& fsm, Source&, Target&) const {
      return !Refused<ToolChange>::reason(*fsm.ctx, e.tool) && e.tool == fsm.ctx->tools.spindle;
    }
  };
  struct Startable {
    template <class Request, class Fsm, class Source, class Target>
    bool operator()(const Request& e, Fsm& fsm, Source&, Target&) const {
      return !Refused<Request>::reason(*fsm.ctx, e.tool) &&
             !(std::is_same_v<Request, ToolChange> && e.tool == fsm.ctx->tools.spindle);
    }
  };
  struct Refuse {
    template <class Request, class Fsm, class Source, class Target>
    void operator()(const Request& e, Fsm& fsm, Source&, Target&) const {
      const std::string why = *Refused<Request>::reason(*fsm.ctx, e.tool);
      if constexpr (std::is_same_v<Request, ToolChange>) {
        Step fail = failure_step("M6 T" + std::to_string(e.tool) + " refused: " + why);
        fail.tool = e.tool;
        fsm.ctx->publish(fail);
        fsm.ctx->status.activity = "idle";
      }
      fsm.ctx->tell(MessageKind::error, why);
    }
  };
  struct AnswerDone {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      Step done;
      done.kind = StepKind::done;
      done.tool = fsm.ctx->tools.spindle;
      done.label = "done";
      fsm.ctx->publish(done);
    }
  };
  /// The executor aborts the program with the reason; nothing is uncertain.
  struct StopProgram {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      Step fail = failure_step(fsm.ctx->stop_reason);
      fail.tool = fsm.ctx->tools.spindle;
      fsm.ctx->publish(fail);
      fsm.ctx->tell(MessageKind::error, fsm.ctx->stop_reason);
    }
  };
  struct IsBusy {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.ctx->status.phase != Phase::idle;
    }
  };

  using initial_state = Idle;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                           Event          Next        Action       Guard
  // +-------------------------------+--------------+-----------+------------+---------------------------+
  Row < Idle                          , ToolChange   , none      , Refuse     , Refused<ToolChange>       >,
  Row < Idle                          , ToolChange   , none      , AnswerDone , AlreadyInSpindle          >,
  Row < Idle                          , ToolChange   , ChangeFlow, TakeRequest, Startable                 >,
  Row < Idle                          , LoadRequest  , none      , Refuse     , Refused<LoadRequest>      >,
  Row < Idle                          , LoadRequest  , LoadFlow  , TakeRequest, Startable                 >,
  Row < Idle                          , UnloadRequest, none      , Refuse     , Refused<UnloadRequest>    >,
  Row < Idle                          , UnloadRequest, UnloadFlow, TakeRequest, Startable                 >,
  Row < ChangeFlow::exit_pt<Finished> , LegDone      , Idle      , AnswerDone , none                      >,
  Row < ChangeFlow::exit_pt<Failed>   , FlowFailed   , Failed    , none       , none                      >,
  Row < ChangeFlow::exit_pt<Stopped>  , LegDone      , Idle      , StopProgram, none                      >,
  Row < LoadFlow::exit_pt<Finished>   , LegDone      , Idle      , AnswerDone , none                      >,
  Row < UnloadFlow::exit_pt<Finished> , LegDone      , Idle      , AnswerDone , none                      >
  >;
  // clang-format on
};

template <>
inline std::optional<std::string> Operating_::Refused<ToolChange>::reason(const Context& c, int t) {
  return why_not_change(c, t);
}
template <>
inline std::optional<std::string> Operating_::Refused<LoadRequest>::reason(const Context& c, int t) {
  return why_not_load(c, t);
}
template <>
inline std::optional<std::string> Operating_::Refused<UnloadRequest>::reason(const Context& c, int t) {
  return why_not_unload(c, t);
}
using Operating = msm::back::state_machine<Operating_>;

// ================================================================ top
struct Machine_ : msmf::state_machine_def<Machine_> {
  explicit Machine_(Context* context) : ctx(context) {}
  Context* ctx;

  struct MachineNotReady : msmf::state<> {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      fsm.ctx->status = Status{Phase::not_ready, Awaiting::nothing, "machine off, not homed or in estop"};
    }
  };
  struct Faulted : msmf::state<> {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      Context& c = *fsm.ctx;
      c.ports.cancel_timer();
      c.close_chuck();
      // An executor still waiting for its next step aborts the program on this.
      c.publish(failure_step(c.fault_reason));
      c.status = Status{Phase::fault, Awaiting::nothing, "fault: " + c.fault_reason};
      c.tell(MessageKind::error, "fault: " + c.fault_reason + "; " + c.whereabouts() +
                                     ". Check the spindle and the rack, then clear the fault.");
    }
  };

  struct SpindleUncertain {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.ctx->tools.uncertain;
    }
  };
  struct MachineIsReady {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.ctx->machine_ready;
    }
  };
  /// A flow was cut off: what the spindle holds is no longer a fact.
  struct MarkInterrupted {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event& e, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      if constexpr (std::is_same_v<Event, Abort>) c.fault_reason = e.reason;
      if constexpr (std::is_same_v<Event, NotReady>) {
        c.fault_reason = "the machine went off, lost homing or entered estop during a sequence";
      }
      c.tools.uncertain = true;
      c.ports.save(c.tools);
    }
  };
  struct SayUncertain {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->fault_reason = "the last sequence was interrupted (saved state says uncertain)";
    }
  };
  struct ClearTheFault {
    template <class Fsm, class Source, class Target>
    void operator()(const ClearFault& e, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      c.tools.uncertain = false;
      c.fault_reason.clear();
      c.record_in_spindle(e.spindle_tool);
      c.tell(MessageKind::info, "fault cleared; " + c.whereabouts());
    }
  };
  using IsBusy = Operating_::IsBusy;

  using initial_state = MachineNotReady;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                          Event        Next       Action           Guard
  // +------------------------------+------------+----------+----------------+-----------------------+
  Row < MachineNotReady              , Ready      , Operating, none           , Not<SpindleUncertain> >,
  Row < MachineNotReady              , Ready      , Faulted  , SayUncertain   , SpindleUncertain      >,
  Row < MachineNotReady              , Abort      , none     , none           , none                  >,
  Row < MachineNotReady              , NotReady   , none     , none           , none                  >,
  Row < Operating                    , NotReady   , MachineNotReady, none     , Not<IsBusy>           >,
  Row < Operating                    , NotReady   , Faulted  , MarkInterrupted, IsBusy                >,
  Row < Operating                    , Abort      , none     , none           , Not<IsBusy>           >,
  Row < Operating                    , Abort      , Faulted  , MarkInterrupted, IsBusy                >,
  Row < Operating::exit_pt<Failed>   , FlowFailed , Faulted  , none           , none                  >,
  Row < Faulted                      , ClearFault , Operating, ClearTheFault  , MachineIsReady        >,
  Row < Faulted                      , ClearFault , MachineNotReady, ClearTheFault  , Not<MachineIsReady>   >,
  Row < Faulted                      , Abort      , none     , none           , none                  >,
  Row < Faulted                      , Ready      , none     , none           , none                  >,
  Row < Faulted                      , NotReady   , none     , none           , none                  >
  >;
  // clang-format on

  template <class Fsm, class Event>
  void no_transition(const Event& e, Fsm& fsm, int state) {
    ctx->ports.unexpected("state #" + std::to_string(state),
                          boost::core::demangle(typeid(e).name()));
    fsm.process_event(Abort{"internal error: unexpected " + boost::core::demangle(typeid(e).name())});
  }
  template <class Fsm, class Event>
  void exception_caught(const Event& e, Fsm& fsm, std::exception& error) {
    ctx->ports.unexpected(std::string("exception: ") + error.what(),
                          boost::core::demangle(typeid(e).name()));
    fsm.process_event(Abort{std::string("internal error: ") + error.what()});
  }
};
using Machine = msm::back::state_machine<Machine_>;

}  // namespace fatc::machine
