#pragma once

// A collet nut screwed on from its pocket. docs/sequences.md#collet-nuts.

#include <boost/mpl/vector/vector30.hpp>

#include "screwing.hpp"

namespace fatc::machine {

// ================================================================ screwing on
/// The fetch of a collet-nut changer (`chuck.kind` "collet_nut"): the
/// spindle forward at the load speed plunges onto the nut in the pocket
/// `tighten_plunges` times and stops over it; the recognition sensor (where
/// given) must then see the nut at zone 1 and see it screwed home at zone 2,
/// else it is screwed on once more, then the changer faults naming the zone.
struct ScrewingOn_ : Flow<ScrewingOn_> {
  template <class Parent>
  static int served_pocket(const Context&, int, const Parent& leg) {
    return leg.pocket;
  }
  int retries = 0;  ///< screwed on once more
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& leg) {
    Flow::on_entry(e, leg);
    retries = 0;
  }

  // The phases; plan/routes.hpp says where each goes.
  struct ToSpinOff : GoingAtPocket<plan::nut_to_spin_off> {};
  struct BackToSpinOff : GoingAtPocket<plan::nut_back_to_spin_off> {};
  struct StartingForward : TurningSpindle<Forward> {};
  struct ComingUpToSpeed : RampingSpindle<AtSpeed> {};
  struct Tightening : GoingAtPocket<plan::nut_screw_on> {};
  struct StoppingSpindle : TurningSpindle<Stop> {};
  struct RunningDown : RampingSpindle<Standing> {};
  struct ToZone1 : GoingAtPocket<plan::nut_to_zone_1> {};
  /// The beam at zone 1 must be cut: the nut came with the spindle.
  struct SeeingNut : AwaitingSensor<BeamReads<true>> {};
  struct ToZone2 : GoingAtPocket<plan::nut_to_zone_2> {};
  /// The beam at zone 2 must be clear: the nut is screwed home, not hanging low.
  struct SeeingSeated : AwaitingSensor<BeamReads<false>> {};
  /// Up and back to safe, the nut on the spindle.
  struct Away : GoingAtPocket<plan::nut_away> {};

  using FaultNotAtSpeed = FaultSaying<NotAtSpeed<Forward>, false>;
  /// Zone `Zone` read wrong: the nut is screwed on once more.
  template <int Zone>
  struct SayScrewingAgain {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      ++fsm.retries;
      fsm.ctx->tell(MessageKind::info,
                    "tool " + std::to_string(fsm.tool) + " over pocket " +
                        std::to_string(fsm.pocket) +
                        (Zone == 1 ? ": zone 1 sees no nut (" + Sensors::nut_pin() + " off)"
                                   : "'s nut not screwed home: zone 2 still sees it (" +
                                         Sensors::nut_pin() + " on)") +
                        "; screwing it on once more");
    }
  };
  /// Read wrong twice at zone `Zone`: where the nut is, nobody knows for sure.
  template <int Zone>
  struct FaultZone {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      const Recognition& zones = *c.config.chuck.recognition;
      const std::string screwed =
          " after it was screwed on twice " + screwed_words<Forward>(c, fsm) + ", " +
          std::to_string(c.config.chuck.tighten_plunges) + " plunge" +
          (c.config.chuck.tighten_plunges == 1 ? "" : "s") + " each";
      if (Zone == 2) fsm.ctx->record_in_spindle(fsm.tool);
      fsm.ctx->fail_check(
          Zone == 1 ? "tool " + std::to_string(fsm.tool) + " not on the spindle" + screwed +
                          ": zone 1 (" + z_words(zones.zone_1_z) + ") sees no nut (" +
                          Sensors::nut_pin() + " off)"
                    : "tool " + std::to_string(fsm.tool) + "'s nut not screwed home" + screwed +
                          ": zone 2 (" + z_words(zones.zone_2_z) + ") still sees it (" +
                          Sensors::nut_pin() + " on)",
          true);
    }
  };

  using initial_state = OpeningCover;
  // 24 rows, more than boost::mpl::vector takes, hence vector24.
  // clang-format off
  using transition_table = boost::mpl::vector24<
  //    Start            Event          Next              Action                   Guard
  // +----------------+--------------+-----------------+------------------------+----------------------------------------+
  Row < OpeningCover   , SensorReport , ToSpinOff       , none                   , CoverOpen                              >,
  Row < OpeningCover   , TimerElapsed , Halted          , FaultCoverDidNotOpen   , CoverHasOpenedSensor                   >,
  Row < ToSpinOff      , InPosition   , StartingForward , none                   , none                                   >,
  Row < BackToSpinOff  , InPosition   , StartingForward , none                   , none                                   >,
  Row < StartingForward, CommandDone  , ComingUpToSpeed , none                   , none                                   >,
  Row < ComingUpToSpeed, SensorReport , Tightening      , none                   , Sensed<AtSpeed>                        >,
  Row < ComingUpToSpeed, TimerElapsed , Tightening      , none                   , Ramped<AtSpeed>                        >,
  Row < ComingUpToSpeed, TimerElapsed , Halted          , FaultNotAtSpeed        , Not<Ramped<AtSpeed>>                   >,
  Row < Tightening     , InPosition   , StoppingSpindle , none                   , none                                   >,
  Row < StoppingSpindle, CommandDone  , RunningDown     , none                   , none                                   >,
  Row < RunningDown    , SensorReport , ToZone1         , none                   , And<Sensed<Standing>, Recognizes>      >,
  Row < RunningDown    , SensorReport , Away            , RecordToolInSpindle    , And<Sensed<Standing>, Not<Recognizes>> >,
  Row < RunningDown    , TimerElapsed , ToZone1         , none                   , And<Ramped<Standing>, Recognizes>      >,
  Row < RunningDown    , TimerElapsed , Away            , RecordToolInSpindle    , And<Ramped<Standing>, Not<Recognizes>> >,
  Row < RunningDown    , TimerElapsed , Halted          , FaultSpindleDidNotStop , Not<Ramped<Standing>>                  >,
  Row < ToZone1        , InPosition   , SeeingNut       , none                   , none                                   >,
  Row < SeeingNut      , SensorReport , ToZone2         , none                   , BeamReads<true>                        >,
  Row < SeeingNut      , TimerElapsed , BackToSpinOff   , SayScrewingAgain<1>    , Not<Retried>                           >,
  Row < SeeingNut      , TimerElapsed , Halted          , FaultZone<1>           , Retried                                >,
  Row < ToZone2        , InPosition   , SeeingSeated    , none                   , none                                   >,
  Row < SeeingSeated   , SensorReport , Away            , RecordToolInSpindle    , BeamReads<false>                       >,
  Row < SeeingSeated   , TimerElapsed , BackToSpinOff   , SayScrewingAgain<2>    , Not<Retried>                           >,
  Row < SeeingSeated   , TimerElapsed , Halted          , FaultZone<2>           , Retried                                >,
  Row < Away           , InPosition   , Finished        , none                   , none                                   >
  >;
  // clang-format on
};
using ScrewingOn = Machine_of<ScrewingOn_>;

}  // namespace fatc::machine
