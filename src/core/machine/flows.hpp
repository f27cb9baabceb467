#pragma once

// The flows a machinist starts: M6 (change), load and probe, unload; and the
// top of the machine that holds them.

#include <algorithm>
#include <boost/core/demangle.hpp>
#include <cstdio>
#include <type_traits>

#include "handover.hpp"

namespace fatc::machine {

// ================================================================ change (M6)
/// M6: empty the spindle (its tool back to its pocket, or handed out), then
/// fetch the requested tool (from its pocket, or handed in), then measure it
/// if `probe_after_change` asks. docs/sequences.md#m6.
struct ChangeFlow_ : Flow<ChangeFlow_> {
  using flag_list = boost::mpl::vector2<flag::Busy, flag::Changing>;

  /// LinuxCNC's spindle off and, where wired, zero speed.
  struct WaitingForSpindle
      : AwaitingSensor<SpindleIsStopped, SpindleStopTimeout, flag::AwaitsSpindle> {};
  struct SaySpindleDidNotStop {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      fsm.ctx->fault_reason = "the spindle did not stop within spindle_stop_timeout_seconds";
      if (c.config.sensors.zero_speed && !c.sensors.zero_speed) {
        fsm.ctx->fault_reason += " (zero-speed off)";
      }
    }
  };
  struct ProbesAfterChange {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.ctx->config.probe_after_change != ProbeAfterChange::off;
    }
  };

  using Returning = ReturnLeg<Before>;
  struct DecidingHowToEmpty : Decision {};
  /// The spindle is empty: how does the requested tool get into it?
  struct DecidingHowToFetch : Decision {};
  struct DecidingToMeasure : Decision {};
  using initial_state = WaitingForSpindle;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                            Event           Next                Action                Guard
  // +--------------------------------+---------------+-------------------+---------------------+-------------------------+
  Row < WaitingForSpindle              , SensorReport  , DecidingHowToEmpty, none                , SpindleIsStopped     >,
  Row < WaitingForSpindle              , TimerElapsed  , Failed            , SaySpindleDidNotStop, none                    >,
  Row < DecidingHowToEmpty             , none          , Returning         , none                , SpindleHoldsRackTool    >,
  Row < DecidingHowToEmpty             , none          , HandOutLeg        , none                , SpindleHoldsManualTool  >,
  Row < DecidingHowToEmpty             , none          , DecidingHowToFetch, none                , Not<SpindleHoldsTool>   >,
  Row < Returning::exit_pt<Finished>   , LegDone       , DecidingHowToFetch, none                , none                    >,
  Row < HandOutLeg::exit_pt<Finished>  , LegDone       , DecidingHowToFetch, none                , none                    >,
  Row < HandOutLeg::exit_pt<Cancelled> , LegDone       , Cancelled         , none                , none                    >,
  Row < DecidingHowToFetch             , none          , RetrieveLeg       , none                , RequestedRackTool       >,
  Row < DecidingHowToFetch             , none          , HandInLeg         , none                , RequestedManualTool     >,
  Row < DecidingHowToFetch             , none          , Finished          , none                , Not<ToolRequested>      >,
  Row < RetrieveLeg::exit_pt<Finished> , LegDone       , DecidingToMeasure , none                , none                    >,
  Row < HandInLeg::exit_pt<Finished>   , LegDone       , DecidingToMeasure , none                , none                    >,
  Row < HandInLeg::exit_pt<Cancelled>  , LegDone       , Cancelled         , none                , none                    >,
  Row < DecidingToMeasure              , none          , MeasureLeg        , none                , ProbesAfterChange       >,
  Row < DecidingToMeasure              , none          , Finished          , none                , Not<ProbesAfterChange>  >,
  Row < MeasureLeg::exit_pt<Finished>  , LegDone       , Finished          , none                , none                    >,
  Row < MeasureLeg::exit_pt<Failed>    , FlowFailed    , Failed            , none                , none                    >
  >;
  // clang-format on
};
using ChangeFlow = Machine_of<ChangeFlow_>;

/// Tells LinuxCNC (M61) what the spindle holds; `Which` tells uses apart.
template <class Which>
struct ReportingSpindleTool : Commanding<SpindleToolCommand> {};
struct AfterInsertion {};
struct AtTheEnd {};
struct AfterFetch {};
struct AfterReturn {};

