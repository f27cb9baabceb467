#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "../config/config.hpp"
#include "../rack/tool_state.hpp"

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
  /// a whole number beyond an int), left out of `tools`; tools listed twice;
  /// lines LinuxCNC reads in pieces.
  std::vector<LineNote> problems;
};

/// Reads a tool table as LinuxCNC's tooldata_read_entry does: `;` starts a
/// comment, fields are separated by spaces, each a letter (T P D X Y Z A B C
/// U V W I J Q, either case) and a number read with sscanf; a line with a bad
/// field is skipped whole, and so is one whose numbers mean nothing. A line
/// over 255 characters is read as LinuxCNC's fgets reads it, 255 at a time,
/// each piece a line (a tool from its start, a field or the comment cut),
/// with one note saying what it read. Never throws.
ToolTable parse_tool_table(std::string_view text);

/// The Z of each tool `table` gives one, in `units`: the table is in the
/// machine's units, `machine_per_mm` of them to the mm. The keep-out's
/// lengths (ToolLengths::table), for --check, --plan, --teach and the component.
std::map<int, double> tool_lengths(const ToolTable& table, Units units, double machine_per_mm);

/// A tool whose P the rack map changed.
struct PocketChange {
  int tool = 0;
  std::optional<int> was;  ///< the P the table gave it; nullopt: the line had none
  int pocket = 0;          ///< the P written: its pocket, 0 for a tool outside the rack
  bool operator==(const PocketChange& other) const {
    return tool == other.tool && was == other.was && pocket == other.pocket;
  }
};

struct PocketRewrite {
  std::string text;                   ///< the table with the rack's pockets in P
  std::vector<PocketChange> changes;  ///< in the order of the lines
  /// Each tool's P in `text`, as its first line gives it (nullopt: none).
  std::map<int, std::optional<int>> p_of;
};

/// The rack map in the P column of a tool table (LinuxCNC keeps P for
/// bookkeeping with RANDOM_TOOLCHANGER = 0, and every GUI's tool page shows
/// it): a tool that belongs in a pocket gets that pocket's number, whether it
/// sits there or in the spindle; a tool outside the rack whose P names a
/// pocket of the rack gets P0, so that no pocket shows two tools. Only the P
/// field of those lines changes (one with none gets it after its T); every
/// other line, field, space and comment stays byte for byte, lengths
/// included. A rack tool the table has no line for gets none: a line would
/// give LinuxCNC a tool with no length, and the table is the operator's.
PocketRewrite with_rack_pockets(std::string_view text, const ToolState& tools);

/// The operator's line when the table's P disagreed with the changer's map
/// (a P edited in a GUI): where the changer has each tool, what the table
/// said, and how a tool really moves to another pocket.
std::string pocket_disagreement_words(const std::vector<PocketChange>& changes);

}  // namespace fatc
