#pragma once

// The legs every flow is made of: flush the chuck, return a tool to its
// pocket, retrieve a tool from its pocket, measure a tool on the sensor.
// docs/sequences.md is the contract these tables follow.

#include <cmath>

#include "chuck.hpp"

namespace fatc::machine {

// ================================================================ the rack cover
/// `rack_cover`: the cover opens before a leg's first move into the rack (at
/// once where there is none or it is open already); it closes when the
/// changer is done with the rack (Operating's ComparingSensors). Rows:
/// SensorReport [CoverOpen] on, TimerElapsed to the fault.
struct OpeningCover : msmf::state<> {
  using flag_list = boost::mpl::vector1<flag::AwaitsSensor>;
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    Context& c = *fsm.ctx;
    c.open_cover();
    if (c.cover_reads_open()) {
      c.recheck_sensors();
    } else if (c.config.rack_cover->opened_sensor) {
      c.await_sensor(c.config.rack_cover->timeout_seconds,
                     "waiting for the rack cover to open (rack-cover-opened)");
    } else {
      c.await_sensor(c.config.rack_cover->seconds, "opening the rack cover");
    }
  }
  template <class Event, class Fsm>
  void on_exit(const Event&, Fsm& fsm) {
    fsm.ctx->ports.cancel_timer();
  }
  /// A cover with no `rack-cover-opened` is open once it has had its seconds.
  struct HasNoOpenedSensor {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return !fsm.ctx->config.rack_cover->opened_sensor;
    }
  };
  struct Settle {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->cover_settled = true;
      fsm.ctx->recheck_sensors();
    }
  };
  using internal_transition_table =
      boost::mpl::vector<msmf::Internal<TimerElapsed, Settle, HasNoOpenedSensor>>;
};
/// The rack cover is open, or there is none.
struct CoverOpen : SensorGuard<CoverOpen> {
  template <class Leg>
  static bool holds(const Context& c, const Leg&) {
    return c.cover_reads_open();
  }
};
struct CoverDidNotOpen {
  template <class Leg>
  static std::string text(const Context& c, const Leg&) {
    return "the rack cover did not open within rack_cover.timeout_seconds (" +
           seconds_words(c.config.rack_cover->timeout_seconds) +
           ", rack-cover-opened off): nothing moved into the rack";
  }
};
using FaultCoverDidNotOpen = FaultSaying<CoverDidNotOpen, false>;
/// Only then is a timeout a fault: without it the timer means "open by now".
struct CoverHasOpenedSensor {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->config.rack_cover && fsm.ctx->config.rack_cover->opened_sensor;
  }
};

// ================================================================ flush
/// Opens the chuck briefly, `flush.pulses` times, so that whatever the spindle
/// may still hold drops before it receives a tool (docs/sequences.md#flush).
/// Each opening waits until the chuck may open and must read open; each
/// closing must read closed. Ends with the chuck closed.
struct FlushLeg_ : Flow<FlushLeg_> {
  int pulses_done = 0;

  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    pulses_done = 0;
  }

  struct WaitingToOpen : WaitingToOpenChuck<ToFlush> {};
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
  //    Start                  Event          Next                 Action                             Guard
  // +----------------------+--------------+--------------------+----------------------------------+-----------------+
  Row < DecidingToPulse      , none         , WaitingToOpen      , none                             , PulsesLeft      >,
  Row < DecidingToPulse      , none         , Finished           , none                             , Not<PulsesLeft> >,
  Row < WaitingToOpen        , SensorReport , PulseOpen          , none                             , ChuckMayOpen    >,
  Row < WaitingToOpen        , TimerElapsed , Halted             , FaultChuckMayNotOpen<ToFlush>    , none            >,
  Row < PulseOpen            , TimerElapsed , CheckingDrawbarOpen, none                             , none            >,
  Row < CheckingDrawbarOpen  , SensorReport , PulseClosed        , none                             , DrawbarOpen     >,
  Row < CheckingDrawbarOpen  , TimerElapsed , Halted             , FaultDrawbarStayedClosed<ToFlush>, none            >,
  Row < PulseClosed          , TimerElapsed , CheckingDrawbarClosed, none                           , none            >,
  Row < CheckingDrawbarClosed, SensorReport , DecidingToPulse    , none                             , DrawbarClosed   >,
  Row < CheckingDrawbarClosed, TimerElapsed , Halted             , FaultDrawbarStayedOpen<ToFlush>  , none            >
  >;
  // clang-format on
};
using FlushLeg = Machine_of<FlushLeg_>;