// ================================================================ load and probe
/// The operator loads a tool by hand at `loading`; it is measured on the
/// sensor and put away in its pocket. docs/sequences.md#load-and-probe.
struct LoadFlow_ : Flow<LoadFlow_> {
  using flag_list = boost::mpl::vector2<flag::Busy, flag::Loading>;

  struct JogPrompt {
    template <class Leg>
    std::string operator()(const Context& c, const Leg&) const {
      return "Tool " + std::to_string(c.requested_tool) +
             " is in the spindle. Jog it closer to the touch-off sensor if you like, then press "
             "Continue to probe (Cancel to stop)";
    }
  };
  struct AwaitingProbe : AskingOperator<JogPrompt> {};
  struct SayCancelled {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->tell(MessageKind::info, "load of tool " + std::to_string(fsm.ctx->requested_tool) +
                                           " cancelled, nothing measured; " +
                                           fsm.ctx->whereabouts());
    }
  };

  using Returning = ReturnLeg<Before>;
  using Inserting = InsertLeg<EndingTheRun>;
  using Probe = ProbingLeg<OverMdi>;
  using PuttingAway = ReturnLeg<PutAway>;
  using ReportingTool = ReportingSpindleTool<AfterInsertion>;
  using ReportingFinalTool = ReportingSpindleTool<AtTheEnd>;
  struct DecidingToReturn : Decision {};
  using initial_state = DecidingToReturn;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                              Event             Next                Action        Guard
  // +----------------------------------+-----------------+-------------------+-------------+-----------------------------+
  Row < DecidingToReturn                 , none            , Returning         , none        , SpindleHoldsOtherTool       >,
  Row < DecidingToReturn                 , none            , ToLoading         , none        , Not<SpindleHoldsOtherTool>  >,
  Row < Returning::exit_pt<Finished>     , LegDone         , ToLoading         , none        , none                        >,
  Row < ToLoading                        , InPosition      , Inserting         , none        , Not<RequestedToolInSpindle> >,
  Row < ToLoading                        , InPosition      , AwaitingProbe     , none        , RequestedToolInSpindle      >,
  Row < Inserting::exit_pt<Finished>     , LegDone         , ReportingTool     , none        , none                        >,
  Row < Inserting::exit_pt<Cancelled>    , LegDone         , ReportingFinalTool, SayCancelled, none                        >,
  Row < ReportingTool                    , CommandDone     , AwaitingProbe     , none        , none                        >,
  Row < AwaitingProbe                    , OperatorContinue, Probe             , none        , none                        >,
  Row < AwaitingProbe                    , OperatorCancel  , ReportingFinalTool, SayCancelled, none                        >,
  Row < Probe::exit_pt<Finished>         , LegDone         , PuttingAway       , none        , none                        >,
  Row < Probe::exit_pt<Probe::NotMeasured>, LegDone        , ReportingFinalTool, none        , none                        >,
  Row < PuttingAway::exit_pt<Finished>   , LegDone         , ReportingFinalTool, none        , none                        >,
  Row < ReportingFinalTool               , CommandDone     , Finished          , none        , none                        >
  >;
  // clang-format on
};
using LoadFlow = Machine_of<LoadFlow_>;

// ================================================================ unload
/// The requested tool is fetched (if not in the spindle already) and taken
/// out by the operator at `loading`. docs/sequences.md#unload.
struct UnloadFlow_ : Flow<UnloadFlow_> {
  using flag_list = boost::mpl::vector2<flag::Busy, flag::Unloading>;

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
  using Removing = RemoveLeg<EndingTheRun>;
  using ReportingTool = ReportingSpindleTool<AfterInsertion>;
  using ReportingFinalTool = ReportingSpindleTool<AtTheEnd>;
  struct DecidingWhereToStart : Decision {};
  using initial_state = DecidingWhereToStart;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                            Event         Next                Action        Guard
  // +--------------------------------+-------------+-------------------+-------------+------------------------+
  Row < DecidingWhereToStart           , none        , ToLoading         , none        , RequestedToolInSpindle >,
  Row < DecidingWhereToStart           , none        , Returning         , none        , SpindleHoldsOtherTool  >,
  Row < DecidingWhereToStart           , none        , RetrieveLeg       , none        , SpindleEmpty           >,
  Row < Returning::exit_pt<Finished>   , LegDone     , RetrieveLeg       , none        , none                   >,
  Row < RetrieveLeg::exit_pt<Finished> , LegDone     , ToLoading         , none        , none                   >,
  Row < ToLoading                      , InPosition  , ReportingTool     , none        , none                   >,
  Row < ReportingTool                  , CommandDone , Removing          , none        , none                   >,
  Row < Removing::exit_pt<Finished>    , LegDone     , FlushLeg          , none        , none                   >,
  Row < Removing::exit_pt<Cancelled>   , LegDone     , ReportingFinalTool, SayCancelled, none                   >,
  Row < FlushLeg::exit_pt<Finished>    , LegDone     , ReportingFinalTool, none        , none                   >,
  Row < ReportingFinalTool             , CommandDone , Finished          , none        , none                   >
  >;
  // clang-format on
};
using UnloadFlow = Machine_of<UnloadFlow_>;

