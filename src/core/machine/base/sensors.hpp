#pragma once

// The optional sensors in the tables: guards that read them (each passes
// when its sensor is not wired) and the state that waits for one of them.
// docs/sequences.md#sensors.

#include <cstdio>

#include "common.hpp"

namespace fatc::machine {

// ---------------------------------------------------------------- durations

/// How long a wired sensor may take to confirm a change.
struct SensorTimeout {
  double operator()(const Config& c) const { return c.sensor_timeout_seconds; }
};
/// How long the spindle may take to stop.
struct SpindleStopTimeout {
  double operator()(const Config& c) const { return c.spindle_stop_timeout_seconds; }
};

/// "1.0 s": a timeout in a message.
inline std::string seconds_words(double seconds) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f s", seconds);
  return buffer;
}

// ---------------------------------------------------------------- guards

/// A guard that is also asked on entry (does the wait start at all?):
/// `Derived::holds(ctx, leg)` answers both.
template <class Derived>
struct SensorGuard {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return Derived::holds(*fsm.ctx, fsm);
  }
};

/// LinuxCNC has the spindle off and, where wired, the spindle's own feedback agrees.
struct SpindleIsStopped : SensorGuard<SpindleIsStopped> {
  template <class Leg>
  static bool holds(const Context& c, const Leg&) {
    return c.spindle_at_standstill();
  }
  static std::string awaited(const Context&) { return "waiting for the spindle to stop"; }
};
/// The drawbar has the air to open.
struct AirPressureOk : SensorGuard<AirPressureOk> {
  template <class Leg>
  static bool holds(const Context& c, const Leg&) {
    return c.sensors.air_ok();
  }
  static std::string awaited(const Context&) {
    return "waiting for air pressure (" + Sensors::air_pin() + ")";
  }
};
/// The drawbar feedback reads released.
struct DrawbarOpen : SensorGuard<DrawbarOpen> {
  template <class Leg>
  static bool holds(const Context& c, const Leg&) {
    return c.sensors.drawbar_reads_open();
  }
  static std::string awaited(const Context&) { return "waiting for the drawbar to report open"; }
};
/// The drawbar feedback reads clamped.
struct DrawbarClosed : SensorGuard<DrawbarClosed> {
  template <class Leg>
  static bool holds(const Context& c, const Leg&) {
    return c.sensors.drawbar_reads_closed();
  }
  static std::string awaited(const Context&) { return "waiting for the drawbar to report closed"; }
};
/// The spindle's sensor reads the leg's tool in the spindle.
struct ToolReadsInSpindle : SensorGuard<ToolReadsInSpindle> {
  template <class Leg>
  static bool holds(const Context& c, const Leg&) {
    return c.sensors.spindle_reads(true);
  }
  static std::string awaited(const Context&) {
    return "waiting for " + Sensors::tool_pin() + " to see the tool";
  }
};
/// The spindle's sensor reads the spindle empty.
struct SpindleReadsEmpty : SensorGuard<SpindleReadsEmpty> {
  template <class Leg>
  static bool holds(const Context& c, const Leg&) {
    return c.sensors.spindle_reads(false);
  }
  static std::string awaited(const Context&) {
    return "waiting for " + Sensors::tool_pin() + " to see the spindle empty";
  }
};
/// The pocket of the leg's tool reads empty: a tool can go in.
struct PocketReadsEmpty : SensorGuard<PocketReadsEmpty> {
  template <class Leg>
  static bool holds(const Context& c, const Leg& leg) {
    return c.sensors.pocket_reads(leg.pocket, false);
  }
};
/// The pocket of the leg's tool reads occupied and the spindle empty: the
/// tool can be fetched.
struct ReadyToFetch : SensorGuard<ReadyToFetch> {
  template <class Leg>
  static bool holds(const Context& c, const Leg& leg) {
    return c.sensors.pocket_reads(leg.pocket, true) && c.sensors.spindle_reads(false);
  }
};
/// The wired sensors agree with the tool state.
struct SensorsAgree : SensorGuard<SensorsAgree> {
  template <class Leg>
  static bool holds(const Context& c, const Leg&) {
    return c.disagreements().empty();
  }
  static std::string awaited(const Context& c) {
    std::string words = "comparing the sensors with the saved tool state";
    for (const auto& disagreement : c.disagreements()) words += "; " + disagreement;
    return words;
  }
};

// ---------------------------------------------------------------- when a check fails

/// Where a leg stops when one of its checks failed: the CheckFailed its
/// action raised follows at once and faults the changer (the top table's
/// `Operating, CheckFailed` row), so nothing else happens here.
struct Halted : msmf::state<> {};

/// A check failed: the changer faults with `Words`' reason. `Uncertain`: it
/// failed after the chuck moved, so what the spindle holds is not a fact.
template <class Words, bool Uncertain>
struct FaultSaying {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    fsm.ctx->fail_check(Words::text(*fsm.ctx, fsm), Uncertain);
  }
};

// ---------------------------------------------------------------- waiting for a sensor

/// Waits until `Condition` holds, at most `Timeout` of the config. On entry
/// it looks at the sensors once (a SensorReport queued behind the event that
/// brought it here), so it leaves at once when `Condition` already holds.
/// Its rows: SensorReport guarded by `Condition`, and TimerElapsed for the fault.
template <class Condition, class Timeout = SensorTimeout, class Flag = flag::AwaitsSensor>
struct AwaitingSensor : msmf::state<> {
  using flag_list = boost::mpl::vector1<Flag>;
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    if (Condition::holds(*fsm.ctx, fsm)) {
      fsm.ctx->raise.sensor_report();
    } else {
      fsm.ctx->await_sensor(Timeout{}(fsm.ctx->config), Condition::awaited(*fsm.ctx));
    }
  }
  template <class Event, class Fsm>
  void on_exit(const Event&, Fsm& fsm) {
    fsm.ctx->ports.cancel_timer();
  }
};

}  // namespace fatc::machine