// ================================================================ return
/// The return of whatever the spindle held before: to its own pocket.
struct Before {
  static int pocket(const Context& ctx, int tool) { return ctx.return_pocket(tool).value_or(0); }
};
/// The return of the tool the load flow is about: to the pocket the load chose.
struct PutAway {
  static int pocket(const Context& ctx, int) { return ctx.load_pocket; }
};

/// Puts the tool in the spindle into a pocket (docs/sequences.md#return):
/// `Which` says which one (Before: its own; PutAway: the one the load chose).
template <class Which>
struct ReturnLeg_ : Flow<ReturnLeg_<Which>> {
  static int served_tool(const Context& ctx) { return ctx.tools.spindle; }
  static int served_pocket(const Context& ctx, int tool) { return Which::pocket(ctx, tool); }
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow<ReturnLeg_<Which>>::on_entry(e, parent);
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
  /// Up and away; a fetch that follows on the direct path starts over this pocket.
  struct Away : Walking<Away> {
    template <class Leg>
    static plan::Route route(const Context& c, const Leg& leg) {
      return plan::return_away(c.config, leg.pocket, c.fetch_follows_return);
    }
  };

  struct RecordToolInPocket {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->record_in_pocket(fsm.tool, fsm.pocket);
    }
  };
  struct PocketFull {
    template <class Leg>
    static std::string text(const Context&, const Leg& leg) {
      return "pocket " + std::to_string(leg.pocket) + " is not empty (" + pocket_pin(leg.pocket) +
             " on): tool " + std::to_string(leg.tool) + " cannot go in";
    }
  };
  using FaultPocketFull = FaultSaying<PocketFull, false>;
  /// The tool came up with the spindle: it is there, as far as anyone knows.
  struct FaultToolStillInSpindle {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->record_in_spindle(fsm.tool);
      fsm.ctx->fail_check("tool " + std::to_string(fsm.tool) +
                              " still in the spindle after the chuck opened at pocket " +
                              std::to_string(fsm.pocket) +
                              " and the spindle lifted (tool-present on)",
                          true);
    }
  };

  using initial_state = OpeningCover;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                  Event          Next                   Action                               Guard
  // +----------------------+--------------+----------------------+------------------------------------+-----------------------+
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

