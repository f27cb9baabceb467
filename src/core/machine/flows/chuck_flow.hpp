#pragma once

// The chuck atoms from G-code: release and clamp.

#include "../chuck.hpp"

namespace fatc::machine {

// ================================================================ chuck atoms
/// A chuck atom from G-code (nc_files/fixed_atc_probe_chuck_*.ngc), with
/// the interlocks of the legs: a release waits until the chuck may open
/// (air, the spindle at a standstill), gives the chuck `chuck_seconds`, and
/// the drawbar must then read open; the chuck stays open until a clamp, which
/// gives it `chuck_seconds` again and must read closed. What the spindle
/// holds stays as recorded (docs/sequences.md#chuck-atoms).
struct ChuckFlow_ : Flow<ChuckFlow_> {
  static int served_tool(const Context& ctx) { return ctx.tools.spindle; }
  template <class Parent>
  static int served_pocket(const Context&, int, const Parent&) {
    return 0;
  }
  ChuckRequest::Action action = ChuckRequest::Action::clamp;  ///< what this atom does
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    if constexpr (std::is_same_v<Event, ChuckRequest>) action = e.action;
  }

  struct Releases {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.action == ChuckRequest::Action::release;
    }
  };
  struct DecidingWhich : Decision {};
  struct WaitingToOpen : WaitingToOpenChuck<ForRelease> {};
  struct Opening : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      fsm.ctx->open_chuck();
      fsm.ctx->wait(fsm.ctx->config.chuck_seconds, "releasing the chuck (G-code)");
    }
  };
  struct Closing : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      fsm.ctx->close_chuck();
      fsm.ctx->wait(fsm.ctx->config.chuck_seconds, "clamping the chuck (G-code)");
    }
  };
  /// After a clamp, the spindle's sensor (where wired) must agree with the record:
  /// what a hand did at the spindle meanwhile is checked before the program
  /// goes on.
  struct SpindleAsRecorded : SensorGuard<SpindleAsRecorded> {
    template <class Leg>
    static bool holds(const Context& c, const Leg&) {
      return c.sensors.spindle_reads(c.tools.spindle != 0);
    }
    static std::string awaited(const Context& c) {
      return "waiting for " + Sensors::tool_pin() + " to see " +
             (c.tools.spindle != 0 ? "tool " + std::to_string(c.tools.spindle)
                                   : std::string("the spindle empty")) +
             " after the clamp";
    }
  };
  struct CheckingSpindle : AwaitingSensor<SpindleAsRecorded> {};
  struct SpindleNotAsRecorded {
    template <class Leg>
    static std::string text(const Context& c, const Leg&) {
      const int held = c.tools.spindle;
      return "after the clamp from G-code " + Sensors::tool_pin() +
             (held != 0 ? " reads the spindle empty (off), but tool " + std::to_string(held) +
                              " is recorded in it"
                        : std::string(" reads a tool (on), but the spindle is recorded empty"));
    }
  };
  using FaultSpindleNotAsRecorded = FaultSaying<SpindleNotAsRecorded, true>;
  struct SayReleased {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const int held = fsm.ctx->tools.spindle;
      fsm.ctx->tell(MessageKind::info,
                    held == 0 ? std::string("chuck released (G-code); clamp it before other work")
                              : "chuck released at loading (G-code); tool " + std::to_string(held) +
                                    " stays recorded in the spindle: clamp it, then unload it "
                                    "with the panel if you took it out");
    }
  };

  using initial_state = DecidingWhich;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                  Event          Next                   Action                                Guard
  // +----------------------+--------------+----------------------+-------------------------------------+---------------+
  Row < DecidingWhich        , none         , WaitingToOpen        , none                                , Releases      >,
  Row < DecidingWhich        , none         , Closing              , none                                , Not<Releases> >,
  Row < WaitingToOpen        , SensorReport , Opening              , none                                , ChuckMayOpen  >,
  Row < WaitingToOpen        , TimerElapsed , Halted               , FaultChuckMayNotOpen<ForRelease>    , none          >,
  Row < Opening              , TimerElapsed , CheckingDrawbarOpen  , none                                , none          >,
  Row < CheckingDrawbarOpen  , SensorReport , Finished             , SayReleased                         , DrawbarOpen   >,
  Row < CheckingDrawbarOpen  , TimerElapsed , Halted               , FaultDrawbarStayedClosed<ForRelease>, none          >,
  Row < Closing              , TimerElapsed , CheckingDrawbarClosed, none                                , none          >,
  Row < CheckingDrawbarClosed, SensorReport , CheckingSpindle      , none                                , DrawbarClosed >,
  Row < CheckingDrawbarClosed, TimerElapsed , Halted               , FaultDrawbarStayedOpen<ForClamp>    , none          >,
  Row < CheckingSpindle      , SensorReport , Finished             , none                                , SpindleAsRecorded >,
  Row < CheckingSpindle      , TimerElapsed , Halted               , FaultSpindleNotAsRecorded           , none          >
  >;
  // clang-format on
};

}  // namespace fatc::machine
