#pragma once

// What the two collet-nut legs share (`chuck.kind` "collet_nut"): the
// spindle turned by the changer, its ramps, and the tool-recognition zones.
// docs/sequences.md#collet-nuts.

#include <cmath>

#include "../../formatted.hpp"
#include "cover.hpp"

namespace fatc::machine {

/// "1200 rpm in reverse": a speed of the changer's in a message.
inline std::string rpm_words(double rpm) {
  return formatted("%.0f rpm %s", std::fabs(rpm), rpm < 0.0 ? "in reverse" : "forward");
}
/// "Z -60.000": a height in a message.
inline std::string z_words(double z) { return formatted("Z %.3f", z); }

/// The spindle screws collet nuts (`chuck.kind` "collet_nut"): the legs
/// screw a nut off or on instead of working a drawbar.
struct ScrewsNuts {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->config.screws_nuts();
  }
};

// ---------------------------------------------------------------- the spindle
/// The speeds of a leg: `Reverse` unscrews, `Forward` screws on, `Stop`.
struct Reverse {
  static double rpm(const Config& c) { return -c.chuck.unload_rpm; }
};
struct Forward {
  static double rpm(const Config& c) { return c.chuck.load_rpm; }
};
struct Stop {
  static double rpm(const Config&) { return 0.0; }
};

/// Asks LinuxCNC (through the executor: M4, M3, M5) for the spindle at
/// `Speed` over the served pocket; CommandDone follows.
template <class Speed>
struct TurningSpindle : msmf::state<> {
  using flag_list = boost::mpl::vector1<flag::AwaitsMotion>;
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    const double rpm = Speed::rpm(fsm.ctx->config);
    const std::string p = "pocket " + std::to_string(fsm.pocket);
    fsm.ctx->turn_spindle(rpm, rpm == 0.0 ? "spindle stopped over " + p
                                          : "spindle " + rpm_words(rpm) + " over " + p);
  }
};

/// The spindle turns at the speed asked for: `spindle-at-speed` where wired.
struct AtSpeed {
  static bool senses(const Context& c) { return c.sensors.senses_at_speed(); }
  static bool holds(const Context& c) { return !c.machine.spindle_stopped && c.sensors.at_speed(); }
  static std::string awaited(const Context& c) {
    return "waiting for the spindle to come up to speed (" + Sensors::at_speed_pin() + ")" +
           (c.machine.spindle_stopped ? ", spindle-stopped on" : "");
  }
  static constexpr const char* ramp = "letting the spindle come up to speed";
};
/// The spindle stands: LinuxCNC has it off and `zero-speed` says so where wired.
struct Standing {
  static bool senses(const Context& c) { return c.sensors.wired.wired(Sensor::zero_speed); }
  static bool holds(const Context& c) { return c.spindle_at_standstill(); }
  static std::string awaited(const Context&) { return "waiting for the spindle to stop"; }
  static constexpr const char* ramp = "letting the spindle stop";
};

/// Waits for the spindle to reach `Speed` (AtSpeed or Standing): its sensor
/// where wired, up to `spindle_stop_timeout_seconds`, else it has
/// `chuck.spindle_ramp_seconds`. Rows: SensorReport [Sensed<Speed>] and
/// TimerElapsed [Ramped<Speed>] on, TimerElapsed otherwise to the fault.
template <class Speed>
struct RampingSpindle : msmf::state<> {
  using flag_list = boost::mpl::vector1<flag::AwaitsSpindle>;
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    Context& c = *fsm.ctx;
    if (!Speed::senses(c)) {
      c.await_sensor(c.config.chuck.spindle_ramp_seconds, Speed::ramp);
    } else if (Speed::holds(c)) {
      c.raise.sensor_report();
    } else {
      c.await_sensor(c.config.spindle_stop_timeout_seconds, Speed::awaited(c));
    }
  }
  template <class Event, class Fsm>
  void on_exit(const Event&, Fsm& fsm) {
    fsm.ctx->ports.cancel_timer();
  }
};
/// Its sensor says the spindle got there.
template <class Speed>
struct Sensed {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return Speed::senses(*fsm.ctx) && Speed::holds(*fsm.ctx);
  }
};
/// No sensor: the ramp's time is up, and LinuxCNC agrees.
template <class Speed>
struct Ramped {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return !Speed::senses(*fsm.ctx) && Speed::holds(*fsm.ctx);
  }
};

/// The spindle did not reach the leg's speed: nothing was screwed yet.
template <class Speed>
struct NotAtSpeed {
  template <class Leg>
  static std::string text(const Context& c, const Leg& leg) {
    return "the spindle did not come up to " + rpm_words(Speed::rpm(c.config)) + " over pocket " +
           std::to_string(leg.pocket) + " within spindle_stop_timeout_seconds (" +
           seconds_words(c.config.spindle_stop_timeout_seconds) + ", " +
           (c.machine.spindle_stopped ? std::string("spindle-stopped on")
                                      : Sensors::at_speed_pin() + " off") +
           "): tool " + std::to_string(leg.tool) + " not screwed";
  }
};
/// The spindle still turns over the pocket: where the nut is, nobody knows.
struct DidNotStop {
  template <class Leg>
  static std::string text(const Context& c, const Leg& leg) {
    std::string why = c.sensors.turning_words();
    if (!c.machine.spindle_stopped) why = "spindle-stopped off" + (why.empty() ? "" : ", " + why);
    return "the spindle did not stop over pocket " + std::to_string(leg.pocket) +
           " within spindle_stop_timeout_seconds (" +
           seconds_words(c.config.spindle_stop_timeout_seconds) + ", " + why + ")";
  }
};
using FaultSpindleDidNotStop = FaultSaying<DidNotStop, true>;

// ---------------------------------------------------------------- the tool-recognition zones
/// `chuck.recognition` is given.
struct Recognizes {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->config.chuck.recognition.has_value();
  }
};
/// The beam reads a nut (`Seen` true) or none where the nose stands.
template <bool Seen>
struct BeamReads : SensorGuard<BeamReads<Seen>> {
  template <class Leg>
  static bool holds(const Context& c, const Leg&) {
    return c.sensors.nut_reads(Seen);
  }
  static std::string awaited(const Context&) {
    return "reading the tool-recognition sensor (" + Sensors::nut_pin() + ")";
  }
};
/// The nut was screwed once more already.
struct Retried {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.retries > 0;
  }
};
/// Where the nut was screwed, for a fault: "at pocket 2, the spindle at
/// 1200 rpm in reverse down to the engage Z -80.000".
template <class Speed, class Leg>
std::string screwed_words(const Context& c, const Leg& leg) {
  return "at pocket " + std::to_string(leg.pocket) + ", the spindle at " +
         rpm_words(Speed::rpm(c.config)) + " down to the engage Z (" +
         z_words(c.config.pockets.at(leg.pocket).at.z) + ")";
}

}  // namespace fatc::machine
