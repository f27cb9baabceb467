#pragma once

// What the machine's INI says of the changer beyond its limits (ini.hpp):
// the executor's section and LinuxCNC's own M6 (--check), the user M-codes
// (a program run offline).

#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "ini.hpp"

namespace fatc::io {

/// [FIXED_ATC_PROBE] as hal/fixed_atc_probe.hal and the NGC step executor
/// read it, one line per problem: every key there, the motion pin numbers two
/// digits as in the pin names, the analog outputs different, RETURN_TO_XY 0
/// or 1, STEP_TIMEOUT a number of seconds longer than every wait of `config`
/// (when given) between two steps, which the executor would take for a
/// component that stopped answering. Nothing when the INI has no key of the
/// section at all (an INI checked for its limits only).
std::vector<std::string> executor_problems(const IniFile& ini, const Config* config);

/// The [EMCIO] keys that make LinuxCNC's own M6, which the changer's remap
/// calls once its change ends at safe, move the machine after every change:
/// TOOL_CHANGE_POSITION (a rapid there, canon's CHANGE_TOOL),
/// TOOL_CHANGE_QUILL_UP (Z up to machine zero) and TOOL_CHANGE_AT_G30 (to
/// the G30 position), the two from the interpreter before CHANGE_TOOL; 2.9
/// and 2.10 read them from [EMCIO] only. One line each, without the path:
/// "[EMCIO]TOOL_CHANGE_POSITION (line 12): ...". TOOL_CHANGE_WITH_SPINDLE_ON
/// is not named: the remap stops the spindle itself.
std::vector<std::string> builtin_m6_moves(const IniFile& ini);

/// A folder of the INI as LinuxCNC's IniFile::TildeExpansion gives it:
/// `~/` at its start is $HOME's, anything else as it is.
std::string tilde_expanded(const std::string& folder);

/// The user M-codes (100-199) LinuxCNC's task finds for the INI, as it looks
/// for them when it starts: an executable named M1nn in [DISPLAY]PROGRAM_PREFIX
/// (else nc_files) or in one of the first five folders of
/// [RS274NGC]USER_M_PATH (':' between, `~/` for $HOME), each from `folder`
/// (the INI's, where LinuxCNC runs).
std::vector<int> user_m_codes(const IniFile& ini, const std::string& folder);

}  // namespace fatc::io
