#pragma once

// What the modes read before they run: the config, the INI's soft limits,
// LinuxCNC's tool table, the rack of the state file; each problem one line.

#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/dry_run/simulator.hpp"
#include "core/rack/keepout.hpp"
#include "core/rack/tool_state.hpp"
#include "options.hpp"

namespace fatc::io {

/// The INI's soft limits in `units`; nullopt and one line on `err` when it
/// cannot be read. Its #INCLUDE problems go first on `err`, one line each,
/// counted in `problems`: they say why a key is missing.
std::optional<SoftLimits> read_limits(const std::string& ini_path, Units units, std::ostream& err,
                                      int& problems);

/// "config unreadable" or "config not valid": what kept an input from being checked.
std::string fault_of(const char* input, const std::string& path);

struct Loaded {
  std::optional<Config> config;
  std::optional<SoftLimits> limits;
  /// LinuxCNC's tool table (--tool-table, else the INI's) in the config's
  /// units: the lengths the sequences are checked with.
  ToolLengths lengths;
  std::optional<std::string> table_path;  ///< the table read, if any
  std::vector<std::string> table_skipped;  ///< what its lines say of themselves, "line N: why"
  std::map<int, double> measured;          ///< the state file's measured lengths
  /// Why the INI's tool table was not read (LinuxCNC starts without one).
  std::optional<std::string> table_unread;
  int problems = 0;  ///< lines written to `err`
  /// What an input kept from being checked, "INI unreadable: soft limits not checked".
  std::vector<std::string> not_checked;
};

/// LinuxCNC's tool table as the keep-out reads it: --tool-table, else the
/// INI's [EMCIO]TOOL_TABLE; each Z in `units` (the table is in the INI's).
struct TableRead {
  std::optional<std::string> path;  ///< none: no table named
  std::map<int, double> lengths;
  std::string error;  ///< why it could not be read, empty when it was
  std::vector<std::string> skipped;  ///< ToolTable::problems, as "line N: why"
};
TableRead read_table(const Options& options, Units units);

/// Reads the config and, if given, the INI; every problem one line on `err`.
Loaded load(const Options& options, std::ostream& err);

/// Whose rack --plan and --plot show: "the rack as at first start", "the rack as PATH has it".
std::string rack_words(const Options& options);

/// The rack at first start, or as --state has it (nothing uncertain, nothing
/// under way); nullopt and the line on `err` when the state file is bad.
std::optional<ToolState> rack_of(const Options& options, const Config& config, std::ostream& err);

/// "an empty spindle", "T3 in the spindle": the spindle a planned change starts from.
std::string spindle_words(int tool);

/// Why the changer refuses the planned change, if it does: its fail step's words.
std::optional<std::string> refusal(const Simulator& plan);

}  // namespace fatc::io
