#pragma once

// The top of the machine: off, operating, faulted.

#include <boost/core/demangle.hpp>

#include "operating.hpp"

namespace fatc::machine {

// ================================================================ top
struct Machine_ : msmf::state_machine_def<Machine_> {
  explicit Machine_(Context* context) : ctx(context) {}
  Context* ctx;
  /// The running flow had rows for the event in hand and their guards said
  /// no: as Boost.MSM treats a submachine's, that is no unexpected event.
  bool flow_declined = false;
  /// A request Operating leaves unanswered while no flow runs waits here
  /// (msmf::Defer) and is offered again after the next event: see
  /// `waits_for_the_changer`.
  using activate_deferred_events = int;

  struct MachineNotReady : msmf::state<> {
    using flag_list = boost::mpl::vector1<flag::NotReady>;
    using internal_transition_table = RefusesRequests<BecauseNotReady>;
    /// A chuck a release left open closes with the machine, as a spring
    /// drawbar does when its air goes; whatever a hand did at the spindle
    /// meanwhile, the operator confirms once the machine is back.
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      Context& c = *fsm.ctx;
      c.release_spindle();
      if (!c.outputs.chuck_open) return;
      c.close_chuck();
      c.tools.uncertain = true;
      c.ports.save(c.tools);
      c.tell(MessageKind::error,
             "the chuck, left released by G-code, closed: the machine went off; say what the "
             "spindle holds once it is back on");
    }
  };
  struct Faulted : msmf::state<> {
    using flag_list = boost::mpl::vector1<flag::Faulted>;
    using internal_transition_table = RefusesRequests<BecauseFaulted>;
    template <class Event, class Fsm>
    void on_entry([[maybe_unused]] const Event& e, Fsm& fsm) {
      Context& c = *fsm.ctx;
      // A flow's failure carries its reason; where Operating itself failed (the
      // sensors disagree) it has said why already.
      if constexpr (std::is_same_v<Event, FlowFailed>) {
        if (!e.reason.empty()) c.activity.fault_reason = e.reason;
      }
      c.close_chuck();
      c.release_spindle();
      // An executor still waiting for its next step aborts the program on this.
      c.publish(failure_step(c.activity.fault_reason));
      c.tell(MessageKind::error, "fault: " + c.activity.fault_reason + "; " + c.whereabouts() +
                                     ". Check the spindle and the rack, then clear the fault.");
    }
  };

