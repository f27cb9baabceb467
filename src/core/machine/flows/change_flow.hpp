#pragma once

// M6: the change flow.

#include <boost/mpl/vector/vector30.hpp>

#include "../legs/handover.hpp"
#include "../legs/probing_leg.hpp"
#include "../legs/retrieve_leg.hpp"
#include "../legs/return_leg.hpp"
#include "change.hpp"

namespace fatc::machine {

// ================================================================ change (M6)
/// M6: while the spindle runs down (M5 comes before the executor runs) rise
/// to safe Z and cross at it toward the first pocket, nothing lower and the
/// chuck closed, until it stands (within spindle_stop_timeout_seconds of the
/// end of those moves); then empty the spindle (its tool back to its pocket,
/// or handed out), fetch the requested tool (from its pocket, or handed in),
/// and measure it if its measuring rule asks (`tools`, `probe_after_change`). docs/sequences.md#m6.
struct ChangeFlow_ : Flow<ChangeFlow_> {
  /// The requested tool is in the rack: a fetch follows the return.
  static bool fetch_follows_return(const Context& c) {
    return c.tools.pocket_holding(c.request.tool).has_value();
  }

  /// M6's first leg: the return of the spindle's rack tool, else the fetch
  /// of the requested one. None for a handover at `loading`, where the
  /// operator's hand meets the spindle once it stands.
  static std::optional<plan::FirstLeg> first_leg(const Context& c) {
    if (c.tools.spindle != 0) {
      const auto pocket = c.return_pocket(c.tools.spindle);
      if (!pocket) return std::nullopt;
      return plan::FirstLeg{true, *pocket};
    }
    const auto pocket = c.tools.pocket_holding(c.request.tool);
    if (c.request.tool == 0 || !pocket) return std::nullopt;
    return plan::FirstLeg{false, *pocket};
  }
  /// Up to safe Z and across toward the first leg's pocket while the spindle
  /// runs down (plan::while_spindle_stops); the leg then starts from there.
  struct MovingWhileRunningDown : Walking<MovingWhileRunningDown> {
    template <class Flow>
    static plan::Route route(const Context& c, const Flow&) {
      const auto first = first_leg(c);
      if (!first) return {};
      return plan::phase(c.config, c.standing(), plan::while_spindle_stops_before, *first);
    }
  };
  /// The spindle still turns, and part of the way needs no standstill.
  struct MayMoveWhileRunningDown {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      return !c.spindle_at_standstill() && !MovingWhileRunningDown::route(c, fsm).empty();
    }
  };
  /// LinuxCNC's spindle off and, where wired, zero speed.
  struct WaitingForSpindle
      : AwaitingSensor<SpindleIsStopped, SpindleStopTimeout, flag::AwaitsSpindle> {};
  struct SaySpindleDidNotStop {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      std::string why = "the spindle did not stop within spindle_stop_timeout_seconds";
      if (const std::string turning = fsm.ctx->sensors.turning_words(); !turning.empty()) {
        why += " (" + turning + ")";
      }
      *fsm.failure = std::move(why);
    }
  };
  /// The requested tool's measuring rule asks for it (`tools`, `probe_after_change`).
  struct ProbesAfterChange {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      return c.measuring(c.request.tool).after_change;
    }
  };

  using Returning = ReturnLeg<Before>;
  struct DecidingHowToEmpty : Decision {};
  /// The spindle is empty: how does the requested tool get into it?
  struct DecidingHowToFetch : Decision {};
  struct DecidingToMeasure : Decision {};
  struct DecidingWhileRunningDown : Decision {};
  using initial_state = DecidingWhileRunningDown;
  // One table for the whole change: 21 rows, one more than boost::mpl::vector
  // takes, hence vector21.
  // clang-format off
  using transition_table = boost::mpl::vector21<
  //    Start                            Event          Next                     Action                 Guard
  // +--------------------------------+--------------+------------------------+----------------------+------------------------------+
  Row < DecidingWhileRunningDown       , none         , MovingWhileRunningDown , none                 , MayMoveWhileRunningDown      >,
  Row < DecidingWhileRunningDown       , none         , WaitingForSpindle      , none                 , Not<MayMoveWhileRunningDown> >,
  Row < MovingWhileRunningDown         , InPosition   , WaitingForSpindle      , none                 , none                         >,
  Row < WaitingForSpindle              , SensorReport , DecidingHowToEmpty     , none                 , SpindleIsStopped             >,
  Row < WaitingForSpindle              , TimerElapsed , Failed                 , SaySpindleDidNotStop , none                         >,
  Row < DecidingHowToEmpty             , none         , Returning              , none                 , SpindleHoldsRackTool         >,
  Row < DecidingHowToEmpty             , none         , HandOutLeg             , none                 , SpindleHoldsManualTool       >,
  Row < DecidingHowToEmpty             , none         , DecidingHowToFetch     , none                 , Not<SpindleHoldsTool>        >,
  Row < Returning::exit_pt<Finished>   , LegDone      , DecidingHowToFetch     , none                 , none                         >,
  Row < HandOutLeg::exit_pt<Finished>  , LegDone      , DecidingHowToFetch     , none                 , none                         >,
  Row < HandOutLeg::exit_pt<Cancelled> , LegDone      , Cancelled              , none                 , none                         >,
  Row < DecidingHowToFetch             , none         , RetrieveLeg            , none                 , RequestedRackTool            >,
  Row < DecidingHowToFetch             , none         , HandInLeg              , none                 , RequestedManualTool          >,
  Row < DecidingHowToFetch             , none         , Finished               , none                 , Not<ToolRequested>           >,
  Row < RetrieveLeg::exit_pt<Finished> , LegDone      , DecidingToMeasure      , none                 , none                         >,
  Row < HandInLeg::exit_pt<Finished>   , LegDone      , DecidingToMeasure      , none                 , none                         >,
  Row < HandInLeg::exit_pt<Cancelled>  , LegDone      , Cancelled              , none                 , none                         >,
  Row < DecidingToMeasure              , none         , MeasureLeg             , none                 , ProbesAfterChange            >,
  Row < DecidingToMeasure              , none         , Finished               , none                 , Not<ProbesAfterChange>       >,
  Row < MeasureLeg::exit_pt<Finished>  , LegDone      , Finished               , none                 , none                         >,
  Row < MeasureLeg::exit_pt<Failed>    , FlowFailed   , Failed                 , none                 , none                         >
  >;
  // clang-format on
};

}  // namespace fatc::machine
