#pragma once

// A tool's measuring rule (`tools.N.measure`, else `probe_after_change`) and
// its check tolerance, asked in one place: the changer's flows and the
// preflight of a program ask them here.

#include <string>

#include "settings.hpp"

namespace fatc {

/// What `tool`'s measuring rule asks of the changer.
struct Measuring {
  MeasureRule rule = MeasureRule::off;
  /// M6 takes it to the sensor once it is in the spindle.
  bool after_change = false;
  /// That probe compares the length with the stored one (`check`) and
  /// writes nothing.
  bool checks = false;
  /// Nothing takes it to the sensor, a load or measure all neither: LinuxCNC's
  /// tool table has its length (`never`).
  bool never = false;
};
/// `known`: the changer has a length of `tool`.
Measuring measuring_of(const Config& config, int tool, bool known);

/// How far a checked tool's length may differ from the stored one, and the
/// key that says so: its own `tools.N.check_tolerance`, else `probe_check_tolerance`.
struct CheckTolerance {
  double length = 0.0;
  std::string key;
};
CheckTolerance check_tolerance_for(const Config& config, int tool);

}  // namespace fatc