  struct IsBusy {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.template is_flag_active<flag::Busy>();
    }
  };
  /// A dry run (verify, an air run): the chuck stays closed, so the tools are where they were.
  struct DryRun {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return Flows::any([&](auto flow) {
        using Flow = decltype(flow);
        return Flow::dry_run && fsm.template is_flag_active<Flow>();
      });
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
      return fsm.ctx->machine.ready;
    }
  };
  /// A flow was cut off: what the spindle holds is no longer a fact.
  struct MarkInterrupted {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event& e, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      if constexpr (std::is_same_v<Event, Abort> || std::is_same_v<Event, InternalError>) {
        c.activity.fault_reason = e.reason;
      }
      if constexpr (std::is_same_v<Event, NotReady>) {
        c.activity.fault_reason =
            "the machine went off, lost homing or entered estop during a sequence";
      }
      c.tools.uncertain = true;
      c.ports.save(c.tools);
    }
  };
  /// A sensor check failed in a leg; after a chuck action, what the
  /// spindle holds is no longer a fact.
  struct RecordFailedCheck {
    template <class Fsm, class Source, class Target>
    void operator()(const CheckFailed& e, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      c.activity.fault_reason = e.reason;
      if (e.uncertain) {
        c.tools.uncertain = true;
        c.ports.save(c.tools);
      }
    }
  };
  struct RecordUnsafeStep {
    template <class Fsm, class Source, class Target>
    void operator()(const UnsafeStep& e, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->activity.fault_reason = e.reason;
    }
  };
  struct SayUncertain {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const auto& cut_off = fsm.ctx->tools.in_progress;
      fsm.ctx->activity.fault_reason =
          cut_off && cut_off->step == kChuckHeldOpen
              ? "the chuck was held open by G-code when the machine went off or the component "
                "stopped (the saved tool state is uncertain)"
              : "the last sequence was cut off (the saved tool state is uncertain)";
      // What the wired sensors read helps the operator answer.
      for (const auto& disagreement : fsm.ctx->disagreements()) {
        fsm.ctx->activity.fault_reason += "; " + disagreement;
      }
    }
  };
  /// The operator says what the spindle holds and, for a sequence that was
  /// cut off at a pocket, whether that pocket holds its tool. Nothing moves.
  struct ClearTheFault {
    template <class Fsm, class Source, class Target>
    void operator()(const ClearFault& e, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      const int answered = e.pocket_holds_tool ? c.sequence_pocket() : 0;
      c.tools.confirm(e.spindle_tool, e.pocket_holds_tool);
      // The operator has looked at the rack: every pocket sensor not
      // contradicted by an answer is taken at its word (only while the
      // machine is on: its sensors may have no power otherwise).
      std::string adopted;
      if (c.machine.ready) {
        for (const auto& change : c.sensors.adopt_pocket_sensors(answered, c.tools)) {
          adopted += change + "; ";
        }
      }
      c.activity.fault_reason.clear();
      c.ports.save(c.tools);
      c.tell(MessageKind::info, "fault cleared; " + adopted + c.whereabouts());
    }
  };
  /// The operator's answer fits the record (ToolState::contradiction).
  struct AnswerFits {
    template <class Fsm, class Source, class Target>
    bool operator()(const ClearFault& e, Fsm& fsm, Source&, Target&) const {
      return !fsm.ctx->tools.contradiction(e.spindle_tool, e.pocket_holds_tool);
    }
  };
  /// An answer that cannot be is refused; the fault holds, nothing recorded.
  struct SayAnswerContradicts {
    template <class Fsm, class Source, class Target>
    void operator()(const ClearFault& e, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->tell(MessageKind::error,
                    "clear fault refused: " +
                        *fsm.ctx->tools.contradiction(e.spindle_tool, e.pocket_holds_tool) +
                        "; check confirm-tool and confirm-pocket");
    }
  };
  template <class Words>
  struct Say {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->tell(MessageKind::info, Words::text);
    }
  };
  struct NothingWaitsToContinue {
    static constexpr const char* text = "Continue: nothing is waiting for the operator";
  };
  struct NothingWaitsToCancel {
    static constexpr const char* text = "Cancel: nothing is waiting for the operator";
  };
  struct ThereIsNoFault {
    static constexpr const char* text = "clear fault: there is no fault";
  };

  using initial_state = MachineNotReady;
  // clang-format off
  /// Off, on and working, and what makes the changer fault.
  using until_a_fault = boost::mpl::vector<
  //    Start                        Event           Next              Action            Guard
  // +----------------------------+---------------+-----------------+-----------------+-----------------------+
  Row < MachineNotReady            , Ready         , Operating       , none            , Not<SpindleUncertain> >,
  Row < MachineNotReady            , Ready         , Faulted         , SayUncertain    , SpindleUncertain      >,
  Row < MachineNotReady            , NotReady      , none            , none            , none                  >,
  Row < MachineNotReady            , Abort         , none            , none            , none                  >,
  Row < MachineNotReady            , InternalError , Faulted         , MarkInterrupted , none                  >,
  Row < Operating                  , Ready         , none            , none            , none                  >,
  Row < Operating                  , NotReady      , MachineNotReady , none            , Not<IsBusy>           >,
  Row < Operating                  , NotReady      , MachineNotReady , StopDryRun      , DryRun                >,
  Row < Operating                  , NotReady      , Faulted         , MarkInterrupted , And<IsBusy, Not<DryRun>> >,
  Row < Operating                  , Abort         , none            , none            , Not<IsBusy>           >,
  Row < Operating                  , Abort         , Faulted         , MarkInterrupted , IsBusy                >,
  Row < Operating                  , InternalError , Faulted         , MarkInterrupted , none                  >,
  Row < Operating                  , UnsafeStep    , Faulted         , RecordUnsafeStep, none                  >,
  Row < Operating                  , CheckFailed   , Faulted         , RecordFailedCheck, none                 >,
  Row < Operating::exit_pt<Failed> , FlowFailed    , Faulted         , none            , none                  >
  >;
  /// A fault holds until the operator says what the spindle holds.
  using after_a_fault = boost::mpl::vector<
  //    Start                        Event           Next              Action            Guard
  // +----------------------------+---------------+-----------------+-----------------+-----------------------+
  Row < Faulted                    , ClearFault    , Operating       , ClearTheFault   , And<AnswerFits, MachineIsReady>      >,
  Row < Faulted                    , ClearFault    , MachineNotReady , ClearTheFault   , And<AnswerFits, Not<MachineIsReady>> >,
  Row < Faulted                    , ClearFault    , none            , SayAnswerContradicts, Not<AnswerFits>              >,
  Row < Faulted                    , Ready         , none            , none            , none                  >,
  Row < Faulted                    , NotReady      , none            , none            , none                  >,
  Row < Faulted                    , Abort         , none            , none            , none                  >,
  Row < Faulted                    , InternalError , none            , none            , none                  >
  >;
  using transition_table = boost::mpl::joint_view<until_a_fault, after_a_fault>;
  /// A request no state above answers with no flow running: Operating's
  /// ComparingSensors waits for the cover it closed (CoverStillClosing), or
  /// Operating is on its way out to a fault. It waits and is offered again
  /// after the next event: taken once the cover reads closed, refused by
  /// Faulted (the cover's timeout) or MachineNotReady.
  template <class List>
  struct Waiting;
  template <class... Each>
  struct Waiting<FlowList<Each...>> {
    using type =
        boost::mpl::vector<Internal<typename Each::request, msmf::Defer, Not<IsBusy>>...>;
  };
  using waits_for_the_changer = typename Waiting<Flows>::type;
  /// What no state above answers: a request while a flow runs (Idle and the
  /// other states answer every request themselves), the operator pressed a
  /// button that has nothing to act on, or the spindle or a sensor changed
  /// (facts the guards read). Kept here, not in Operating: an internal table
  /// of a submachine breaks its anonymous rows under favor_compile_time.
  using nothing_else_answers = boost::mpl::vector<
  Internal < OperatorContinue, Say<NothingWaitsToContinue>, none >,
  Internal < OperatorCancel  , Say<NothingWaitsToCancel>  , none >,
  Internal < ClearFault      , Say<ThereIsNoFault>        , none >,
  Internal < SensorReport    , none                       , none >
  >;
  using internal_transition_table = boost::mpl::joint_view<
      boost::mpl::joint_view<RefusesRequests<BecauseBusy, IsBusy>, waits_for_the_changer>,
      nothing_else_answers>;
  // clang-format on

  template <class Fsm, class Event>
  void no_transition(const Event& e, Fsm& fsm, int state) {
    if (flow_declined) return;
    ctx->ports.unexpected("state #" + std::to_string(state),
                          boost::core::demangle(typeid(e).name()));
    fsm.process_event(
        InternalError{"internal error: unexpected " + boost::core::demangle(typeid(e).name())});
  }
  template <class Fsm, class Event>
  void exception_caught(const Event& e, Fsm& fsm, std::exception& error) {
    ctx->ports.unexpected(std::string("exception: ") + error.what(),
                          boost::core::demangle(typeid(e).name()));
    fsm.process_event(InternalError{std::string("internal error: ") + error.what()});
  }
};
using Machine = Machine_of<Machine_>;

}  // namespace fatc::machine
