#pragma once

// Returning the tool in the spindle to a pocket. docs/sequences.md#return.

#include "screwing_off.hpp"

namespace fatc::machine {

// ================================================================ return
/// The return of whatever the spindle held before: to its own pocket.
struct Before {
  template <class Parent>
  static int pocket(const Context& ctx, int tool, const Parent&) {
    return ctx.return_pocket(tool).value_or(0);
  }
};
/// The return of the tool the load flow is about: to the pocket the load chose.
struct PutAway {
  template <class Parent>
  static int pocket(const Context&, int, const Parent& load) {
    return load.load_pocket;
  }
};

/// Puts the tool in the spindle into a pocket (docs/sequences.md#return):
/// `Which` says which one (Before: its own; PutAway: the one the load chose).
template <class Which>
struct ReturnLeg_ : Flow<ReturnLeg_<Which>> {
  static int served_tool(const Context& ctx) { return ctx.tools.spindle; }
  template <class Parent>
  static int served_pocket(const Context& ctx, int tool, const Parent& parent) {
    return Which::pocket(ctx, tool, parent);
  }
  bool fetch_follows = false;  ///< the flow fetches a tool next (Flow::fetch_follows_return)
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow<ReturnLeg_<Which>>::on_entry(e, parent);
    fetch_follows = Parent::fetch_follows_return(*this->ctx);
    this->ctx->record_progress("returning tool " + std::to_string(this->tool) + " to pocket " +
                                   std::to_string(this->pocket),
                               this->pocket);
  }

  // The phases; plan/routes.hpp says where each goes.
  struct ToApproach : GoingAtPocket<plan::return_to_approach> {};
  struct IntoPocket : GoingAtPocket<plan::return_into_pocket> {};
  struct WaitingToOpen : WaitingToOpenChuck<AtPocket> {};
  struct ReleasingTool : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      fsm.ctx->open_chuck();
      fsm.ctx->wait(fsm.ctx->config.chuck_seconds, "releasing tool " + std::to_string(fsm.tool) +
                                                       " into pocket " +
                                                       std::to_string(fsm.pocket));
    }
  };
  struct UpFromTool : GoingAtPocket<plan::return_up_from_tool> {};
  /// The spindle lifted with the chuck open: the tool must have stayed behind.
  struct CheckingToolLeft : AwaitingSensor<SpindleReadsEmpty> {};
  struct Away : AwayFromPocket {};

  /// The tool came up with the spindle: it is there, as far as anyone knows.
  struct FaultToolStillInSpindle {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->record_in_spindle(fsm.tool);
      fsm.ctx->fail_check("tool " + std::to_string(fsm.tool) +
                              " still in the spindle after the chuck opened at pocket " +
                              std::to_string(fsm.pocket) + " and the spindle lifted (" +
                              Sensors::tool_pin() + " on)",
                          true);
    }
  };

  /// A collet-nut changer screws the nut off instead (`chuck.kind`).
  struct Starting : Decision {};
  using initial_state = Starting;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                  Event          Next                   Action                               Guard
  // +----------------------+--------------+----------------------+------------------------------------+-----------------------+
  Row < Starting             , none         , OpeningCover         , none                               , Not<ScrewsNuts>       >,
  Row < Starting             , none         , ScrewingOff          , none                               , ScrewsNuts            >,
  Row < ScrewingOff::exit_pt<Finished>, LegDone, Finished          , none                               , none                  >,
  Row < OpeningCover         , SensorReport , ToApproach           , none                               , CoverOpen             >,
  Row < OpeningCover         , TimerElapsed , Halted               , FaultCoverDidNotOpen               , CoverHasOpenedSensor  >,
  Row < ToApproach           , InPosition   , IntoPocket           , none                               , PocketReadsEmpty      >,
  Row < ToApproach           , InPosition   , Halted               , FaultPocketFull                    , Not<PocketReadsEmpty> >,
  Row < IntoPocket           , InPosition   , WaitingToOpen        , none                               , none                  >,
  Row < WaitingToOpen        , SensorReport , ReleasingTool        , none                               , ChuckMayOpen          >,
  Row < WaitingToOpen        , TimerElapsed , Halted               , FaultChuckMayNotOpen<AtPocket>     , none                  >,
  Row < ReleasingTool        , TimerElapsed , CheckingDrawbarOpen  , none                               , none                  >,
  Row < CheckingDrawbarOpen  , SensorReport , UpFromTool           , RecordToolInPocket                 , DrawbarOpen           >,
  Row < CheckingDrawbarOpen  , TimerElapsed , Halted               , FaultDrawbarStayedClosed<AtPocket> , none                  >,
  Row < UpFromTool           , InPosition   , CheckingToolLeft     , none                               , none                  >,
  Row < CheckingToolLeft     , SensorReport , CheckingDrawbarClosed, CloseChuck                         , SpindleReadsEmpty     >,
  Row < CheckingToolLeft     , TimerElapsed , Halted               , FaultToolStillInSpindle            , none                  >,
  Row < CheckingDrawbarClosed, SensorReport , Away                 , none                               , DrawbarClosed         >,
  Row < CheckingDrawbarClosed, TimerElapsed , Halted               , FaultDrawbarStayedOpen<AbovePocket>, none                  >,
  Row < Away                 , InPosition   , Finished             , none                               , none                  >
  >;
  // clang-format on
};
template <class Which>
using ReturnLeg = Machine_of<ReturnLeg_<Which>>;

}  // namespace fatc::machine