// ================================================================ retrieve
/// Takes the requested tool out of its pocket (docs/sequences.md#retrieve).
/// The tool must show in the spindle once the chuck closed on it; if not, it
/// is gripped once more where it is (the chuck opens and closes again), and
/// seen neither time, the changer faults.
struct RetrieveLeg_ : Flow<RetrieveLeg_> {
  int retries = 0;  ///< grips tried again
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    retries = 0;
    ctx->record_progress(
        "fetching tool " + std::to_string(tool) + " from pocket " + std::to_string(pocket), pocket);
  }
  // The phases; plan/routes.hpp says where each goes.
  /// Over the pocket to above-chuck; straight over it from safe, or, on the
  /// direct path, from anywhere at safe Z (where a direct return ends).
  struct ToAboveChuck : Walking<ToAboveChuck> {
    template <class Leg>
    static plan::Route route(const Context& c, const Leg& leg) {
      const bool at_safe_z = (c.known_axes & axis_z) && c.position.z == c.config.safe.z;
      const bool at_safe = c.at_safe() || (c.config.path == Path::direct && at_safe_z);
      return plan::fetch_to_above_chuck(c.config, leg.pocket, at_safe);
    }
  };
  struct WaitingToOpen : WaitingToOpenChuck<AbovePocket> {};
  struct OpeningChuck : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      const std::string p = std::to_string(fsm.pocket);
      fsm.ctx->open_chuck();
      fsm.ctx->wait(fsm.ctx->config.chuck_seconds,
                    fsm.retries == 0 ? "opening the chuck above pocket " + p
                                     : "opening the chuck again at pocket " + p + " to grip tool " +
                                           std::to_string(fsm.tool) + " once more");
    }
  };
  struct DownAroundTool : GoingAtPocket<plan::fetch_down_to_tool> {};
  struct Settling : Waiting<ChuckSeconds> {};
  struct GrippingTool : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      fsm.ctx->close_chuck();
      fsm.ctx->wait(fsm.ctx->config.chuck_seconds, "gripping tool " + std::to_string(fsm.tool));
    }
  };
  /// The drawbar reads closed and tool-present sees the tool.
  struct Gripped : SensorGuard<Gripped> {
    template <class Leg>
    static bool holds(const Context& c, const Leg&) {
      return c.drawbar_reads_closed() && c.spindle_reads(true);
    }
    static std::string awaited(const Context&) {
      return "waiting for the drawbar to report closed and tool-present to see the tool";
    }
  };
  struct CheckingGrip : AwaitingSensor<Gripped> {};
  struct OutAndAway : GoingAtPocket<plan::fetch_out_and_away> {};

  /// The grip was tried once more already.
  struct Retried {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.retries > 0;
    }
  };
  struct CannotFetch {
    template <class Leg>
    static std::string text(const Context& c, const Leg& leg) {
      const std::string t = std::to_string(leg.tool);
      if (!c.pocket_reads(leg.pocket, true)) {
        return "pocket " + std::to_string(leg.pocket) + " reads empty (" + pocket_pin(leg.pocket) +
               " off): tool " + t + " cannot be fetched";
      }
      return "the spindle is not empty (tool-present on): tool " + t + " cannot be fetched";
    }
  };
  using FaultCannotFetch = FaultSaying<CannotFetch, false>;
  struct SayGrippingAgain {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      ++fsm.retries;
      fsm.ctx->tell(MessageKind::info, "tool " + std::to_string(fsm.tool) +
                                           " not in the spindle after the chuck closed at pocket " +
                                           std::to_string(fsm.pocket) +
                                           " (tool-present off); gripping it once more");
    }
  };
  struct NotGripped {
    template <class Leg>
    static std::string text(const Context&, const Leg& leg) {
      return "tool " + std::to_string(leg.tool) +
             " not in the spindle after the chuck closed at pocket " + std::to_string(leg.pocket) +
             " (tool-present off, retried once)";
    }
  };
  using FaultToolNotGripped = FaultSaying<NotGripped, true>;
  /// Where the chuck opens: above the pocket, or at it when gripping again.
  struct WhereItOpens {
    template <class Leg>
    static std::string where(const Leg& leg) {
      return leg.retries == 0 ? AbovePocket::where(leg) : AtPocket::where(leg);
    }
  };

  struct Starting : Decision {};
  using initial_state = Starting;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                        Event          Next                 Action                                  Guard
  // +----------------------------+--------------+--------------------+---------------------------------------+----------------------------------+
  Row < Starting                   , none         , Halted             , FaultCannotFetch                      , Not<ReadyToFetch>                >,
  Row < Starting                   , none         , OpeningCover       , none                                  , ReadyToFetch                     >,
  Row < OpeningCover               , SensorReport , ToAboveChuck       , none                                  , CoverOpen                        >,
  Row < OpeningCover               , TimerElapsed , Halted             , FaultCoverDidNotOpen                  , CoverHasOpenedSensor             >,
  Row < ToAboveChuck               , InPosition   , FlushLeg           , none                                  , none                             >,
  Row < FlushLeg::exit_pt<Finished>, LegDone      , WaitingToOpen      , none                                  , none                             >,
  Row < WaitingToOpen              , SensorReport , OpeningChuck       , none                                  , ChuckMayOpen                     >,
  Row < WaitingToOpen              , TimerElapsed , Halted             , FaultChuckMayNotOpen<WhereItOpens>    , none                             >,
  Row < OpeningChuck               , TimerElapsed , CheckingDrawbarOpen, none                                  , none                             >,
  Row < CheckingDrawbarOpen        , SensorReport , DownAroundTool     , none                                  , And<DrawbarOpen, Not<Retried>>   >,
  Row < CheckingDrawbarOpen        , SensorReport , GrippingTool       , none                                  , And<DrawbarOpen, Retried>        >,
  Row < CheckingDrawbarOpen        , TimerElapsed , Halted             , FaultDrawbarStayedClosed<WhereItOpens>, none                             >,
  Row < DownAroundTool             , InPosition   , Settling           , none                                  , none                             >,
  Row < Settling                   , TimerElapsed , GrippingTool       , none                                  , none                             >,
  Row < GrippingTool               , TimerElapsed , CheckingGrip       , none                                  , none                             >,
  Row < CheckingGrip               , SensorReport , OutAndAway         , RecordToolInSpindle                   , Gripped                          >,
  Row < CheckingGrip               , TimerElapsed , Halted             , FaultDrawbarStayedOpen<AtPocket>      , Not<DrawbarClosed>               >,
  Row < CheckingGrip               , TimerElapsed , WaitingToOpen      , SayGrippingAgain                      , And<DrawbarClosed, Not<Retried>> >,
  Row < CheckingGrip               , TimerElapsed , Halted             , FaultToolNotGripped                   , And<DrawbarClosed, Retried>      >,
  Row < OutAndAway                 , InPosition   , Finished           , none                                  , none                             >
  >;
  // clang-format on
};
using RetrieveLeg = Machine_of<RetrieveLeg_>;