// ================================================================ measure all
/// Measure all: each tool fetched from its pocket, measured on the sensor and
/// put back, one after another, with a report of each length and its change.
/// Cancel stops the batch once the tool under way is back in its pocket (a
/// probe under way stops too). The legs are the load's and M6's own types, so
/// the machine grows by one table, not by new copies of the legs.
/// docs/sequences.md#measure-all.
struct MeasureAllFlow_ : Flow<MeasureAllFlow_> {
  using flag_list = boost::mpl::vector2<flag::Busy, flag::Measuring>;

  using Returning = ReturnLeg<Before>;
  using Probe = ProbingLeg<OverMdi>;
  /// The spindle's tool goes back first; then the next tool, if any is left.
  struct DecidingNextTool : Decision {};
  /// LinuxCNC is told (M61) what the spindle holds after each fetch and return.
  using ReportingFetched = ReportingSpindleTool<AfterFetch>;
  using ReportingReturned = ReportingSpindleTool<AfterReturn>;

  struct ToolsLeft {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context::Batch& b = fsm.ctx->batch;
      return !b.cancel && b.done < b.tools.size();
    }
  };
  struct TakeNextTool {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      const int tool = c.batch.tools[c.batch.done];
      c.requested_tool = tool;
      const auto stored = c.tools.lengths.find(tool);
      c.batch.stored =
          stored == c.tools.lengths.end() ? std::nullopt : std::optional<double>(stored->second);
      c.tell(MessageKind::info, "measure all: tool " + std::to_string(tool) + " (" +
                                    std::to_string(c.batch.done + 1) + " of " +
                                    std::to_string(c.batch.tools.size()) + ")");
    }
  };
  struct RecordMeasured {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      const double now = *c.last_length;
      std::string line =
          "T" + std::to_string(c.requested_tool) + " " + format_length(c.config, now);
      if (c.batch.stored) {
        char change[32];
        std::snprintf(change, sizeof change, "%+.4f", now - *c.batch.stored);
        line += " (was " + format_length(c.config, *c.batch.stored) + ", " + change + ")";
      } else {
        line += " (first measurement)";
      }
      c.batch.report.push_back(line);
      ++c.batch.done;
    }
  };
  struct RecordNotMeasured {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      c.batch.report.push_back("T" + std::to_string(c.requested_tool) +
                               " not measured: " + c.probe_problem);
      ++c.batch.done;
    }
  };
  struct SayReport {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      std::string text =
          "measure all " + std::string(c.batch.cancel ? "cancelled after " : "done: ") +
          std::to_string(c.batch.done) + " of " + std::to_string(c.batch.tools.size()) + " tools";
      for (const auto& line : c.batch.report) text += "; " + line;
      c.tell(MessageKind::info, text);
    }
  };

  /// Cancel asks the batch to stop after the tool under way is put back; a
  /// probe under way stops too (its own row), and this still stops the batch.
  struct AskToStop {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->batch.cancel = true;
      fsm.ctx->tell(MessageKind::info, "measure all stops once tool " +
                                           std::to_string(fsm.ctx->requested_tool) +
                                           " is back in its pocket");
    }
  };
  /// A second region: it hears Cancel whatever the batch is doing.
  struct ListeningForCancel : msmf::state<> {};

  using initial_state = boost::mpl::vector<DecidingNextTool, ListeningForCancel>;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                               Event         Next              Action             Guard
  // +-----------------------------------+--------------+-----------------+------------------+-----------------------------------+
  Row < DecidingNextTool                  , none          , Returning       , none             , SpindleHoldsTool                  >,
  Row < DecidingNextTool                  , none          , RetrieveLeg     , TakeNextTool     , And<Not<SpindleHoldsTool>, ToolsLeft> >,
  Row < DecidingNextTool                  , none          , Finished        , SayReport        , And<Not<SpindleHoldsTool>, Not<ToolsLeft>> >,
  Row < Returning::exit_pt<Finished>      , LegDone       , ReportingReturned, none            , none                              >,
  Row < ReportingReturned                 , CommandDone   , DecidingNextTool, none             , none                              >,
  Row < RetrieveLeg::exit_pt<Finished>    , LegDone       , ReportingFetched, none             , none                              >,
  Row < ReportingFetched                  , CommandDone   , ToSensor        , none             , none                              >,
  Row < ToSensor                          , InPosition    , Probe           , none             , none                              >,
  Row < Probe::exit_pt<Finished>          , LegDone       , DecidingNextTool, RecordMeasured   , none                              >,
  Row < Probe::exit_pt<Probe::NotMeasured>, LegDone       , DecidingNextTool, RecordNotMeasured, none                              >,
  Row < ListeningForCancel                , OperatorCancel, none            , AskToStop        , none                              >
  >;
  // clang-format on
};
using MeasureAllFlow = Machine_of<MeasureAllFlow_>;

