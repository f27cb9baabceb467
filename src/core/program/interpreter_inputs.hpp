#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tool_table.hpp"

namespace fatc::program {

/// The tool table as rs274 is given it, and how to read its canonical calls:
/// CHANGE_TOOL and CHANGE_TOOL_NUMBER name a tool by its row in the table
/// (from 1, 0 for no tool), not by its number.
struct InterpreterTable {
  std::string text;
  std::vector<int> tool_of_row;  ///< [row] -> tool number; [0] is 0
};

/// The machine's tools, each on one row in order of tool number, LinuxCNC's
/// own lines otherwise (what it skips left out); lengths and diameters (X Y
/// Z U V W D) times `length_scale` (rs274 reads them as inches whatever the
/// machine's units: sim.tbl's Z40 was a G43 of 1016 mm).
InterpreterTable interpreter_table(const ToolTable& table, double length_scale);

/// The machine's parameter file (`5221\t12.5`, one a line) as rs274 is given
/// it: the lengths of G28, G30, G92 and G54-G59.3 (X Y Z U V W) times
/// `length_scale`, as interpreter_table's (a G54 X12.5 of a mm machine was
/// 317.5 mm to rs274); every other line as it is.
std::string interpreter_parameters(std::string_view text, double length_scale);

/// Without a tool table (--lint without --tool-table and --ini): rs274
/// refuses a tool its table lacks, so it is given tools 1 to this (a table
/// holds at most 1000 tools: its CANON_POCKETS_MAX).
constexpr int kToolsWithoutTable = 1000;
InterpreterTable any_tool_table();

/// Whether a REMAP line's value (`M6 modalgroup=6 ngc=fixed_atc_probe_m6`)
/// is this changer's M6.
bool is_own_m6_remap(std::string_view remap);

/// The subroutine the preflight's interpreter runs in place of the
/// machine's, by name, with its text (written to a folder of
/// ini_for_preflight's `folders`): fixed_atc_probe_preflight_m6, for this
/// changer's M6. rs274 runs the remap's preview branch, which only tells the
/// interpreter of the new tool, where the machine's run stops the spindle
/// first and ends in G43. The stand-in does all three, so every offset rs274
/// prints, every move it works out through them (G53, G28, G92, G10 L20),
/// and the spindle after the change are the machine's.
struct StandIn {
  std::string name;
  std::string text;
};
std::vector<StandIn> preflight_stand_ins();

/// A Python file for the INI's [PYTHON]TOPLEVEL that tells rs274 of the
/// user M-codes `codes` (100-199, executables of USER_M_PATH) as LinuxCNC's
/// task tells its interpreter (USER_DEFINED_FUNCTION, which rs274 shows):
/// each a function that does nothing, so M101 P1 Q2 reads as on the machine
/// and runs nothing. (A REMAP of M100-M199 is never run in 2.9: those codes
/// are not remappable.) Then it runs the INI's own TOPLEVEL, `own_toplevel`,
/// into the same namespace, as the plugin would have.
std::string user_m_code_module(const std::vector<int>& codes,
                               const std::optional<std::string>& own_toplevel);

/// The machine's INI text as the preflight's interpreter reads it: HAL pins
/// off (`HAL_PIN_VARS = 0`: with a LinuxCNC running, rs274 would read its live
/// pins, and a tool from a pin is known only when the program runs), and, when
/// given, `folders` (':' between) as its SUBROUTINE_PATH. LinuxCNC takes the
/// first of a key, so the lines go first in [RS274NGC] (a new section when
/// there is none), one folder a line (a line ending in a backslash goes on in
/// the next: LinuxCNC reads at most 255 characters of a line). `folders` ends
/// with the INI's own. The changer's M6 remap runs its stand-in; with
/// `python_toplevel` (user_m_code_module's file), [PYTHON]TOPLEVEL is that.
std::string ini_for_preflight(std::string_view ini_text, const std::string& folders,
                              const std::string& python_toplevel = "");

/// The longest folder ini_for_preflight can give rs274 on a line of its own.
constexpr std::size_t kMaxFolderLength = 250;

}  // namespace fatc::program
