#pragma once

// The legs every flow is made of: flush the chuck, return a tool to its
// pocket, retrieve a tool from its pocket, measure a tool on the sensor.
// docs/sequences.md is the contract these tables follow.

#include <cmath>

#include "common.hpp"

namespace fatc::machine {

/// To the loading position, Z first: where the operator reaches the spindle.
struct ToLoadingZ : Moving<to::LoadingZ> {};
struct ToLoadingXY : Moving<to::LoadingXY> {};

// ================================================================ flush
/// Opens the chuck briefly, `flush.pulses` times, so that whatever the spindle
/// may still hold drops before it receives a tool (docs/sequences.md#flush).
/// Ends with the chuck closed.
struct FlushLeg_ : Flow<FlushLeg_> {
  int pulses_done = 0;

  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    pulses_done = 0;
  }

  struct PulseOpen : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      ++fsm.pulses_done;
      fsm.ctx->open_chuck();
      fsm.ctx->wait(fsm.ctx->config.flush.pulse_seconds, "flushing the chuck (open)");
    }
  };
  struct PulseClosed : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      fsm.ctx->close_chuck();
      fsm.ctx->wait(fsm.ctx->config.flush.pause_seconds, "flushing the chuck (closed)");
    }
  };
  struct PulsesLeft {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.pulses_done < fsm.ctx->config.flush.pulses;
    }
  };

  struct DecidingToPulse : Decision {};
  using initial_state = DecidingToPulse;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start             Event           Next          Action  Guard
  // +----------------+---------------+-------------+-------+-----------------+
  Row < DecidingToPulse, none          , PulseOpen   , none  , PulsesLeft      >,
  Row < DecidingToPulse, none          , Finished    , none  , Not<PulsesLeft> >,
  Row < PulseOpen      , TimerElapsed  , PulseClosed , none  , none            >,
  Row < PulseClosed    , TimerElapsed  , PulseOpen   , none  , PulsesLeft      >,
  Row < PulseClosed    , TimerElapsed  , Finished    , none  , Not<PulsesLeft> >
  >;
  // clang-format on
};
using FlushLeg = msm::back::state_machine<FlushLeg_>;

// ================================================================ return
/// Puts the tool in the spindle back into its own pocket (docs/sequences.md#return).
/// `Which` only tells two uses within one flow apart.
template <class Which>
struct ReturnLeg_ : Flow<ReturnLeg_<Which>> {
  static int served_tool(const Context& ctx) { return ctx.tools.spindle; }
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow<ReturnLeg_<Which>>::on_entry(e, parent);
    const int tool = this->pocket_tool;
    this->ctx->record_progress(
        "returning tool " + std::to_string(tool) + " to pocket " + std::to_string(tool), tool);
  }

  struct ToSafeZ : Moving<to::SafeZ> {};
  struct ToSafeXY : Moving<to::SafeXY> {};
  struct OverSide : Moving<to::SideAtSafeZ> {};
  struct DownToSide : Moving<to::Side> {};
  struct IntoPocket : Moving<to::SlowlyIntoPocket> {};
  struct ReleasingTool : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      fsm.ctx->open_chuck();
      fsm.ctx->wait(fsm.ctx->config.chuck_seconds,
                    "releasing tool " + std::to_string(fsm.pocket_tool) + " into its pocket");
    }
  };
  struct UpToAboveChuck : Moving<to::AboveChuck> {};
  struct UpToClearance : Moving<to::AboveClearance> {};
  struct UpToSafeZ : Moving<to::SafeZOverPocket> {};
  struct BackToSafeXY : Moving<to::SafeXY> {};

  struct RecordToolInPocket {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->record_in_pocket(fsm.pocket_tool);
    }
  };

  using initial_state = ToSafeZ;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start            Event          Next             Action              Guard
  // +----------------+--------------+----------------+--------------------+------+
  Row < ToSafeZ        , InPosition   , ToSafeXY       , none               , none >,
  Row < ToSafeXY       , InPosition   , OverSide       , none               , none >,
  Row < OverSide       , InPosition   , DownToSide     , none               , none >,
  Row < DownToSide     , InPosition   , IntoPocket     , none               , none >,
  Row < IntoPocket     , InPosition   , ReleasingTool  , none               , none >,
  Row < ReleasingTool  , TimerElapsed , UpToAboveChuck , RecordToolInPocket , none >,
  Row < UpToAboveChuck , InPosition   , UpToClearance  , CloseChuck         , none >,
  Row < UpToClearance  , InPosition   , UpToSafeZ      , none               , none >,
  Row < UpToSafeZ      , InPosition   , BackToSafeXY   , none               , none >,
  Row < BackToSafeXY   , InPosition   , Finished       , none               , none >
  >;
  // clang-format on
};
template <class Which>
using ReturnLeg = msm::back::state_machine<ReturnLeg_<Which>>;

