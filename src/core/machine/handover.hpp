#pragma once

// Manual tools (`manual_tools`): M6 to or from a tool that has no pocket. The
// program holds at `loading` while the operator hands the tool over.

#include "legs.hpp"

namespace fatc::machine {

/// Cancel at a hand-over prompt: the program stops, saying where the tools are.
struct SayChangeCancelled {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    fsm.ctx->stop_reason = "M6 T" + std::to_string(fsm.ctx->requested_tool) +
                           " cancelled by the operator; " + fsm.ctx->whereabouts();
  }
};

// ================================================================ hand out
/// Takes the manual tool in the spindle out of the machine: at `loading`, the
/// operator removes it.
struct HandOutLeg_ : Flow<HandOutLeg_> {
  static int served_tool(const Context& ctx) { return ctx.tools.spindle; }

  struct RemovePrompt {
    std::string operator()(const Context& c) const {
      return "M6 T" + std::to_string(c.requested_tool) + ": remove tool " +
             std::to_string(c.tools.spindle) +
             " (it has no pocket) from the spindle, then press Continue (Cancel stops the program)";
    }
  };
  struct AwaitingRemoval : HoldingForOperator<RemovePrompt> {};

  struct RecordToolRemoved {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->record_out_of_machine(fsm.pocket_tool);
    }
  };

  using initial_state = ToLoadingZ;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start            Event             Next             Action              Guard
  // +----------------+-----------------+----------------+-------------------+------+
  Row < ToLoadingZ     , InPosition      , ToLoadingXY    , none              , none >,
  Row < ToLoadingXY    , InPosition      , AwaitingRemoval, none              , none >,
  Row < AwaitingRemoval, OperatorContinue, Finished       , RecordToolRemoved , none >,
  Row < AwaitingRemoval, OperatorCancel  , Stopped        , SayChangeCancelled, none >
  >;
  // clang-format on
};
using HandOutLeg = msm::back::state_machine<HandOutLeg_>;

// ================================================================ hand in
/// Puts the requested manual tool in the spindle: at `loading`, after a flush,
/// the operator inserts it; then up to safe Z.
struct HandInLeg_ : Flow<HandInLeg_> {
  struct InsertPrompt {
    std::string operator()(const Context& c) const {
      return "M6 T" + std::to_string(c.requested_tool) + ": insert tool " +
             std::to_string(c.requested_tool) +
             " into the spindle, then press Continue (Cancel stops the program)";
    }
  };
  struct AwaitingTool : HoldingForOperator<InsertPrompt> {};
  struct UpToSafeZ : Moving<to::SafeZ> {};
  /// LinuxCNC still has the tool the program started the M6 with.
  struct ReportingEmptySpindle : Moving<to::SpindleTool> {};

  struct RecordToolInserted {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->record_in_spindle(fsm.pocket_tool);
    }
  };

  using initial_state = ToLoadingZ;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                        Event             Next                   Action              Guard
  // +----------------------------+-----------------+----------------------+-------------------+------+
  Row < ToLoadingZ                 , InPosition      , ToLoadingXY          , none              , none >,
  Row < ToLoadingXY                , InPosition      , FlushLeg             , none              , none >,
  Row < FlushLeg::exit_pt<Finished>, LegDone         , AwaitingTool         , none              , none >,
  Row < AwaitingTool               , OperatorContinue, UpToSafeZ            , RecordToolInserted, none >,
  Row < AwaitingTool               , OperatorCancel  , ReportingEmptySpindle, SayChangeCancelled, none >,
  Row < UpToSafeZ                  , InPosition      , Finished             , none              , none >,
  Row < ReportingEmptySpindle      , InPosition      , Stopped              , none              , none >
  >;
  // clang-format on
};
using HandInLeg = msm::back::state_machine<HandInLeg_>;

}  // namespace fatc::machine
