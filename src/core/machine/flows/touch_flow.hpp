#pragma once

// Touching the rack: teaching pockets by touch, the datum taught and checked.

#include "../../rack/touch.hpp"
#include "../legs/cover.hpp"
#include "touch.hpp"

namespace fatc::machine {

// ================================================================ touching the rack
/// The probe in the spindle touches each feature (rack/touch.hpp: where each
/// touch starts depends on what the earlier ones found): to the touch's start,
/// a seek at the probe's seek feed, a back-off, a latch at its latch feed;
/// up out of the feature once its touches are made. Teaching then shows what
/// it found beside what config.json says and writes nothing until Continue;
/// the drift check compares the datum with where it was taught. A probe that
/// touches nothing backs out the way it came and the flow ends saying how far
/// it went; LinuxCNC's Stop or the machine going off ends it where it stands
/// (StopDryRun). docs/sequences.md#teach-by-touch.
struct TouchFlow_ : Flow<TouchFlow_> {
  static int served_tool(const Context& ctx) { return ctx.tools.spindle; }

  TouchRequest::Goal goal = TouchRequest::Goal::pockets;
  std::vector<int> features;  ///< the pockets to touch, in order; the datum: one 0
  std::size_t feature = 0;    ///< the one being touched
  std::optional<FeatureTouch> touching;
  std::optional<fatc::Touch> touch;  ///< the touch under way
  std::optional<fatc::Touch> made;   ///< the feature's touch made last, if any
  double tripped = 0.0;        ///< where its seek touched
  std::vector<Found> found;
  std::string problem;  ///< why the flow stops early, once it must

  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    if constexpr (std::is_same_v<Event, TouchRequest>) {
      goal = e.goal;
      features = goal == TouchRequest::Goal::pockets ? touched_pockets(*ctx, e)
                                                     : std::vector<int>{0};
    }
    feature = 0;
    found.clear();
    problem.clear();
    begin_feature();
  }
  /// The pockets a request touches: those it names, else every pocket whose
  /// feature can be touched now (a bore or fork that holds its tool cannot).
  static std::vector<int> touched_pockets(const Context& c, const TouchRequest& e);
  /// The feature `feature` is next: its first touch.
  void begin_feature();
  /// The flow ends early, saying `why` (its end fails the executor with it).
  /// Not stop(): the back-end's stop(Event) would end the machine itself.
  void end_early(std::string why);
  /// The pocket whose column the touches enter, 0 for the datum's (its pocket's).
  int feature_pocket() const;

  struct ToTouch : Walking<ToTouch> {
    template <class Leg>
    static plan::Route route(const Context& c, const Leg& leg) {
      // From one wall of a bore to the next straight across, else up and over.
      return plan::walked(
          c.config,
          leg.made ? plan::to_next_touch(c.config, *leg.made, *leg.touch, leg.tool)
                   : plan::to_touch(c.config, *leg.touch, leg.feature_pocket(), leg.tool),
          c.standing());
    }
  };
  struct Seek {
    template <class Leg>
    Step operator()(const Context& c, const Leg& leg) const {
      return plan::touch_seek(c.config, *leg.touch, leg.tool);
    }
  };
  struct Latch {
    template <class Leg>
    Step operator()(const Context& c, const Leg& leg) const {
      return plan::touch_latch(c.config, *leg.touch, leg.tool);
    }
  };
  struct Seeking : Probing<Seek> {};
  struct BackingOff : Walking<BackingOff> {
    template <class Leg>
    static plan::Route route(const Context& c, const Leg& leg) {
      return plan::walked(c.config, {plan::touch_back_off(c.config, *leg.touch, leg.tripped, leg.tool)},
                          c.standing());
    }
  };
  struct Latching : Probing<Latch> {};
  struct NextTouch : Decision {};
  /// Out of the feature, up to its clearance.
  struct Leaving : Walking<Leaving> {
    template <class Leg>
    static plan::Route route(const Context& c, const Leg& leg) {
      return plan::walked(c.config, plan::leave_feature(c.config, leg.feature_pocket(), leg.tool),
                          c.standing());
    }
  };
  struct NextFeature : Decision {};
  /// A touch found nothing: back to where it started, then out of the feature.
  struct BackingOut : Walking<BackingOut> {
    template <class Leg>
    static plan::Route route(const Context& c, const Leg& leg) {
      plan::Route out{plan::back_to_touch_start(c.config, *leg.touch, leg.tool)};
      for (const Step& up : plan::leave_feature(c.config, leg.feature_pocket(), leg.tool)) {
        out.push_back(up);
      }
      return plan::walked(c.config, out, c.standing());
    }
  };
  struct FoundPrompt {
    template <class Leg>
    Prompt operator()(const Context& c, const Leg& leg) const {
      Prompt shown;
      shown.kind = Prompt::Kind::touch_found;
      shown.tool = c.tools.spindle;
      shown.sequence = leg.goal == TouchRequest::Goal::teach_datum ? "The rack datum" : "Touching";
      for (const std::string& line : found_lines(c.config, leg.found)) {
        shown.action += (shown.action.empty() ? "" : "; ") + line;
      }
      return shown;
    }
  };
  struct Showing : HoldingForOperator<FoundPrompt> {};

