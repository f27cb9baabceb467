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

/// Where the program sets spindle 0 turning, as LinuxCNC's canon commands
/// motion from the interpreter's calls: M3 or M4 in force and a speed other
/// than 0 (S, or G96's D, which canon gives motion whatever S), reached by
/// M3, M4, an S word or M4 after M5; and every M19. Whatever the spindle holds then turns.
struct SpindleStart {
  Site where;
  std::size_t before_use = 0;  ///< how many tool uses the interpreter ran before it
  bool clockwise = true;       ///< M3 in force; false: M4
  bool orients = false;        ///< M19
  double speed = 0.0;          ///< the S in force
  double css_maximum = 0.0;    ///< G96's D in force (0: G97, or G96 without D)
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