// ================================================================ verify a pocket
/// A dry run through one pocket's approach, before its geometry is trusted:
/// the way a return goes in and a fetch comes out, every move at
/// `verify_feed`, the chuck closed throughout, the run held at each waypoint
/// until Continue (nothing can be jogged meanwhile, so the next move starts
/// where the last one ended). Cancel ends the run where it stands.
/// docs/sequences.md#verify-a-pocket.
struct VerifyFlow_ : Flow<VerifyFlow_> {
  using flag_list = boost::mpl::vector2<flag::Busy, flag::Verifying>;
  static int served_tool(const Context& ctx) { return ctx.tools.spindle; }
  static int served_pocket(const Context& ctx, int) { return ctx.verify_pocket; }

  /// The waypoints, in order (plan::verify_pocket).
  plan::Route route;
  std::size_t reached = 0;  ///< the index of the waypoint moved to last

  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    route = plan::verify_pocket(ctx->config, pocket);
    reached = 0;
    ctx->record_progress("verifying pocket " + std::to_string(pocket), pocket);
  }
  /// One waypoint at a time: the run holds at each.
  struct ToWaypoint : Walking<ToWaypoint> {
    template <class Leg>
    static plan::Route route(const Context&, const Leg& leg) {
      return {leg.route.at(leg.reached)};
    }
  };
  struct StopPrompt {
    template <class Leg>
    std::string operator()(const Context& c, const Leg& leg) const {
      return "Verify pocket " + std::to_string(leg.pocket) + ", stop " +
             std::to_string(leg.reached + 1) + " of " + std::to_string(leg.route.size() - 1) +
             ": " + leg.where(c) + ". Look at the clearance, then press Continue (Cancel " +
             "stops here)";
    }
  };
  struct AtWaypoint : HoldingForOperator<StopPrompt> {};

  /// "side of pocket 3 (X=120.000 Y=40.000 Z=-50.000)": what the spindle
  /// reached last, and where that is (the axes known), as --plan writes it.
  std::string where(const Context& c) const {
    std::string words = route.at(reached).label + " (";
    const char* names[] = {"X", "Y", "Z"};
    const double values[] = {c.position.x, c.position.y, c.position.z};
    for (int axis = 0; axis < 3; ++axis) {
      if (!(c.known_axes & (1u << axis))) continue;
      char coordinate[48];
      std::snprintf(coordinate, sizeof coordinate, "%s%s=%.3f", words.back() == '(' ? "" : " ",
                    names[axis], values[axis]);
      words += coordinate;
    }
    return words + ")";
  }
  /// Below the pocket's clearance height, where only its own approach is safe.
  bool inside_rack(const Context& c) const {
    return (c.known_axes & axis_z) &&
           c.position.z < pocket_waypoints(c.config, pocket).above_clearance.z - 1e-9;
  }

  struct LastWaypoint {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.reached + 1 >= fsm.route.size();
    }
  };
  struct Onward {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      ++fsm.reached;
    }
  };
  struct SayVerified {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      char feed[32];
      std::snprintf(feed, sizeof feed, "F%g", fsm.ctx->config.dry_run_feed());
      fsm.ctx->tell(MessageKind::info, "verify of pocket " + std::to_string(fsm.pocket) +
                                           " done: " + std::to_string(fsm.route.size()) +
                                           " moves through its approach at " + feed + ", back at " +
                                           fsm.route.back().label);
    }
  };
  struct SayStoppedHere {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      std::string text =
          "verify of pocket " + std::to_string(fsm.pocket) +
          " cancelled by the operator; the spindle stays where it stopped: " + fsm.where(c);
      if (fsm.inside_rack(c)) {
        text +=
            ", below the rack's clearance: jog it out the way it came in before the next change";
      }
      fsm.ctx->tell(MessageKind::info, text);
    }
  };

  using initial_state = OpeningCover;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start          Event             Next        Action                Guard
  // +--------------+-----------------+-----------+---------------------+----------------------+
  Row < OpeningCover , SensorReport    , ToWaypoint, none                , CoverOpen            >,
  Row < OpeningCover , TimerElapsed    , Halted    , FaultCoverDidNotOpen, CoverHasOpenedSensor >,
  Row < ToWaypoint   , InPosition      , AtWaypoint, none                , Not<LastWaypoint>    >,
  Row < ToWaypoint   , InPosition      , Finished  , SayVerified         , LastWaypoint         >,
  Row < AtWaypoint   , OperatorContinue, ToWaypoint, Onward              , none                 >,
  Row < AtWaypoint   , OperatorCancel  , Cancelled , SayStoppedHere      , none                 >
  >;
  // clang-format on
};
using VerifyFlow = Machine_of<VerifyFlow_>;

