#pragma once

#include <iosfwd>
#include <string>

#include "core/dry_run/timing.hpp"
#include "options.hpp"

namespace fatc::io {

/// What an estimate counts besides the moves, in words, for --lint and --plan.
std::string estimate_costs_text(const MachineTiming& timing);

/// "12.3 s", or "2 min 05 s" from a minute on.
std::string seconds_text(double seconds);

/// --lint: runs the program named in `options` through LinuxCNC's own
/// interpreter (rs274, with the INI and tool table given: linuxcnc/offline/interpreter.hpp),
/// not the machine, and reports its tool changes against the config, the
/// state file, the tool table and the INI's rapid speed: which tools, where
/// each is, which were never measured, what only the running machine knows,
/// what LinuxCNC or the changer would refuse, and the estimated change time.
/// Returns 0 when no problem was found, 1 when one was (every problem one
/// line on `out`), 2 when the program, config, state, tool table or INI
/// cannot be read or rs274 cannot be run (one line each on `err`).
int lint(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace fatc::io
