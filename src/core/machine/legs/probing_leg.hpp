#pragma once

// Measuring the tool in the spindle on the touch-off sensor, and the
// measurement after M6. docs/sequences.md#probing.

#include <cmath>

#include "../base/chuck.hpp"

namespace fatc::machine {

// ================================================================ probing
/// Measures the tool in the spindle on the touch-off sensor
/// (docs/sequences.md#probing): a fast seek, a back-off, a slow latch;
/// a tool that seeks slower than probe_seek_feed (a touch probe) first goes
/// down at that feed to probe_window above where its length puts the touch,
/// and a touch on the way there is refused: it was not slow;
/// length = latched machine Z minus probe_length_compensation_offset, written
/// to the tool table. Over MDI (load, measure all) the operator may cancel
/// it; inside M6 (`probe_after_change`) the changer fetched the tool itself,
/// so a stored length says where it must touch, and `check` writes nothing
/// over a stored length.
struct ProbingLeg_ : Flow<ProbingLeg_> {
  double approach_z = 0.0;     ///< where the fast approach ends, where there is one
  KeepoutLength approach_length;  ///< the length it was planned from
  double first_touch_z = 0.0;  ///< where the seek touched
  double latched_z = 0.0;      ///< where the latch touched
  /// The leg's result, which its flow takes as it ends: the length measured
  /// (latched Z minus probe_length_compensation_offset), or why none was.
  std::optional<double> length;
  std::string problem;

  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    length.reset();
    problem.clear();
    ctx->record_progress("measuring tool " + std::to_string(tool), 0);
  }

  struct NotMeasured : msmf::exit_pseudo_state<LegDone> {};

  /// Where the fast approach of `tool` ends, if it saves time: its length
  /// as the keep-out counts it (the tool table's, the changer's own where
  /// longer, else the longest the config allows), from where the spindle stands.
  static std::optional<double> approach_for(const Context& c, int tool) {
    std::optional<double> start;
    if (c.motion.known_axes & axis_z) {
      start = c.motion.position.z;
    } else if (c.machine.position) {
      start = c.machine.position->z;
    }
    return plan::probe_approach_z(c.config, tool,
                                  c.motion.keepout_lengths.of(tool, c.tools.lengths).length, start);
  }

  struct Approach {
    template <class Leg>
    Step operator()(const Context& c, const Leg& leg) const {
      return plan::probe_approach(c.config, leg.approach_z);
    }
  };
  struct Seek {
    template <class Leg>
    Step operator()(const Context& c, const Leg& leg) const {
      return plan::probe_seek(c.config, leg.tool);
    }
  };
  struct Latch {
    template <class Leg>
    Step operator()(const Context& c, const Leg& leg) const {
      return plan::probe_latch(c.config, leg.tool);
    }
  };
  struct Length {
    template <class Leg>
    Step operator()(const Context& c, const Leg& leg) const {
      return plan::tool_length(leg.tool, c.tools.lengths.at(leg.tool));
    }
  };
  struct DecidingHowToGoDown : msmf::state<> {};
  struct Approaching : Probing<Approach> {};
  struct Seeking : Probing<Seek> {};
  struct BackingOff : Walking<BackingOff> {
    template <class Leg>
    static plan::Route route(const Context& c, const Leg& leg) {
      return plan::phase(c.config, c.standing(), plan::probe_back_off, leg.tool,
                         leg.first_touch_z);
    }
  };
  struct Latching : Probing<Latch> {};
  struct WritingLength : Commanding<Length> {};
  struct Retracting : Walking<Retracting> {
    template <class Leg>
    static plan::Route route(const Context& c, const Leg& leg) {
      return plan::phase(c.config, c.standing(), plan::retract_from_sensor, leg.latched_z);
    }
  };
  struct RetractingUnmeasured : Walking<RetractingUnmeasured> {
    template <class Leg>
    static plan::Route route(const Context& c, const Leg&) {
      return plan::phase(c.config, c.standing(), plan::loading_z);
    }
  };