// ================================================================ chuck atoms
/// What the state file says is under way while a release holds the chuck open.
inline constexpr const char* kChuckHeldOpen = "the chuck held open (released from G-code)";

/// A chuck atom from G-code (nc_files/fixed_atc_probe_chuck_*.ngc), with
/// the interlocks of the legs: a release waits until the chuck may open
/// (air, the spindle at a standstill), gives the chuck `chuck_seconds`, and
/// the drawbar must then read open; the chuck stays open until a clamp, which
/// gives it `chuck_seconds` again and must read closed. What the spindle
/// holds stays as recorded (docs/sequences.md#chuck-atoms).
struct ChuckFlow_ : Flow<ChuckFlow_> {
  using flag_list = boost::mpl::vector2<flag::Busy, flag::Chucking>;
  static int served_tool(const Context& ctx) { return ctx.tools.spindle; }
  static int served_pocket(const Context&, int) { return 0; }

  struct Releases {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.ctx->chuck_action == ChuckRequest::Action::release;
    }
  };
  struct DecidingWhich : Decision {};
  struct WaitingToOpen : WaitingToOpenChuck<ForRelease> {};
  struct Opening : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      fsm.ctx->open_chuck();
      fsm.ctx->wait(fsm.ctx->config.chuck_seconds, "releasing the chuck (G-code)");
    }
  };
  struct Closing : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      fsm.ctx->close_chuck();
      fsm.ctx->wait(fsm.ctx->config.chuck_seconds, "clamping the chuck (G-code)");
    }
  };
  /// After a clamp, `tool-present` (where wired) must agree with the record:
  /// what a hand did at the spindle meanwhile is checked before the program
  /// goes on.
  struct SpindleAsRecorded : SensorGuard<SpindleAsRecorded> {
    template <class Leg>
    static bool holds(const Context& c, const Leg&) {
      return c.spindle_reads(c.tools.spindle != 0);
    }
    static std::string awaited(const Context& c) {
      return c.tools.spindle != 0 ? "waiting for tool-present to see tool " +
                                        std::to_string(c.tools.spindle) + " after the clamp"
                                  : std::string(
                                        "waiting for tool-present to see the spindle "
                                        "empty after the clamp");
    }
  };
  struct CheckingSpindle : AwaitingSensor<SpindleAsRecorded> {};
  struct SpindleNotAsRecorded {
    template <class Leg>
    static std::string text(const Context& c, const Leg&) {
      const int held = c.tools.spindle;
      return held != 0 ? "after the clamp from G-code tool-present reads the spindle empty (off), "
                         "but tool " +
                             std::to_string(held) + " is recorded in it"
                       : std::string(
                             "after the clamp from G-code tool-present reads a tool (on), "
                             "but the spindle is recorded empty");
    }
  };
  using FaultSpindleNotAsRecorded = FaultSaying<SpindleNotAsRecorded, true>;
  struct SayReleased {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const int held = fsm.ctx->tools.spindle;
      fsm.ctx->tell(MessageKind::info,
                    held == 0 ? std::string("chuck released (G-code); clamp it before other work")
                              : "chuck released at loading (G-code); tool " + std::to_string(held) +
                                    " stays recorded in the spindle: clamp it, then unload it "
                                    "with the panel if you took it out");
    }
  };

  using initial_state = DecidingWhich;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                  Event          Next                   Action                                Guard
  // +----------------------+--------------+----------------------+-------------------------------------+---------------+
  Row < DecidingWhich        , none         , WaitingToOpen        , none                                , Releases      >,
  Row < DecidingWhich        , none         , Closing              , none                                , Not<Releases> >,
  Row < WaitingToOpen        , SensorReport , Opening              , none                                , ChuckMayOpen  >,
  Row < WaitingToOpen        , TimerElapsed , Halted               , FaultChuckMayNotOpen<ForRelease>    , none          >,
  Row < Opening              , TimerElapsed , CheckingDrawbarOpen  , none                                , none          >,
  Row < CheckingDrawbarOpen  , SensorReport , Finished             , SayReleased                         , DrawbarOpen   >,
  Row < CheckingDrawbarOpen  , TimerElapsed , Halted               , FaultDrawbarStayedClosed<ForRelease>, none          >,
  Row < Closing              , TimerElapsed , CheckingDrawbarClosed, none                                , none          >,
  Row < CheckingDrawbarClosed, SensorReport , CheckingSpindle      , none                                , DrawbarClosed >,
  Row < CheckingDrawbarClosed, TimerElapsed , Halted               , FaultDrawbarStayedOpen<ForClamp>    , none          >,
  Row < CheckingSpindle      , SensorReport , Finished             , none                                , SpindleAsRecorded >,
  Row < CheckingSpindle      , TimerElapsed , Halted               , FaultSpindleNotAsRecorded           , none          >
  >;
  // clang-format on
};
using ChuckFlow = Machine_of<ChuckFlow_>;

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

