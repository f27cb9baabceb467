#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace fatc::program {

/// A place in a program: a file as messages show it, and a line (0: none known).
struct Site {
  std::string file;
  int line = 0;
};

struct Finding {
  Site where;
  std::string text;
};
/// A Finding built step by step: GCC 12 at -O3 takes the nested braces of a
/// temporary for uninitialized strings (-Wmaybe-uninitialized).
inline Finding finding(const std::string& file, int line, std::string text) {
  Finding found;
  found.where.file = file;
  found.where.line = line;
  found.text = std::move(text);
  return found;
}

/// One M6 or M61, in the order LinuxCNC's interpreter ran them.
struct ToolUse {
  enum class Kind { change, set } kind = Kind::change;
  std::optional<int> tool;  ///< nullopt: known only when the program runs on the machine
  /// An M6's T word's line (a remapped M6 runs in its subroutine), an
  /// M61's own; 0 in a subroutine file of the program's.
  Site where;
  /// false: an M6 on a line rs274 could not run (a HAL pin), put where a
  /// program without loops would have it; a CallListener was not told of it.
  bool ran = true;
};

/// An M3, M4 or M19 LinuxCNC's interpreter ran: whatever the spindle holds then turns.
struct SpindleStart {
  Site where;
  std::size_t before_use = 0;  ///< how many tool uses the interpreter ran before it
  bool clockwise = true;       ///< M3; false: M4
  bool orients = false;        ///< M19
  double speed = 0.0;          ///< the S in force (0: nothing turns)
};

/// What LinuxCNC's interpreter made of a program.
struct InterpreterRun {
  std::vector<ToolUse> uses;
  std::vector<SpindleStart> spindle_starts;  ///< at most kMaxToolUses
  std::vector<Finding> problems;  ///< where the interpreter stopped, or the run was cut short
  std::vector<Finding> unknowns;  ///< what only the running machine knows
  std::size_t uses_not_kept = 0;  ///< tool uses beyond kMaxToolUses, counted only
};

/// Tool uses kept; a program that makes more is still read to its end.
constexpr std::size_t kMaxToolUses = 10000;

}  // namespace fatc::program
