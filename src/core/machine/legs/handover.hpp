#pragma once

// The operator hands a tool over at `loading`: into the spindle, or out of
// it. The load and unload flows ask with the executor run ended; M6 with a
// manual tool (`manual_tools`, a tool with no pocket) asks while the program
// holds (AskingOperator).
// docs/sequences.md#manual-tools.

#include "flush_leg.hpp"

namespace fatc::machine {

// ================================================================ insert
/// Flushes the chuck, then the operator inserts the requested tool.
struct InsertLeg_ : Flow<InsertLeg_> {
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    ctx->record_progress("inserting tool " + std::to_string(tool) + " at loading", 0);
  }
  struct InsertPrompt {
    template <class Leg>
    Prompt operator()(const Context&, const Leg& leg) const {
      Prompt insert;
      insert.kind = Prompt::Kind::insert_tool;
      insert.tool = leg.tool;
      return insert;
    }
  };
  struct AwaitingTool : AskingOperator<InsertPrompt> {};
  /// Continue, yet the spindle's sensor sees no tool: the question stands.
  struct SayToolNotSeen {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->tell(MessageKind::error, "tool " + std::to_string(fsm.tool) +
                                            " is not in the spindle (" + Sensors::tool_pin() +
                                            " off): " + words(fsm.ctx->activity.prompt));
    }
  };

  using initial_state = FlushLeg;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                        Event             Next          Action               Guard
  // +----------------------------+-----------------+-------------+--------------------+-------------------------+
  Row < FlushLeg::exit_pt<Finished>, LegDone         , AwaitingTool, none               , none                    >,
  Row < AwaitingTool               , OperatorContinue, Finished    , RecordToolInSpindle, ToolReadsInSpindle      >,
  Row < AwaitingTool               , OperatorContinue, none        , SayToolNotSeen     , Not<ToolReadsInSpindle> >,
  Row < AwaitingTool               , OperatorCancel  , Cancelled   , none               , none                    >
  >;
  // clang-format on
};
using InsertLeg = Machine_of<InsertLeg_>;

// ================================================================ remove
/// The operator takes the tool in the spindle out.
struct RemoveLeg_ : Flow<RemoveLeg_> {
  static int served_tool(const Context& ctx) { return ctx.tools.spindle; }
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    ctx->record_progress("removing tool " + std::to_string(tool) + " at loading", 0);
  }

  struct RemovePrompt {
    template <class Leg>
    Prompt operator()(const Context&, const Leg& leg) const {
      Prompt remove;
      remove.kind = Prompt::Kind::remove_tool;
      remove.tool = leg.tool;
      return remove;
    }
  };
  struct AwaitingRemoval : AskingOperator<RemovePrompt> {};
  /// Continue, yet the spindle's sensor still sees a tool: the question stands.
  struct SayToolStillThere {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->tell(MessageKind::error, "tool " + std::to_string(fsm.tool) +
                                            " is still in the spindle (" + Sensors::tool_pin() +
                                            " on): " + words(fsm.ctx->activity.prompt));
    }
  };

  using initial_state = AwaitingRemoval;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start            Event             Next       Action             Guard
  // +----------------+-----------------+----------+------------------+------------------------+
  Row < AwaitingRemoval, OperatorContinue, Finished , RecordToolRemoved, SpindleReadsEmpty      >,
  Row < AwaitingRemoval, OperatorContinue, none     , SayToolStillThere, Not<SpindleReadsEmpty> >,
  Row < AwaitingRemoval, OperatorCancel  , Cancelled, none             , none                   >
  >;
  // clang-format on
};
using RemoveLeg = Machine_of<RemoveLeg_>;

// ================================================================ hand out (M6)
/// Takes the manual tool in the spindle out of the machine at `loading`.
struct HandOutLeg_ : Flow<HandOutLeg_> {
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    ctx->record_progress("handing tool " + std::to_string(ctx->tools.spindle) + " out at loading",
                         0);
  }
  using Removing = RemoveLeg;
  using initial_state = ToLoading;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                         Event       Next         Action  Guard
  // +-----------------------------+-----------+------------+-------+------+
  Row < ToLoading                   , InPosition, Removing   , none  , none >,
  Row < Removing::exit_pt<Finished> , LegDone   , Finished   , none  , none >,
  Row < Removing::exit_pt<Cancelled>, LegDone   , Cancelled  , none  , none >
  >;
  // clang-format on
};
using HandOutLeg = Machine_of<HandOutLeg_>;

// ================================================================ hand in (M6)
/// Puts the requested manual tool in the spindle at `loading`, then up to
/// safe Z.
struct HandInLeg_ : Flow<HandInLeg_> {
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    ctx->record_progress("handing tool " + std::to_string(tool) + " in at loading", 0);
  }
  using Inserting = InsertLeg;
  /// LinuxCNC still has the tool the program started the M6 with.
  struct ReportingEmptySpindle : Commanding<SpindleToolCommand> {};

  using initial_state = ToLoading;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                          Event        Next                   Action  Guard
  // +------------------------------+------------+----------------------+-------+------+
  Row < ToLoading                    , InPosition , Inserting            , none  , none >,
  Row < Inserting::exit_pt<Finished> , LegDone    , UpToSafeZ            , none  , none >,
  Row < Inserting::exit_pt<Cancelled>, LegDone    , ReportingEmptySpindle, none  , none >,
  Row < UpToSafeZ                    , InPosition , Finished             , none  , none >,
  Row < ReportingEmptySpindle        , CommandDone, Cancelled            , none  , none >
  >;
  // clang-format on
};
using HandInLeg = Machine_of<HandInLeg_>;

}  // namespace fatc::machine