  struct ApproachSavesTime {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return approach_for(*fsm.ctx, fsm.tool).has_value();
    }
  };
  struct Touched {
    template <class Fsm, class Source, class Target>
    bool operator()(const ProbeResult& e, Fsm&, Source&, Target&) const {
      return e.touched;
    }
  };
  /// Nothing moved: the sensor was tripped before the probe began.
  struct TrippedBefore {
    template <class Fsm, class Source, class Target>
    bool operator()(const ProbeResult& e, Fsm&, Source&, Target&) const {
      return e.tripped_before;
    }
  };
  /// The seek touched more than probe_window away from where the tool's
  /// stored length puts the touch: a shorted sensor, a wrong or pulled-out tool.
  struct OutsideWindow {
    template <class Fsm, class Source, class Target>
    bool operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      const auto stored = c.tools.lengths.find(fsm.tool);
      if (!c.request.in_program || stored == c.tools.lengths.end()) return false;
      const double expected = stored->second + c.config.probe_length_compensation_offset;
      return std::abs(e.z - expected) > c.config.window();
    }
  };
  struct WritesLength {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      return !c.request.in_program || !c.measuring(fsm.tool).checks;
    }
  };
  struct RememberApproach {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.approach_z = *approach_for(*fsm.ctx, fsm.tool);
      fsm.approach_length = fsm.ctx->motion.keepout_lengths.of(fsm.tool, fsm.ctx->tools.lengths);
    }
  };
  struct RememberFirstTouch {
    template <class Fsm, class Source, class Target>
    void operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      fsm.first_touch_z = e.z;
    }
  };
  /// A check: the length is the leg's result and the status shows it; the
  /// stored one stays.
  struct RememberLatch {
    template <class Fsm, class Source, class Target>
    void operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      fsm.latched_z = e.z;
      fsm.length = e.z - fsm.ctx->config.probe_length_compensation_offset;
      fsm.ctx->activity.last_length = fsm.length;
    }
  };
  struct RecordLength {
    template <class Fsm, class Source, class Target>
    void operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      fsm.latched_z = e.z;
      fsm.length = e.z - fsm.ctx->config.probe_length_compensation_offset;
      fsm.ctx->record_length(fsm.tool, *fsm.length);
    }
  };
  struct SayNoTouch {
    template <class Fsm, class Source, class Target>
    void operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      const std::string tool = "tool " + std::to_string(fsm.tool);
      fsm.problem = e.tripped_before ? "the touch-off sensor was already tripped"
                                     : tool + " did not touch the sensor before probe_limit";
      fsm.ctx->tell(MessageKind::error,
                    e.tripped_before ? "probe: " + tool + ": " + fsm.problem + "; nothing written"
                                     : "probe: " + fsm.problem + "; nothing written");
    }
  };
  struct SayOutsideWindow {
    template <class Fsm, class Source, class Target>
    void operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      const double stored = c.tools.lengths.at(fsm.tool);
      const double expected = stored + c.config.probe_length_compensation_offset;
      const bool early = e.z > expected;
      fsm.problem =
          "tool " + std::to_string(fsm.tool) + " touched the sensor at Z " +
          format_length(c.config, e.z) + ", " + format_length(c.config, std::abs(e.z - expected)) +
          (early ? " too early" : " too late") + ": its stored length " +
          format_length(c.config, stored) + " puts the touch at Z " +
          format_length(c.config, expected) + " (probe_window " +
          format_length(c.config, c.config.window()) + "); " +
          (early ? "a shorted sensor, a wrong or pulled-out tool?" : "a broken or wrong tool?");
      c.tell(MessageKind::error, "probe: " + fsm.problem + " Nothing written");
    }
  };
  /// The tool is longer than the length the approach was planned from, by
  /// more than probe_window: it met the sensor at probe_seek_feed, not at its own.
  struct SayTouchedFast {
    template <class Fsm, class Source, class Target>
    void operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      const KeepoutLength& length = fsm.approach_length;
      const char* from = length.source == LengthSource::table ? "LinuxCNC's tool table"
                         : length.source == LengthSource::measured
                             ? "the changer's measurement"
                             : "the longest tool the config allows";
      fsm.problem = "tool " + std::to_string(fsm.tool) + " touched the sensor at Z " +
                    format_length(c.config, e.z) +
                    " on the fast approach (probe_seek_feed), which was to end at Z " +
                    format_length(c.config, fsm.approach_z) + ": it is longer than " +
                    format_length(c.config, length.length) + " (" + from +
                    ") by more than probe_window " + format_length(c.config, c.config.window()) +
                    "; correct its length in the tool table (0: the longest tool the config "
                    "allows counts) and measure it again";
      fsm.ctx->tell(MessageKind::error, "probe: " + fsm.problem + "; nothing written");
    }
  };
  struct SayCancelled {
    template <class Fsm, class Source, class Target>
    void operator()(const OperatorCancel&, Fsm& fsm, Source&, Target&) const {
      fsm.problem = "the probe was cancelled by the operator";
      fsm.ctx->tell(MessageKind::info, "probe of tool " + std::to_string(fsm.tool) +
                                           " cancelled by the operator; nothing written");
    }
  };
  struct CancelStopsProbe {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return !fsm.ctx->request.in_program;
    }
  };

  using initial_state = DecidingHowToGoDown;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                  Event           Next                   Action              Guard
  // +----------------------+---------------+----------------------+-------------------+-----------------------------+
  Row < DecidingHowToGoDown  , none          , Approaching          , RememberApproach  , ApproachSavesTime           >,
  Row < DecidingHowToGoDown  , none          , Seeking              , none              , Not<ApproachSavesTime>      >,
  Row < Approaching          , ProbeResult   , Seeking              , none              , And<Not<Touched>, Not<TrippedBefore>> >,
  Row < Approaching          , ProbeResult   , RetractingUnmeasured , SayTouchedFast    , Touched                     >,
  Row < Approaching          , ProbeResult   , RetractingUnmeasured , SayNoTouch        , TrippedBefore               >,
  Row < Approaching          , OperatorCancel, RetractingUnmeasured , SayCancelled      , CancelStopsProbe            >,
  Row < Seeking              , ProbeResult   , BackingOff           , RememberFirstTouch, And<Touched, Not<OutsideWindow>> >,
  Row < Seeking              , ProbeResult   , RetractingUnmeasured , SayOutsideWindow  , And<Touched, OutsideWindow>  >,
  Row < Seeking              , ProbeResult   , RetractingUnmeasured , SayNoTouch        , Not<Touched>                >,
  Row < Seeking              , OperatorCancel, RetractingUnmeasured , SayCancelled      , CancelStopsProbe            >,
  Row < BackingOff           , InPosition    , Latching             , none              , none                        >,
  Row < Latching             , ProbeResult   , WritingLength        , RecordLength      , And<Touched, WritesLength>  >,
  Row < Latching             , ProbeResult   , Retracting           , RememberLatch     , And<Touched, Not<WritesLength>> >,
  Row < Latching             , ProbeResult   , RetractingUnmeasured , SayNoTouch        , Not<Touched>                >,
  Row < Latching             , OperatorCancel, RetractingUnmeasured , SayCancelled      , CancelStopsProbe            >,
  Row < WritingLength        , CommandDone   , Retracting           , none              , none                        >,
  Row < Retracting           , InPosition    , Finished             , none              , none                        >,
  Row < RetractingUnmeasured , InPosition    , NotMeasured          , none              , none                        >
  >;
  // clang-format on
};
using ProbingLeg = Machine_of<ProbingLeg_>;