  struct Tripped {
    template <class Fsm, class Source, class Target>
    bool operator()(const ProbeResult& e, Fsm&, Source&, Target&) const {
      return e.touched;
    }
  };
  struct TouchesLeft {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.touch.has_value();
    }
  };
  struct Stopping {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return !fsm.problem.empty();
    }
  };
  struct FeaturesLeft {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.feature + 1 < fsm.features.size();
    }
  };
  struct Checking {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.goal == TouchRequest::Goal::check_datum;
    }
  };
  /// Over MDI the operator's Cancel stops a touch (the adapter stops LinuxCNC's probe first).
  struct OverMdi {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return !fsm.ctx->request.in_program;
    }
  };

  struct RememberTrip {
    template <class Fsm, class Source, class Target>
    void operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      fsm.tripped = e.z;
    }
  };
  struct TakeTouch {
    template <class Fsm, class Source, class Target>
    void operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      fsm.touching->touched(e.z);
      fsm.made = fsm.touch;
      fsm.touch = fsm.touching->next();
    }
  };
  struct TakeFeature {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const;
  };
  struct SayNoTouch {
    template <class Fsm, class Source, class Target>
    void operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const;
  };
  struct SayCancelled {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.end_early(fsm.touch->label + ": the touch was cancelled by the operator; nothing written");
    }
  };
  struct Onward {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      ++fsm.feature;
      fsm.begin_feature();
    }
  };
  struct Accept {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const;
  };
  struct WriteNothing {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->tell(MessageKind::info, "touching cancelled by the operator: nothing written");
    }
  };
  struct JudgeDrift {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const;
  };

  using initial_state = OpeningCover;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start          Event             Next         Action        Guard
  // +--------------+-----------------+------------+-------------+-------------------------------+
  Row < OpeningCover , SensorReport    , ToTouch    , none        , CoverOpen                     >,
  Row < OpeningCover , TimerElapsed    , Halted     , FaultCoverDidNotOpen, CoverHasOpenedSensor  >,
  Row < ToTouch      , InPosition      , Seeking    , none        , none                          >,
  Row < Seeking      , ProbeResult     , BackingOff , RememberTrip, Tripped                       >,
  Row < Seeking      , ProbeResult     , BackingOut , SayNoTouch  , Not<Tripped>                  >,
  Row < Seeking      , OperatorCancel  , BackingOut , SayCancelled, OverMdi                       >,
  Row < BackingOff   , InPosition      , Latching   , none        , none                          >,
  Row < Latching     , ProbeResult     , NextTouch  , TakeTouch   , Tripped                       >,
  Row < Latching     , ProbeResult     , BackingOut , SayNoTouch  , Not<Tripped>                  >,
  Row < Latching     , OperatorCancel  , BackingOut , SayCancelled, OverMdi                       >,
  Row < NextTouch    , none            , ToTouch    , none        , TouchesLeft                   >,
  Row < NextTouch    , none            , Leaving    , TakeFeature , Not<TouchesLeft>              >,
  Row < Leaving      , InPosition      , NextFeature, none        , none                          >,
  Row < BackingOut   , InPosition      , Cancelled  , none        , none                          >,
  Row < NextFeature  , none            , Cancelled  , none        , Stopping                      >,
  Row < NextFeature  , none            , ToTouch    , Onward      , And<Not<Stopping>, FeaturesLeft> >,
  Row < NextFeature  , none            , Finished   , JudgeDrift  , And<Not<Stopping>, And<Not<FeaturesLeft>, Checking>> >,
  Row < NextFeature  , none            , Showing    , none        , And<Not<Stopping>, And<Not<FeaturesLeft>, Not<Checking>>> >,
  Row < Showing      , OperatorContinue, Finished   , Accept      , none                          >,
  Row < Showing      , OperatorCancel  , Cancelled  , WriteNothing, none                          >
  >;
  // clang-format on
};

}  // namespace fatc::machine
