#pragma once

// The chuck with its sensors, as states the legs put in their own tables:
// it opens only when it may (air pressure, the spindle at a standstill), the
// drawbar must then read open, and after a close read closed.
// docs/sequences.md#sensors.

#include "sensors.hpp"

namespace fatc::machine {

/// What the state file says is under way while a release holds the chuck open.
inline constexpr const char* kChuckHeldOpen = "the chuck held open (released from G-code)";

// ---------------------------------------------------------------- where, for messages
/// "at pocket 3": where the chuck acts, for a leg that serves pocket `tool`.
struct AtPocket {
  template <class Leg>
  static std::string where(const Leg& leg) {
    return "at pocket " + std::to_string(leg.pocket);
  }
};
struct AbovePocket {
  template <class Leg>
  static std::string where(const Leg& leg) {
    return "above pocket " + std::to_string(leg.pocket);
  }
};
struct ToFlush {
  template <class Leg>
  static std::string where(const Leg&) {
    return "to flush it";
  }
};
struct ForRelease {
  template <class Leg>
  static std::string where(const Leg&) {
    return "for the release from G-code";
  }
};
struct ForClamp {
  template <class Leg>
  static std::string where(const Leg&) {
    return "for the clamp from G-code";
  }
};

// ---------------------------------------------------------------- opening

/// Air pressure OK and the spindle at a standstill: the chuck may open.
struct ChuckMayOpen : SensorGuard<ChuckMayOpen> {
  template <class Leg>
  static bool holds(const Context& c, const Leg&) {
    return c.sensors.air_ok() && c.spindle_at_standstill();
  }
};

/// Waits until the chuck may open: air within sensor_timeout_seconds, a
/// turning spindle within spindle_stop_timeout_seconds. Rows: SensorReport
/// [ChuckMayOpen] to the opening, TimerElapsed to the fault.
template <class Where>
struct WaitingToOpenChuck : msmf::state<> {
  using flag_list = boost::mpl::vector1<flag::AwaitsSensor>;
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    Context& c = *fsm.ctx;
    if (ChuckMayOpen::holds(c, fsm)) {
      c.raise.sensor_report();
    } else if (!c.spindle_at_standstill()) {
      c.await_sensor(c.config.spindle_stop_timeout_seconds,
                     "waiting for the spindle to stop before the chuck opens " + Where::where(fsm));
    } else {
      c.await_sensor(c.config.sensor_timeout_seconds,
                     "waiting for air pressure (" + Sensors::air_pin() +
                         ") before the chuck opens " + Where::where(fsm));
    }
  }
  template <class Event, class Fsm>
  void on_exit(const Event&, Fsm& fsm) {
    fsm.ctx->ports.cancel_timer();
  }
};

/// The chuck did not get to open: no air, or a spindle that kept turning.
/// Nothing moved with it: what the spindle holds is still a fact.
template <class Where>
struct ChuckMayNotOpen {
  template <class Leg>
  static std::string text(const Context& c, const Leg& leg) {
    std::string why;
    if (!c.sensors.air_ok()) why = "air pressure low (" + Sensors::air_pin() + " off)";
    if (!c.spindle_at_standstill()) {
      std::string seen = c.machine.spindle_stopped ? "" : "spindle-stopped off";
      if (const std::string turning = c.sensors.turning_words(); !turning.empty()) {
        seen += std::string(seen.empty() ? "" : ", ") + turning;
      }
      why += std::string(why.empty() ? "" : " and ") +
             "the spindle did not stop within spindle_stop_timeout_seconds (" + seen + ")";
    }
    return why + " before the chuck opened " + Where::where(leg) + "; it stayed closed";
  }
};
template <class Where>
using FaultChuckMayNotOpen = FaultSaying<ChuckMayNotOpen<Where>, false>;

/// The chuck was told to open and the drawbar did not follow: whether it
/// let go of anything is not a fact.
template <class Where>
struct DrawbarStayedClosed {
  template <class Leg>
  static std::string text(const Context& c, const Leg& leg) {
    return "the drawbar did not open " + Where::where(leg) + " within " +
           seconds_words(c.config.sensor_timeout_seconds) + " (" + c.sensors.drawbar_words() + ")";
  }
};
template <class Where>
using FaultDrawbarStayedClosed = FaultSaying<DrawbarStayedClosed<Where>, true>;

/// The chuck was told to close and the drawbar did not follow.
template <class Where>
struct DrawbarStayedOpen {
  template <class Leg>
  static std::string text(const Context& c, const Leg& leg) {
    return "the drawbar did not close " + Where::where(leg) + " within " +
           seconds_words(c.config.sensor_timeout_seconds) + " (" + c.sensors.drawbar_words() + ")";
  }
};
template <class Where>
using FaultDrawbarStayedOpen = FaultSaying<DrawbarStayedOpen<Where>, true>;

/// The drawbar must read open, within sensor_timeout_seconds.
struct CheckingDrawbarOpen : AwaitingSensor<DrawbarOpen> {};
/// The drawbar must read closed, within sensor_timeout_seconds.
struct CheckingDrawbarClosed : AwaitingSensor<DrawbarClosed> {};

}  // namespace fatc::machine
