#pragma once

// M6's start: the spindle runs down. docs/sequences.md#m6.

#include "sensors.hpp"

namespace fatc::machine {

// ================================================================ the spindle runs down
/// M6 stops the spindle (M5) before its executor runs: until it stands the
/// spindle rises to safe Z and crosses at safe Z toward the first pocket
/// (plan::while_spindle_stops), and nothing goes lower and the chuck stays
/// closed. A spindle that does not stand within spindle_stop_timeout_seconds
/// of the end of those moves fails the change. docs/sequences.md#m6.
struct SpindleRunDown_ : Flow<SpindleRunDown_> {
  /// The route M6's first leg walks: the return of the spindle's rack tool,
  /// else the fetch of the requested one. None for a handover at `loading`,
  /// where the operator's hand meets the spindle once it stands.
  static plan::Route first_leg_route(const Context& c) {
    if (c.tools.spindle != 0) {
      const auto pocket = c.return_pocket(c.tools.spindle);
      return pocket ? plan::return_to_approach(c.config, *pocket) : plan::Route{};
    }
    const auto pocket = c.tools.pocket_holding(c.requested_tool);
    if (c.requested_tool == 0 || !pocket) return {};
    return plan::fetch_to_above_chuck(c.config, *pocket, false);
  }
  /// Up to safe Z and across toward the first leg's pocket while the spindle
  /// runs down (plan::while_spindle_stops); the leg then starts from there.
  struct MovingWhileRunningDown : Walking<MovingWhileRunningDown> {
    template <class Leg>
    static plan::Route route(const Context& c, const Leg&) {
      return plan::while_spindle_stops(c.config, first_leg_route(c));
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
      const Context& c = *fsm.ctx;
      fsm.ctx->fault_reason = "the spindle did not stop within spindle_stop_timeout_seconds";
      if (c.config.sensors.zero_speed && !c.sensors.zero_speed) {
        fsm.ctx->fault_reason += " (zero-speed off)";
      }
    }
  };

  struct DecidingToMove : Decision {};
  using initial_state = DecidingToMove;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                    Event          Next                     Action                 Guard
  // +------------------------+--------------+------------------------+----------------------+------------------------------+
  Row < DecidingToMove         , none         , MovingWhileRunningDown , none                 , MayMoveWhileRunningDown      >,
  Row < DecidingToMove         , none         , WaitingForSpindle      , none                 , Not<MayMoveWhileRunningDown> >,
  Row < MovingWhileRunningDown , InPosition   , WaitingForSpindle      , none                 , none                         >,
  Row < WaitingForSpindle      , SensorReport , Finished               , none                 , SpindleIsStopped             >,
  Row < WaitingForSpindle      , TimerElapsed , Failed                 , SaySpindleDidNotStop , none                         >
  >;
  // clang-format on
};
using SpindleRunDown = Machine_of<SpindleRunDown_>;

}  // namespace fatc::machine
