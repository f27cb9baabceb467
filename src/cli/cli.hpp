#pragma once

// The modes that run and end (--check, --plan, --lint ...): which runs, and
// what every one of them refuses first.

#include <iosfwd>
#include <string>

#include "options.hpp"

namespace fatc::io {

/// One line when a file the mode writes (--plot's drawing, the config's .bak
/// on --teach, the state file of --confirm and of the component) is one of the
/// files it reads, so that it would replace an input; empty otherwise.
std::string written_onto_input(const Options& options);

/// --check, --lint and --operator with --ini and no --state read the state
/// file the component reads: [FIXED_ATC_PROBE]STATE, from the INI's folder,
/// where LinuxCNC runs the HAL file that hands it to the component.
Options with_state_of_ini(Options options);

/// --confirm: 0 when the state file was rewritten with the operator's word.
/// --check: 0 when config, state and INI are valid and no planned move breaks
/// the keep-out or the soft limits, 1 otherwise. --plan: 0 printed, 1 refused or invalid. --dot: 0.
/// --lint: 0 clean, 1 problems found in the program, 2 an input it cannot read (see lint.hpp).
/// --teach: 0 written, 1 refused (nothing written), 2 the config or INI cannot be read or the
/// config cannot be written. --plot: 0 written, 1 the config or state is invalid or the
/// change refused, 2 the drawing cannot be written.
int run_tool_mode(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace fatc::io