inline std::optional<std::string> why_not(const Context& c, const ToolChange& e) {
  return why_not_change(c, e.tool);
}
inline std::optional<std::string> why_not(const Context& c, const LoadRequest& e) {
  return why_not_load(c, e.tool, e.pocket);
}
inline std::optional<std::string> why_not(const Context& c, const MeasureRequest& e) {
  return why_not_measure(c, e.tools);
}
inline std::optional<std::string> why_not(const Context& c, const UnloadRequest& e) {
  return why_not_unload(c, e.tool);
}
inline std::optional<std::string> why_not(const Context& c, const VerifyRequest& e) {
  return why_not_verify(c, e.pocket);
}
inline std::optional<std::string> why_not(const Context& c, const ChuckRequest& e) {
  return why_not_chuck(c, e);
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
      return "the changer is busy verifying pocket " + std::to_string(fsm.ctx->verify_pocket);
    if (fsm.template is_flag_active<flag::Chucking>()) return "the changer is busy with the chuck";
    return "the changer is busy changing to tool " + tool;
  }
};
/// The requests, refused for one reason: a state's internal rows.
template <class Because>
using RefusesRequests = boost::mpl::vector<msmf::Internal<ToolChange, Refuse<Because>, none>,
                                           msmf::Internal<LoadRequest, Refuse<Because>, none>,
                                           msmf::Internal<UnloadRequest, Refuse<Because>, none>,
                                           msmf::Internal<MeasureRequest, Refuse<Because>, none>,
                                           msmf::Internal<VerifyRequest, Refuse<Because>, none>,
                                           msmf::Internal<ChuckRequest, Refuse<Because>, none>>;

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
    c.end_sequence();
    c.tell(MessageKind::info, "verify of pocket " + std::to_string(c.verify_pocket) + " stopped (" +
                                  why +
                                  "); nothing was recorded. The spindle may be in the rack: jog "
                                  "it out the way it came in before the next change");
  }
};
struct Operating_ : Flow<Operating_> {
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
  /// Before the changer takes work (at start, after a fault, after every
  /// flow, and whenever a sensor changes while idle) the wired sensors must
  /// agree with the tool state, or come to within sensor_timeout_seconds.
  struct ComparingSensors : AwaitingSensor<SensorsAgree, SensorOrCoverTimeout> {
    using flag_list = boost::mpl::vector2<flag::Idle, flag::AwaitsSensor>;
    using internal_transition_table = RefusesRequests<BecauseSensorsDisagree>;
    template <class Event, class Fsm>
    void on_entry(const Event& e, Fsm& fsm) {
      fsm.ctx->close_cover();
      AwaitingSensor::on_entry(e, fsm);
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
      Context& c = *fsm.ctx;
      if constexpr (std::is_same_v<Request, ToolChange>) {
        c.fetch_follows_return = c.tools.pocket_holding(e.tool).has_value();
      } else {
        c.fetch_follows_return = std::is_same_v<Request, UnloadRequest>;
      }
      if constexpr (std::is_same_v<Request, VerifyRequest>) {
        fsm.ctx->requested_tool = fsm.ctx->tools.spindle;
        fsm.ctx->verify_pocket = e.pocket;
      } else if constexpr (std::is_same_v<Request, ChuckRequest>) {
        fsm.ctx->requested_tool = fsm.ctx->tools.spindle;
        fsm.ctx->chuck_action = e.action;
      } else if constexpr (!std::is_same_v<Request, MeasureRequest>) {
        fsm.ctx->requested_tool = e.tool;
      }
      if constexpr (std::is_same_v<Request, LoadRequest>) {
        fsm.ctx->load_pocket = choose_load_pocket(*fsm.ctx, e.tool, e.pocket).pocket;
      }
      if constexpr (std::is_same_v<Request, MeasureRequest>) {
        std::string skipped;
        fsm.ctx->batch = {measurable_tools(*fsm.ctx, e.tools, skipped), 0, false, {}, {}};
        if (!skipped.empty()) {
          fsm.ctx->tell(MessageKind::info, "measure all skips what is not in the rack: " + skipped);
        }
      }
      fsm.ctx->begin_sequence(request_name(e));
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
  Row < Idle                           , ChuckRequest  , ChuckFlow , TakeRequest               , Not<Refused>                      >
  >;
  /// Comparing the sensors before work, and where each flow ends.
  using around_the_flows = boost::mpl::vector<
  //    Start                              Event          Next              Action              Guard
  // +----------------------------------+--------------+-----------------+-------------------+--------------------+
  Row < ComparingSensors                 , SensorReport , Idle            , none              , SensorsAgree       >,
  Row < ComparingSensors                 , TimerElapsed , Failed          , SaySensorsDisagree, none               >,
  Row < Idle                             , SensorReport , ComparingSensors, none              , Not<SensorsAgree>  >,
  Row < ChangeFlow::exit_pt<Finished>    , LegDone      , ComparingSensors, AnswerDone        , none               >,
  Row < ChangeFlow::exit_pt<Failed>      , FlowFailed   , Failed          , none              , none               >,
  Row < ChangeFlow::exit_pt<Cancelled>   , LegDone      , ComparingSensors, StopProgram       , none               >,
  Row < LoadFlow::exit_pt<Finished>      , LegDone      , ComparingSensors, AnswerDone        , none               >,
  Row < UnloadFlow::exit_pt<Finished>    , LegDone      , ComparingSensors, AnswerDone        , none               >,
  Row < MeasureAllFlow::exit_pt<Finished>, LegDone      , ComparingSensors, AnswerDone        , none               >,
  Row < VerifyFlow::exit_pt<Finished>    , LegDone      , ComparingSensors, AnswerDone        , none               >,
  Row < VerifyFlow::exit_pt<Cancelled>   , LegDone      , ComparingSensors, AnswerDone        , none               >,
  Row < VerifyFlow                       , Abort        , ComparingSensors, StopDryRun        , none               >,
  Row < ChuckFlow::exit_pt<Finished>     , LegDone      , ComparingSensors, AnswerChuckDone   , none               >
  >;
  using transition_table = boost::mpl::joint_view<requests, around_the_flows>;
  // clang-format on
};
using Operating = Machine_of<Operating_>;

// ================================================================ top
struct Machine_ : msmf::state_machine_def<Machine_> {
  explicit Machine_(Context* context) : ctx(context) {}
  Context* ctx;

