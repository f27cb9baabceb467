#pragma once

// A program run offline through rs274, as the machine would run it: what
// --lint reads and what measure all measures for "the tools of the loaded
// program"; and what such a run and an estimate (--plan, --lint) take of the
// machine's INI: the motion limits (assumed where it has none), the tool
// table, the remap.

#include <optional>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/dry_run/timing.hpp"
#include "core/program/interpreter_output.hpp"
#include "core/program/tool_use.hpp"
#include "core/rack/geometry.hpp"
#include "interpreter.hpp"

namespace fatc::io {

/// The motion assumed without an INI (or with one that lacks the axes'
/// limits), per second and per second squared: 3000 mm/min and 500 mm/s²
/// (120 inch/min and 20 inch/s²) on every axis.
constexpr double kAssumedVelocityMm = 50.0;
constexpr double kAssumedAccelerationMm = 500.0;
constexpr double kAssumedVelocityInch = 2.0;
constexpr double kAssumedAccelerationInch = 20.0;

/// The machine for an estimate (change_time), in the config's units: its
/// motion limits and [EMCIO]CYCLE_TIME, and where the limits came from, in
/// words ("the velocities and accelerations of sim.ini"); assumed without an
/// INI or when the INI lacks them. nullopt and `error` when the INI cannot be
/// read.
struct MachineMotion {
  MachineTiming timing;
  std::string source;
};
std::optional<MachineMotion> machine_motion(const std::optional<std::string>& ini_path,
                                            const Config& config, std::string& error);

/// What the INI adds: the motion limits, and whether M6 runs this changer's remap.
struct MachineIni {
  MachineMotion motion;   ///< the limits for the estimate, and where they came from
  bool remaps_m6 = true;     ///< false: the INI has no REMAP=M6 ... ngc=fixed_atc_probe_m6
  std::optional<std::string> tool_table;  ///< [EMCIO]TOOL_TABLE, from the INI's folder
  std::optional<double> units_per_mm;     ///< [TRAJ]LINEAR_UNITS: the tool table's units
  bool return_to_xy = false;              ///< [FIXED_ATC_PROBE]RETURN_TO_XY
  std::optional<SoftLimits> limits;       ///< [AXIS_n]MIN_LIMIT, MAX_LIMIT
  std::string limits_error;               ///< why there are none
  std::vector<std::string> builtin_m6_moves;  ///< [EMCIO] keys that move after every change
  std::vector<program::Finding> include_problems;  ///< IniFile's
};

/// Reads what a program run (--lint, the tools of the loaded program) uses of
/// the INI at `ini_path` (none: the motion assumed, nothing else); nullopt
/// and one line in `error` when it cannot be read.
std::optional<MachineIni> read_machine_ini(const std::optional<std::string>& ini_path,
                                           const Config& config, std::string& error);

/// `input` run through the rs274 find_rs274 names, the tool table without an
/// INI in the config's units; nullopt and one line in `error` when there is
/// no rs274 or an input cannot be read (run_interpreter).
std::optional<program::InterpreterRun> interpret(InterpreterInput input, const Config& config,
                                                 std::string& error);

/// The tools the program puts in the spindle (M6, M61) as LinuxCNC's
/// interpreter runs it with the INI (`ini_path`, may be empty) and its tool
/// table, in order of first use; nullopt and `error` when the program or the
/// INI cannot be read or rs274 cannot be run. What measure all measures for
/// "the tools of the loaded program". Takes as long as rs274 does (up to
/// kInterpreterSeconds): never on the component's poll loop.
std::optional<std::vector<int>> program_tools(const std::string& program_path,
                                              const std::string& ini_path, const Config& config,
                                              std::string& error);

}  // namespace fatc::io
