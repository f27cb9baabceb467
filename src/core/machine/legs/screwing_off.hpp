#pragma once

// A collet nut screwed off into its pocket. docs/sequences.md#collet-nuts.

#include <boost/mpl/vector/vector30.hpp>

#include "returning.hpp"
#include "screwing.hpp"

namespace fatc::machine {

// ================================================================ screwing off
/// The return of a collet-nut changer (`chuck.kind` "collet_nut"): the
/// spindle's tool, its nut held by pocket `Parent::pocket`, screwed off in
/// reverse while the spindle plunges to the engage Z and rises; the
/// recognition sensor (where given) must then see no nut at zone 1, else it
/// is unscrewed once more, then the changer faults with the figures.
struct ScrewingOff_ : Flow<ScrewingOff_> {
  static int served_tool(const Context& ctx) { return ctx.tools.spindle; }
  template <class Parent>
  static int served_pocket(const Context&, int, const Parent& leg) {
    return leg.pocket;
  }
  int retries = 0;            ///< unscrewed once more
  bool fetch_follows = false;  ///< as the return leg it serves says
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& leg) {
    Flow::on_entry(e, leg);
    retries = 0;
    fetch_follows = leg.fetch_follows;
  }

  // The phases; plan/routes.hpp says where each goes.
  struct ToSpinOff : GoingAtPocket<plan::nut_to_spin_off> {};
  struct BackToSpinOff : GoingAtPocket<plan::nut_back_to_spin_off> {};
  struct StartingReverse : TurningSpindle<Reverse> {};
  struct ComingUpToSpeed : RampingSpindle<AtSpeed> {};
  struct Unscrewing : GoingAtPocket<plan::nut_screw_off> {};
  struct StoppingSpindle : TurningSpindle<Stop> {};
  struct RunningDown : RampingSpindle<Standing> {};
  struct ToZone1 : GoingAtPocket<plan::nut_to_zone_1> {};
  /// The beam at zone 1 must be clear: the nut stayed in the pocket.
  struct LookingForNut : AwaitingSensor<BeamReads<false>> {};
  struct Away : AwayFromPocket {};

  using FaultNotAtSpeed = FaultSaying<NotAtSpeed<Reverse>, false>;
  struct SayUnscrewingAgain {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      ++fsm.retries;
      fsm.ctx->tell(MessageKind::info,
                    "tool " + std::to_string(fsm.tool) + "'s nut still seen at zone 1 (" +
                        Sensors::nut_pin() + " on) over pocket " + std::to_string(fsm.pocket) +
                        "; unscrewing it once more");
    }
  };
  /// Seen twice: the nut is on the spindle, as far as anyone knows.
  struct FaultNutStillOn {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      fsm.ctx->record_in_spindle(fsm.tool);
      fsm.ctx->fail_check(
          "tool " + std::to_string(fsm.tool) + "'s nut still on the spindle after it was "
          "unscrewed twice " + screwed_words<Reverse>(c, fsm) + " and up to " +
          z_words(c.config.pockets.at(fsm.pocket).at.z + c.config.chuck.rise_after_unload_offset_z) +
          ": zone 1 (" + z_words(c.config.chuck.recognition->zone_1_z) + ") sees it (" +
          Sensors::nut_pin() + " on)",
          true);
    }
  };

  using initial_state = OpeningCover;
  // 21 rows, one more than boost::mpl::vector takes, hence vector21.
  // clang-format off
  using transition_table = boost::mpl::vector21<
  //    Start            Event          Next              Action                   Guard
  // +----------------+--------------+-----------------+------------------------+----------------------------------------+
  Row < OpeningCover   , SensorReport , ToSpinOff       , none                   , CoverOpen                              >,
  Row < OpeningCover   , TimerElapsed , Halted          , FaultCoverDidNotOpen   , CoverHasOpenedSensor                   >,
  Row < ToSpinOff      , InPosition   , StartingReverse , none                   , PocketReadsEmpty                       >,
  Row < ToSpinOff      , InPosition   , Halted          , FaultPocketFull        , Not<PocketReadsEmpty>                  >,
  Row < BackToSpinOff  , InPosition   , StartingReverse , none                   , none                                   >,
  Row < StartingReverse, CommandDone  , ComingUpToSpeed , none                   , none                                   >,
  Row < ComingUpToSpeed, SensorReport , Unscrewing      , none                   , Sensed<AtSpeed>                        >,
  Row < ComingUpToSpeed, TimerElapsed , Unscrewing      , none                   , Ramped<AtSpeed>                        >,
  Row < ComingUpToSpeed, TimerElapsed , Halted          , FaultNotAtSpeed        , Not<Ramped<AtSpeed>>                   >,
  Row < Unscrewing     , InPosition   , StoppingSpindle , none                   , none                                   >,
  Row < StoppingSpindle, CommandDone  , RunningDown     , none                   , none                                   >,
  Row < RunningDown    , SensorReport , ToZone1         , none                   , And<Sensed<Standing>, Recognizes>      >,
  Row < RunningDown    , SensorReport , Away            , RecordToolInPocket     , And<Sensed<Standing>, Not<Recognizes>> >,
  Row < RunningDown    , TimerElapsed , ToZone1         , none                   , And<Ramped<Standing>, Recognizes>      >,
  Row < RunningDown    , TimerElapsed , Away            , RecordToolInPocket     , And<Ramped<Standing>, Not<Recognizes>> >,
  Row < RunningDown    , TimerElapsed , Halted          , FaultSpindleDidNotStop , Not<Ramped<Standing>>                  >,
  Row < ToZone1        , InPosition   , LookingForNut   , none                   , none                                   >,
  Row < LookingForNut  , SensorReport , Away            , RecordToolInPocket     , BeamReads<false>                       >,
  Row < LookingForNut  , TimerElapsed , BackToSpinOff   , SayUnscrewingAgain     , Not<Retried>                           >,
  Row < LookingForNut  , TimerElapsed , Halted          , FaultNutStillOn        , Retried                                >,
  Row < Away           , InPosition   , Finished        , none                   , none                                   >
  >;
  // clang-format on
};
using ScrewingOff = Machine_of<ScrewingOff_>;

}  // namespace fatc::machine
