#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gcode_scan.hpp"

namespace fatc::gcode {

/// How deep LinuxCNC nests subroutine calls: its INTERP_SUB_ROUTINE_LEVELS
/// (10) counts the main program too.
constexpr int kMaxCallDepth = 9;

/// A place in a program: a file as messages show it, and a line (0: the file).
struct Site {
  std::string file;
  int line = 0;
};

struct Finding {
  Site where;
  std::string text;
};

/// One M6 or M61, in the order the program runs them.
struct ToolUse {
  enum class Kind { change, set } kind = Kind::change;
  std::optional<int> tool;  ///< nullopt: no T before the M6, or a number computed at run time
  std::string written;      ///< "T3", "T#<tool>", "" (M6 without a T), "Q3" (M61)
  Site where;               ///< the M6 or M61
  bool in_flow = false;     ///< inside a loop or conditional, or a subroutine called from one
};

/// One file of the program, read.
struct SourceFile {
  std::string name;  ///< as messages show it
  ScannedFile scanned;
};

/// Where a walk finds the file of a subroutine the program calls (`name`.ngc).
class SubroutineFinder {
 public:
  virtual ~SubroutineFinder() = default;
  /// The file, scanned; nullptr and `why_not` ("not found beside the program")
  /// when there is none or it cannot be read.
  virtual const SourceFile* find(const std::string& name, std::string& why_not) = 0;
};

/// One REMAP line of the machine's INI: `REMAP = M400 modalgroup=10 ngc=m400`.
struct Remap {
  std::string code;    ///< "M400", "T", "G88.1": upper case
  std::string ngc;     ///< the NGC subroutine it runs, empty for a Python remap
  std::string python;  ///< the Python function it runs
};
/// nullopt when the line names no code.
std::optional<Remap> parse_remap(std::string_view line);

/// The subroutine of this changer's M6 remap.
constexpr const char* kOwnM6Remap = "fixed_atc_probe_m6";

struct WalkOptions {
  std::map<std::string, Remap> remaps;  ///< by code
  bool remaps_known =
      false;  ///< the INI was read: a code LinuxCNC lacks and no REMAP names is an error
  std::size_t max_blocks = 200000;    ///< events followed, calls included, before the walk gives up
  std::size_t max_tool_uses = 10000;  ///< M6 and M61 counted before the walk gives up
};

struct Walk {
  std::vector<ToolUse> uses;
  std::vector<Finding> problems;   ///< what LinuxCNC would refuse, parts not read
  std::vector<Finding> unknowns;   ///< what cannot be known without running the program
  std::vector<std::string> files;  ///< every file read, the program first
};

/// Follows the program from its first line as LinuxCNC would run it, without
/// evaluating anything: subroutine definitions are skipped, calls followed
/// (recursion once, at most kMaxCallDepth deep), every branch of a conditional
/// and every loop body taken once, until an M2/M30 outside any conditional.
Walk walk(const SourceFile& program, SubroutineFinder& finder, const WalkOptions& options);

}  // namespace fatc::gcode