// ================================================================ retrieve
/// Takes the requested tool out of its pocket (docs/sequences.md#retrieve).
struct RetrieveLeg_ : Flow<RetrieveLeg_> {
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    ctx->record_progress(
        "fetching tool " + std::to_string(pocket_tool) + " from pocket " + std::to_string(pocket_tool),
        pocket_tool);
  }
  struct ToSafeZ : Moving<to::SafeZ> {};
  struct ToSafeXY : Moving<to::SafeXY> {};
  struct OverPocket : Moving<to::PocketAtSafeZ> {};
  struct DownToClearance : Moving<to::AboveClearance> {};
  struct DownToAboveChuck : Moving<to::AboveChuck> {};
  struct OpeningChuck : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      fsm.ctx->open_chuck();
      fsm.ctx->wait(fsm.ctx->config.chuck_seconds,
                    "opening the chuck above pocket " + std::to_string(fsm.pocket_tool));
    }
  };
  struct SlowlyDownToPocket : Moving<to::SlowlyDownToPocket> {};
  struct Settling : Waiting<ChuckSeconds> {};
  struct GrippingTool : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      fsm.ctx->close_chuck();
      fsm.ctx->wait(fsm.ctx->config.chuck_seconds,
                    "gripping tool " + std::to_string(fsm.pocket_tool));
    }
  };
  struct SlowlyOutToSide : Moving<to::SlowlyToSide> {};
  struct UpToSafeZ : Moving<to::SafeZOverPocket> {};
  struct BackToSafeXY : Moving<to::SafeXY> {};

  struct AlreadyAtSafe {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.ctx->at_safe();
    }
  };

  /// A return just before ended at safe: no need to go there again.
  struct DecidingToGoToSafe : Decision {};
  using initial_state = DecidingToGoToSafe;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                                Event          Next                 Action               Guard
  // +------------------------------------+--------------+--------------------+--------------------+--------------------+
  Row < DecidingToGoToSafe                 , none         , ToSafeZ            , none               , Not<AlreadyAtSafe> >,
  Row < DecidingToGoToSafe                 , none         , OverPocket         , none               , AlreadyAtSafe      >,
  Row < ToSafeZ                            , InPosition   , ToSafeXY           , none               , none >,
  Row < ToSafeXY                           , InPosition   , OverPocket         , none               , none >,
  Row < OverPocket                         , InPosition   , DownToClearance    , none               , none >,
  Row < DownToClearance                    , InPosition   , DownToAboveChuck   , none               , none >,
  Row < DownToAboveChuck                   , InPosition   , FlushLeg           , none               , none >,
  Row < FlushLeg::exit_pt<Finished>        , LegDone      , OpeningChuck       , none               , none >,
  Row < OpeningChuck                       , TimerElapsed , SlowlyDownToPocket , none               , none >,
  Row < SlowlyDownToPocket                 , InPosition   , Settling           , none               , none >,
  Row < Settling                           , TimerElapsed , GrippingTool       , none               , none >,
  Row < GrippingTool                       , TimerElapsed , SlowlyOutToSide    , RecordToolInSpindle, none >,
  Row < SlowlyOutToSide                    , InPosition   , UpToSafeZ          , none               , none >,
  Row < UpToSafeZ                          , InPosition   , BackToSafeXY       , none               , none >,
  Row < BackToSafeXY                       , InPosition   , Finished           , none               , none >
  >;
  // clang-format on
};
using RetrieveLeg = msm::back::state_machine<RetrieveLeg_>;

// ================================================================ probing
/// The load flow runs the probe over MDI: the operator may cancel it, and it
/// always writes the length.
struct OverMdi {
  static constexpr bool cancellable = true;
  static bool writes_length(const Context&, int) { return true; }
};
/// M6 (`probe_after_change`) runs the probe inside the program, which the
/// operator stops with LinuxCNC's Stop; `check` only compares a stored length.
struct InsideProgram {
  static constexpr bool cancellable = false;
  static bool writes_length(const Context& c, int tool) {
    return c.config.probe_after_change != ProbeAfterChange::check ||
           c.tools.lengths.count(tool) == 0;
  }
};

