#pragma once

// A sequence flown in the air.

#include "../legs/cover.hpp"
#include "air_run.hpp"

namespace fatc::machine {

// ================================================================ an air run
/// A sequence flown above the rack before its first real change: the route
/// plan_air_run made of it (every move in the rack raised, at the operator's
/// feed, the chuck closed throughout, nothing taken, handed or measured),
/// walked in one go. The tools stay where they were: no save but the
/// sequence's own record. LinuxCNC's Stop or the machine going off ends it
/// where it stands (StopDryRun). docs/operating.md#a-change-in-the-air.
struct AirRunFlow_ : Flow<AirRunFlow_> {
  static int served_tool(const Context& ctx) { return ctx.tools.spindle; }

  std::string name;
  std::vector<Step> route;

  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    if constexpr (std::is_same_v<Event, AirRunRequest>) {
      name = e.name;
      route = e.route;
    }
  }
  struct Flying : Walking<Flying> {
    template <class Leg>
    static plan::Route route(const Context& c, const Leg& leg) {
      return plan::walked(c.config, leg.route, c.standing());
    }
  };
  struct SayFlown {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->tell(MessageKind::info, fsm.name + " done: " + std::to_string(fsm.route.size()) +
                                           " moves, nothing taken or recorded");
    }
  };

  using initial_state = OpeningCover;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start          Event          Next      Action                Guard
  // +--------------+--------------+---------+---------------------+----------------------+
  Row < OpeningCover , SensorReport , Flying  , none                , CoverOpen            >,
  Row < OpeningCover , TimerElapsed , Halted  , FaultCoverDidNotOpen, CoverHasOpenedSensor >,
  Row < Flying       , InPosition   , Finished, SayFlown            , none                 >
  >;
  // clang-format on
};

}  // namespace fatc::machine
