#pragma once

#include <optional>
#include <string>
#include <vector>

#include "../config/config.hpp"
#include "../motion/point.hpp"
#include "tool_use.hpp"
#include "../dry_run/simulator.hpp"
#include "../dry_run/timing.hpp"
#include "../rack/keepout.hpp"
#include "../rack/tool_state.hpp"
#include "tool_table.hpp"

namespace fatc {

/// A tool length the program sets (G10 L1, L10, L11), in the config's units.
struct LengthSet {
  std::size_t before_use = 0;  ///< how many of the uses rs274 ran (ToolUse::ran) came before it
  int tool = 0;
  double length = 0.0;
};

struct PreflightInput {
  const Config* config = nullptr;
  ToolState tools;                   ///< at the program's start
  std::string state_name;            ///< the state file, as messages show it
  const ToolTable* table = nullptr;  ///< LinuxCNC's tool table, when given
  std::string table_name;
  MachineTiming machine;  ///< for the estimate (change_time)
  /// What each move of a planned change is checked with for the tool it
  /// carries: LinuxCNC's tool table (the INI's or --tool-table) and the
  /// longest the config allows (carried_lengths), and what the program sets
  /// before the change, in the order rs274 ran it.
  ToolLengths lengths;
  std::vector<LengthSet> lengths_set;
  /// The program's M3 and M4: one that turns a probe (`tools.N.kind`) is a problem.
  std::vector<program::SpindleStart> spindle_starts;
};

/// One M6 or M61 of the program, as the changer would meet it.
struct PreflightRow {
  program::ToolUse use;
  std::string code;               ///< "M6 T3", "M6", "M61 Q3"
  std::string where;              ///< "pocket 3", "manual: handed over at loading", ...
  std::string rule;               ///< the tool's measuring rule, rule_words(): "checked ±0.05"
  std::string length;             ///< "30.0000 mm (state file)", "never measured", ...
  std::optional<double> seconds;  ///< nullopt: not estimated
};

struct Preflight {
  std::vector<PreflightRow> rows;
  std::vector<program::Finding> problems;
  std::vector<int> tools;  ///< every tool the program puts in the spindle, in order of first use
  /// The tool of every M6 in the order LinuxCNC runs them, repeats and T0
  /// included; nullopt where it is not known.
  std::vector<std::optional<int>> order;
  int changes = 0;         ///< M6 that change the tool (not to the tool already in the spindle)
  int manual = 0;          ///< of them, to a manual tool
  int not_estimated = 0;   ///< of them, with a tool or spindle not known
  int operator_waits = 0;  ///< waits for the operator in the estimated changes
  double seconds = 0.0;    ///< estimated time of all estimated changes
};

/// Follows the program's tool uses, as LinuxCNC's interpreter ran them,
/// through the rack (ToolState), the lengths (state file, or the tool table
/// when given) and the planned steps of each change (plan_change, the --plan
/// path), each move of which must keep the tip of the tool it carries out
/// of the holders (check_steps, from safe as --check plans it).
Preflight preflight(const std::vector<program::ToolUse>& uses, const PreflightInput& input);

}  // namespace fatc
