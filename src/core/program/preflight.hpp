#pragma once

#include <optional>
#include <string>
#include <vector>

#include "../config/config.hpp"
#include "../rack/point.hpp"
#include "tool_use.hpp"
#include "../plan/simulator.hpp"
#include "../plan/timing.hpp"
#include "../rack/tool_state.hpp"
#include "tool_table.hpp"

namespace fatc {

struct PreflightInput {
  const Config* config = nullptr;
  ToolState tools;                   ///< at the program's start
  std::string state_name;            ///< the state file, as messages show it
  const ToolTable* table = nullptr;  ///< LinuxCNC's tool table, when given
  std::string table_name;
  MachineTiming machine;  ///< for the estimate (change_time)
};

/// One M6 or M61 of the program, as the changer would meet it.
struct PreflightRow {
  program::ToolUse use;
  std::string code;               ///< "M6 T3", "M6", "M61 Q3"
  std::string where;              ///< "pocket 3", "manual: handed over at loading", ...
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
/// path).
Preflight preflight(const std::vector<program::ToolUse>& uses, const PreflightInput& input);

}  // namespace fatc