/// Measures the tool in the spindle on the touch-off sensor
/// (docs/sequences.md#probing): a fast seek, a back-off, a slow latch;
/// length = latched machine Z minus probe_length_compensation_offset, written
/// to the tool table when `Run` says so.
template <class Run>
struct ProbingLeg_ : Flow<ProbingLeg_<Run>> {
  double first_touch_z = 0.0;  ///< where the seek touched
  double latched_z = 0.0;      ///< where the latch touched

  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow<ProbingLeg_<Run>>::on_entry(e, parent);
    this->ctx->record_progress("measuring tool " + std::to_string(this->pocket_tool), 0);
  }

  struct NotMeasured : msmf::exit_pseudo_state<LegDone> {};

  struct Seeking : Probing<to::ProbeSeek, Run::cancellable> {};
  struct BackingOff : Moving<to::ProbeBackOff> {};
  struct Latching : Probing<to::ProbeLatch, Run::cancellable> {};
  struct WritingLength : Commanding<to::ToolLength> {};
  struct Retracting : Moving<to::RetractFromSensor> {};
  struct RetractingUnmeasured : Moving<to::LoadingZ> {};

  struct Touched {
    template <class Fsm, class Source, class Target>
    bool operator()(const ProbeResult& e, Fsm&, Source&, Target&) const {
      return e.touched;
    }
  };
  struct WritesLength {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return Run::writes_length(*fsm.ctx, fsm.pocket_tool);
    }
  };
  struct RememberFirstTouch {
    template <class Fsm, class Source, class Target>
    void operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      fsm.first_touch_z = e.z;
    }
  };
  struct RememberLatch {
    template <class Fsm, class Source, class Target>
    void operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      fsm.latched_z = e.z;
      fsm.ctx->last_length = e.z - fsm.ctx->config.probe_length_compensation_offset;
    }
  };
  struct RecordLength {
    template <class Fsm, class Source, class Target>
    void operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      fsm.latched_z = e.z;
      fsm.ctx->record_length(fsm.pocket_tool,
                             e.z - fsm.ctx->config.probe_length_compensation_offset);
    }
  };
  struct SayNoTouch {
    template <class Fsm, class Source, class Target>
    void operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      const std::string tool = "probe: tool " + std::to_string(fsm.pocket_tool);
      fsm.ctx->tell(MessageKind::error,
                    e.tripped_before
                        ? tool + ": the touch-off sensor was already tripped; nothing written"
                        : tool + " did not touch the sensor before probe_limit; nothing written");
    }
  };
  struct SayCancelled {
    template <class Fsm, class Source, class Target>
    void operator()(const OperatorCancel&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->tell(MessageKind::info, "probe of tool " + std::to_string(fsm.pocket_tool) +
                                           " cancelled by the operator; nothing written");
    }
  };
  struct CancelStopsProbe {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm&, Source&, Target&) const {
      return Run::cancellable;
    }
  };

  using initial_state = Seeking;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                  Event           Next                   Action              Guard
  // +----------------------+---------------+----------------------+-------------------+-----------------------------+
  Row < Seeking              , ProbeResult   , BackingOff           , RememberFirstTouch, Touched                     >,
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
template <class Run>
using ProbingLeg = msm::back::state_machine<ProbingLeg_<Run>>;

// ================================================================ measure after M6
/// `probe_after_change`: takes the tool just put in the spindle to the sensor
/// and measures it, or checks it against its stored length; ends at safe Z.
struct MeasureLeg_ : Flow<MeasureLeg_> {
  using Probe = ProbingLeg<InsideProgram>;
  struct OverSensor : Moving<to::SensorXY> {};
  struct UpToSafeZ : Moving<to::SafeZ> {};

  struct LengthDiffers {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      return std::abs(*c.last_length - c.tools.lengths.at(fsm.pocket_tool)) >
             c.config.check_tolerance();
    }
  };
  struct SayMeasured {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      fsm.ctx->tell(MessageKind::info,
                    "tool " + std::to_string(fsm.pocket_tool) + " measures " +
                        format_length(c.config, *c.last_length) + ", stored " +
                        format_length(c.config, c.tools.lengths.at(fsm.pocket_tool)));
    }
  };
  struct SayBrokenOrPulledOut {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      c.fault_reason = "tool " + std::to_string(fsm.pocket_tool) + " measures " +
                       format_length(c.config, *c.last_length) + " but its stored length is " +
                       format_length(c.config, c.tools.lengths.at(fsm.pocket_tool)) +
                       " (probe_check_tolerance " +
                       format_length(c.config, c.config.check_tolerance()) +
                       "): tool broken or pulled out?";
    }
  };
  struct SayNotMeasured {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->fault_reason = "tool " + std::to_string(fsm.pocket_tool) +
                              " could not be measured after the change (probe_after_change)";
    }
  };

  using initial_state = ToLoadingZ;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                                 Event       Next        Action                Guard
  // +-------------------------------------+-----------+-----------+---------------------+--------------------+
  Row < ToLoadingZ                          , InPosition, OverSensor, none                , none               >,
  Row < OverSensor                          , InPosition, Probe     , none                , none               >,
  Row < Probe::exit_pt<Finished>            , LegDone   , UpToSafeZ , SayMeasured         , Not<LengthDiffers> >,
  Row < Probe::exit_pt<Finished>            , LegDone   , Failed    , SayBrokenOrPulledOut, LengthDiffers      >,
  Row < Probe::exit_pt<Probe::NotMeasured>  , LegDone   , Failed    , SayNotMeasured      , none               >,
  Row < UpToSafeZ                           , InPosition, Finished  , none                , none               >
  >;
  // clang-format on
};
using MeasureLeg = msm::back::state_machine<MeasureLeg_>;

}  // namespace fatc::machine
