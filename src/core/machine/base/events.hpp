#pragma once

#include <optional>
#include <string>

#include "../../config/config.hpp"

namespace fatc {

/// The machine is on, homed and out of estop.
struct Ready {};
/// The machine went off, out of homing, or into estop.
struct NotReady {};
/// The executor finished the last published move.
struct InPosition {};
/// The executor finished the last published command (M61, G10): nothing moved.
struct CommandDone {};
/// The executor finished a probe move; `z` is the latched machine Z.
struct ProbeResult {
  bool touched = false;
  double z = 0.0;
  bool tripped_before = false;  ///< the sensor was already tripped: nothing moved
};
/// The timer the current state armed ran out.
struct TimerElapsed {};
/// The spindle started or stopped turning, or a wired sensor changed, or a
/// state asks for a fresh look at them; Context::machine.spindle_stopped and
/// Context::sensors hold the facts.
struct SensorReport {};
/// The operator pressed Continue (or Done).
struct OperatorContinue {};
/// The operator pressed Cancel.
struct OperatorCancel {};
/// LinuxCNC aborted the program or the executor failed.
struct Abort {
  std::string reason;
};
/// An event no state expected, or an exception in an action: a bug. The
/// changer faults, whatever it was doing.
struct InternalError {
  std::string reason;
};
/// A step the changer was about to publish breaks the rack keep-out or the
/// machine's soft limits: it was not published.
struct UnsafeStep {
  std::string reason;
};
/// A check of a wired sensor failed (raised by the leg that checked, queued
/// behind the current event): the changer faults. `uncertain`: it failed
/// after the chuck moved, so what the spindle holds is no longer a fact.
struct CheckFailed {
  std::string reason;
  bool uncertain = false;
};
/// A taught config.json (teach-pocket, teach-loading, ...): the changer works
/// with `config` from the next request on. Taken only while idle; otherwise
/// refused, named `request` ("teach safe") in the refusal.
struct ConfigChanged {
  Config config;
  std::string request;
};
/// The operator checked the spindle and says what it holds, and, when a
/// sequence was cut off at a pocket, whether that pocket holds its tool.
struct ClearFault {
  int spindle_tool = 0;
  std::optional<bool> pocket_holds_tool;
};

}  // namespace fatc
