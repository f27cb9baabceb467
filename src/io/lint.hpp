#pragma once

#include <cstddef>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "cli.hpp"

namespace fatc::io {

/// Rapid speed assumed without an INI, in mm per minute (and inch per minute).
constexpr double kAssumedRapidMm = 3000.0;
constexpr double kAssumedRapidInch = 120.0;

/// The machine's rapid speed for an estimate, in the config's units per
/// minute, and where it came from, in words ("rapids at 12000 mm/min
/// ([TRAJ]MAX_LINEAR_VELOCITY of sim.ini)"); assumed without an INI. nullopt
/// and `error` when the INI cannot be read.
struct RapidSpeed {
  double per_minute = 0.0;
  std::string source;
};
std::optional<RapidSpeed> rapid_speed(const std::optional<std::string>& ini_path,
                                      const Config& config, std::string& error);

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