// ================================================================ probing
/// The load flow runs the probe over MDI: the operator may cancel it, and it
/// always writes the length.
struct OverMdi {
  static constexpr bool cancellable = true;
  /// The operator has just put the tool in by hand, maybe with a new cutter:
  /// its stored length is no expectation.
  static constexpr bool checks_window = false;
  static bool writes_length(const Context&, int) { return true; }
};
/// M6 (`probe_after_change`) runs the probe inside the program, which the
/// operator stops with LinuxCNC's Stop; `check` only compares a stored length.
struct InsideProgram {
  static constexpr bool cancellable = false;
  /// The changer fetched the tool itself: a stored length says where it must touch.
  static constexpr bool checks_window = true;
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
    this->ctx->record_progress("measuring tool " + std::to_string(this->tool), 0);
  }

  struct NotMeasured : msmf::exit_pseudo_state<LegDone> {};

  struct Seek {
    template <class Leg>
    Step operator()(const Context& c, const Leg&) const {
      return plan::probe_seek(c.config);
    }
  };
  struct Latch {
    template <class Leg>
    Step operator()(const Context& c, const Leg&) const {
      return plan::probe_latch(c.config);
    }
  };
  struct Length {
    template <class Leg>
    Step operator()(const Context& c, const Leg& leg) const {
      return plan::tool_length(leg.tool, c.tools.lengths.at(leg.tool));
    }
  };
  struct Seeking : Probing<Seek, Run::cancellable> {};
  struct BackingOff : Walking<BackingOff> {
    template <class Leg>
    static plan::Route route(const Context& c, const Leg& leg) {
      return {plan::probe_back_off(c.config, leg.first_touch_z)};
    }
  };
  struct Latching : Probing<Latch, Run::cancellable> {};
  struct WritingLength : Commanding<Length> {};
  struct Retracting : Walking<Retracting> {
    template <class Leg>
    static plan::Route route(const Context& c, const Leg& leg) {
      return {plan::retract_from_sensor(c.config, leg.latched_z)};
    }
  };
  struct RetractingUnmeasured : Walking<RetractingUnmeasured> {
    template <class Leg>
    static plan::Route route(const Context& c, const Leg&) {
      return {plan::loading_z(c.config)};
    }
  };

  struct Touched {
    template <class Fsm, class Source, class Target>
    bool operator()(const ProbeResult& e, Fsm&, Source&, Target&) const {
      return e.touched;
    }
  };
  /// The seek touched more than probe_window away from where the tool's
  /// stored length puts the touch: a shorted sensor, a wrong or pulled-out tool.
  struct OutsideWindow {
    template <class Fsm, class Source, class Target>
    bool operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      const auto stored = c.tools.lengths.find(fsm.tool);
      if (!Run::checks_window || stored == c.tools.lengths.end()) return false;
      const double expected = stored->second + c.config.probe_length_compensation_offset;
      return std::abs(e.z - expected) > c.config.window();
    }
  };
  struct WritesLength {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return Run::writes_length(*fsm.ctx, fsm.tool);
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
      fsm.ctx->record_length(fsm.tool, e.z - fsm.ctx->config.probe_length_compensation_offset);
    }
  };
  struct SayNoTouch {
    template <class Fsm, class Source, class Target>
    void operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      const std::string tool = "tool " + std::to_string(fsm.tool);
      fsm.ctx->probe_problem = e.tripped_before
                                   ? "the touch-off sensor was already tripped"
                                   : tool + " did not touch the sensor before probe_limit";
      fsm.ctx->tell(MessageKind::error,
                    e.tripped_before
                        ? "probe: " + tool + ": " + fsm.ctx->probe_problem + "; nothing written"
                        : "probe: " + fsm.ctx->probe_problem + "; nothing written");
    }
  };
  struct SayOutsideWindow {
    template <class Fsm, class Source, class Target>
    void operator()(const ProbeResult& e, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      const double stored = c.tools.lengths.at(fsm.tool);
      const double expected = stored + c.config.probe_length_compensation_offset;
      const bool early = e.z > expected;
      c.probe_problem =
          "tool " + std::to_string(fsm.tool) + " touched the sensor at Z " +
          format_length(c.config, e.z) + ", " + format_length(c.config, std::abs(e.z - expected)) +
          (early ? " too early" : " too late") + ": its stored length " +
          format_length(c.config, stored) + " puts the touch at Z " +
          format_length(c.config, expected) + " (probe_window " +
          format_length(c.config, c.config.window()) + "); " +
          (early ? "a shorted sensor, a wrong or pulled-out tool?" : "a broken or wrong tool?");
      c.tell(MessageKind::error, "probe: " + c.probe_problem + " Nothing written");
    }
  };
  struct SayCancelled {
    template <class Fsm, class Source, class Target>
    void operator()(const OperatorCancel&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->probe_problem = "the probe was cancelled by the operator";
      fsm.ctx->tell(MessageKind::info, "probe of tool " + std::to_string(fsm.tool) +
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
template <class Run>
using ProbingLeg = Machine_of<ProbingLeg_<Run>>;

// ================================================================ measure after M6
/// `probe_after_change`: takes the tool just put in the spindle to the sensor
/// and measures it, or checks it against its stored length; ends at safe Z.
struct MeasureLeg_ : Flow<MeasureLeg_> {
  using Probe = ProbingLeg<InsideProgram>;

  struct LengthDiffers {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      return std::abs(*c.last_length - c.tools.lengths.at(fsm.tool)) > c.config.check_tolerance();
    }
  };
  struct SayMeasured {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      fsm.ctx->tell(MessageKind::info, "tool " + std::to_string(fsm.tool) + " measures " +
                                           format_length(c.config, *c.last_length) + ", stored " +
                                           format_length(c.config, c.tools.lengths.at(fsm.tool)));
    }
  };
  struct SayBrokenOrPulledOut {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      c.fault_reason =
          "tool " + std::to_string(fsm.tool) + " measures " +
          format_length(c.config, *c.last_length) + " but its stored length is " +
          format_length(c.config, c.tools.lengths.at(fsm.tool)) + " (probe_check_tolerance " +
          format_length(c.config, c.config.check_tolerance()) + "): tool broken or pulled out?";
    }
  };
  struct SayNotMeasured {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->fault_reason =
          "tool " + std::to_string(fsm.tool) +
          " could not be measured after the change (probe_after_change): " + fsm.ctx->probe_problem;
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