  struct MachineNotReady : msmf::state<> {
    using flag_list = boost::mpl::vector1<flag::NotReady>;
    using internal_transition_table = RefusesRequests<BecauseNotReady>;
    /// A chuck a release left open closes with the machine, as a spring
    /// drawbar does when its air goes; whatever a hand did at the spindle
    /// meanwhile, the operator confirms once the machine is back.
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      Context& c = *fsm.ctx;
      if (!c.chuck_open) return;
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
    void on_entry(const Event&, Fsm& fsm) {
      Context& c = *fsm.ctx;
      c.close_chuck();
      // An executor still waiting for its next step aborts the program on this.
      c.publish(failure_step(c.fault_reason));
      c.tell(MessageKind::error, "fault: " + c.fault_reason + "; " + c.whereabouts() +
                                     ". Check the spindle and the rack, then clear the fault.");
    }
  };

  struct IsBusy {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.template is_flag_active<flag::Busy>();
    }
  };
  /// A dry run (verify): the chuck stays closed, so the tools are where they were.
  struct DryRun {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.template is_flag_active<flag::Verifying>();
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
      if constexpr (std::is_same_v<Event, Abort> || std::is_same_v<Event, InternalError>) {
        c.fault_reason = e.reason;
      }
      if constexpr (std::is_same_v<Event, NotReady>) {
        c.fault_reason = "the machine went off, lost homing or entered estop during a sequence";
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
      c.fault_reason = e.reason;
      if (e.uncertain) {
        c.tools.uncertain = true;
        c.ports.save(c.tools);
      }
    }
  };
  struct RecordUnsafeStep {
    template <class Fsm, class Source, class Target>
    void operator()(const UnsafeStep& e, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->fault_reason = e.reason;
    }
  };
  struct SayUncertain {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const auto& cut_off = fsm.ctx->tools.in_progress;
      fsm.ctx->fault_reason =
          cut_off && cut_off->step == kChuckHeldOpen
              ? "the chuck was held open by G-code when the machine went off or the component "
                "stopped (the saved tool state is uncertain)"
              : "the last sequence was cut off (the saved tool state is uncertain)";
      // What the wired sensors read helps the operator answer.
      for (const auto& disagreement : fsm.ctx->disagreements()) {
        fsm.ctx->fault_reason += "; " + disagreement;
      }
    }
  };
  /// The operator says what the spindle holds and, for a sequence that was
  /// cut off at a pocket, whether that pocket holds its tool. Nothing moves.
  struct ClearTheFault {
    template <class Fsm, class Source, class Target>
    void operator()(const ClearFault& e, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      const int answered =
          c.tools.in_progress && e.pocket_holds_tool ? c.tools.in_progress->pocket : 0;
      c.tools.confirm(e.spindle_tool, e.pocket_holds_tool);
      // The operator has looked at the rack: every pocket sensor not
      // contradicted by an answer is taken at its word (only while the
      // machine is on: its sensors may have no power otherwise).
      std::string adopted;
      if (c.machine_ready) {
        for (const auto& change :
             adopt_pocket_sensors(c.config.sensors, c.sensors, answered, c.tools)) {
          adopted += change + "; ";
        }
      }
      c.fault_reason.clear();
      c.ports.save(c.tools);
      c.tell(MessageKind::info, "fault cleared; " + adopted + c.whereabouts());
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
  Row < Faulted                    , ClearFault    , Operating       , ClearTheFault   , MachineIsReady        >,
  Row < Faulted                    , ClearFault    , MachineNotReady , ClearTheFault   , Not<MachineIsReady>   >,
  Row < Faulted                    , Ready         , none            , none            , none                  >,
  Row < Faulted                    , NotReady      , none            , none            , none                  >,
  Row < Faulted                    , Abort         , none            , none            , none                  >,
  Row < Faulted                    , InternalError , none            , none            , none                  >
  >;
  using transition_table = boost::mpl::joint_view<until_a_fault, after_a_fault>;
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
  using internal_transition_table =
      boost::mpl::joint_view<RefusesRequests<BecauseBusy>, nothing_else_answers>;
  // clang-format on

  template <class Fsm, class Event>
  void no_transition(const Event& e, Fsm& fsm, int state) {
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
