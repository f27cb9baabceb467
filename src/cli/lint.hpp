#pragma once

#include <cstddef>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "cli.hpp"
#include "core/dry_run/timing.hpp"

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

/// What an estimate counts besides the moves, in words, for --lint and --plan.
std::string estimate_costs_text(const MachineTiming& timing);

/// "12.3 s", or "2 min 05 s" from a minute on.
std::string seconds_text(double seconds);

/// --lint: runs the program named in `options` through LinuxCNC's own
/// interpreter (rs274, with the INI and tool table given: interpreter.hpp),
/// not the machine, and reports its tool changes against the config, the
/// state file, the tool table and the INI's rapid speed: which tools, where
/// each is, which were never measured, what only the running machine knows,
/// what LinuxCNC or the changer would refuse, and the estimated change time.
/// Returns 0 when no problem was found, 1 when one was (every problem one
/// line on `out`), 2 when the program, config, state, tool table or INI
/// cannot be read or rs274 cannot be run (one line each on `err`).
int lint(const Options& options, std::ostream& out, std::ostream& err);

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