// ================================================================ measure after M6
/// A measuring rule after M6 (`tools`, `probe_after_change`): takes the tool
/// just put in the spindle to the sensor and measures it, or checks it
/// against its stored length; ends at safe Z.
struct MeasureLeg_ : Flow<MeasureLeg_> {
  using Probe = ProbingLeg;

  /// What the probe measured, as it finished.
  template <class Fsm>
  static double measured(Fsm& fsm) {
    return *fsm.template get_state<Probe&>().length;
  }

  struct LengthDiffers {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      return std::abs(measured(fsm) - c.tools.lengths.at(fsm.tool)) >
             c.config.check_tolerance_of(fsm.tool);
    }
  };
  struct SayMeasured {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      fsm.ctx->tell(MessageKind::info, "tool " + std::to_string(fsm.tool) + " measures " +
                                           format_length(c.config, measured(fsm)) +
                                           ", stored " +
                                           format_length(c.config, c.tools.lengths.at(fsm.tool)));
    }
  };
  struct SayBrokenOrPulledOut {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      const CheckTolerance tolerance = check_tolerance_for(c.config, fsm.tool);
      const double length = measured(fsm);
      const double stored = c.tools.lengths.at(fsm.tool);
      *fsm.failure =
          "tool " + std::to_string(fsm.tool) + " measures " + format_length(c.config, length) +
          " but its stored length is " + format_length(c.config, stored) + ", " +
          format_length(c.config, std::abs(length - stored)) +
          (length < stored ? " shorter" : " longer") +
          " (" + tolerance.key + " " + format_length(c.config, tolerance.length) +
          "): tool broken or pulled out?";
    }
  };
  struct SayNotMeasured {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      *fsm.failure =
          "tool " + std::to_string(fsm.tool) +
          " could not be measured after the change (" + rule_said(fsm.ctx->config, fsm.tool) +
          "): " +
          fsm.template get_state<Probe&>().problem;
    }
  };

  using initial_state = ToSensor;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                                 Event       Next        Action                Guard
  // +-------------------------------------+-----------+-----------+---------------------+--------------------+
  Row < ToSensor                            , InPosition, Probe     , none                , none               >,
  Row < Probe::exit_pt<Finished>            , LegDone   , UpToSafeZ , SayMeasured         , Not<LengthDiffers> >,
  Row < Probe::exit_pt<Finished>            , LegDone   , Failed    , SayBrokenOrPulledOut, LengthDiffers      >,
  Row < Probe::exit_pt<Probe::NotMeasured>  , LegDone   , Failed    , SayNotMeasured      , none               >,
  Row < UpToSafeZ                           , InPosition, Finished  , none                , none               >
  >;
  // clang-format on
};
using MeasureLeg = Machine_of<MeasureLeg_>;

}  // namespace fatc::machine
