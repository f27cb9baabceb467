#pragma once

// The dry run through one pocket's approach.

#include "../legs/cover.hpp"
#include "verify.hpp"

namespace fatc::machine {

// ================================================================ verify a pocket
/// A dry run through one pocket's approach, before its geometry is trusted:
/// the way a return goes in and a fetch comes out, every move at
/// `verify_feed`, the chuck closed throughout, the run held at each waypoint
/// until Continue (nothing can be jogged meanwhile, so the next move starts
/// where the last one ended). Cancel ends the run where it stands.
/// docs/sequences.md#verify-a-pocket.
struct VerifyFlow_ : Flow<VerifyFlow_> {
  static int served_tool(const Context& ctx) { return ctx.tools.spindle; }

  /// The waypoints, in order (plan::verify_pocket).
  plan::Route route;
  std::size_t reached = 0;  ///< the index of the waypoint moved to last

  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    if constexpr (std::is_same_v<Event, VerifyRequest>) pocket = e.pocket;
    route = plan::verify_pocket(ctx->config, pocket);
    reached = 0;
    ctx->record_progress("verifying pocket " + std::to_string(pocket), pocket);
  }
  /// One waypoint at a time: the run holds at each.
  struct ToWaypoint : Walking<ToWaypoint> {
    template <class Leg>
    static plan::Route route(const Context& c, const Leg& leg) {
      return plan::walked(c.config, {leg.route.at(leg.reached)}, c.standing());
    }
  };
  struct StopPrompt {
    template <class Leg>
    Prompt operator()(const Context& c, const Leg& leg) const {
      Prompt stop;
      stop.kind = Prompt::Kind::verify_stop;
      stop.tool = c.tools.spindle;
      stop.pocket = leg.pocket;
      stop.stop = static_cast<int>(leg.reached) + 1;
      stop.stops = static_cast<int>(leg.route.size()) - 1;
      stop.waypoint = leg.route.at(leg.reached).label;
      stop.at = c.motion.position;
      stop.known_axes = c.motion.known_axes;
      return stop;
    }
  };
  struct AtWaypoint : HoldingForOperator<StopPrompt> {};

  /// "side of pocket 3 (X=120.000 Y=40.000 Z=-50.000)": what the spindle
  /// reached last, and where that is.
  std::string where(const Context& c) const {
    return waypoint_words(route.at(reached).label, c.motion.position, c.motion.known_axes);
  }
  /// Below the pocket's clearance height, where only its own approach is safe.
  bool inside_rack(const Context& c) const {
    return (c.motion.known_axes & axis_z) &&
           c.motion.position.z < pocket_waypoints(c.config, pocket).above_clearance.z - 1e-9;
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

}  // namespace fatc::machine
