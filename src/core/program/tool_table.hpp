#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "../config/config.hpp"

namespace fatc {

/// Something said of one line of a file (0: the file as a whole).
struct LineNote {
  int line = 0;
  std::string text;
};

/// One tool of LinuxCNC's tool table file (`T3 P3 Z40.0 D10.0 ;comment`).
struct ToolTableEntry {
  int tool = 0;
  std::optional<double> z;  ///< the length offset (Z); nullopt when the line has none
  int line = 0;
  std::vector<std::string> fields;  ///< as the line writes them ("T3", "Z40.0")
};

struct ToolTable {
  std::map<int, ToolTableEntry> tools;  ///< by tool number; the first line of a tool listed twice
  /// Lines LinuxCNC skips ("Unrecognized line skipped"), lines with a number
  /// LinuxCNC would read but no tool can have (NaN, infinite, over 100000 either way,
  /// a whole number beyond an int), left out of `tools`; tools listed twice.
  std::vector<LineNote> problems;
};

/// Reads a tool table as LinuxCNC's tooldata_read_entry does: `;` starts a
/// comment, fields are separated by spaces, each a letter (T P D X Y Z A B C
/// U V W I J Q, either case) and a number read with sscanf; a line with a bad
/// field is skipped whole, and so is one whose numbers mean nothing. Never throws.
ToolTable parse_tool_table(std::string_view text);

/// The Z of each tool `table` gives one, in `units`: the table is in the
/// machine's units, `machine_per_mm` of them to the mm. The keep-out's
/// lengths (ToolLengths::table), for --check, --plan, --teach and the component.
std::map<int, double> tool_lengths(const ToolTable& table, Units units, double machine_per_mm);

}  // namespace fatc
