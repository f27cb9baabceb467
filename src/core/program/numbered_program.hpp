#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "tool_table.hpp"

namespace fatc::program {

/// The longest line LinuxCNC reads (its LINELEN 255, less the line end):
/// a line numbered beyond it is left as it was.
constexpr std::size_t kMaxLineLength = 252;

/// Line numbers are written as N words from this on, far above what
/// programs write themselves (LinuxCNC reads N words up to 2^31-1).
constexpr long long kFirstLineNumber = 1000000000;
/// Lines numbered; a longer program is cut there.
constexpr int kMaxLines = 1000000000;

/// The program as the interpreter is given it: each line that holds code
/// starts with the N word kFirstLineNumber + its line number, so that the
/// canonical calls and the errors rs274 prints name their line (it prints the
/// N word of the line, not its number). An N word the line had is replaced;
/// N words change nothing else in LinuxCNC. An M2 on a line after the last
/// ends a program that has no end of its own (rs274 -n 0 would repeat its
/// error for ever, and a stopped rs274 loses what it had not yet written).
struct NumberedProgram {
  std::string text;
  /// Lines that read #5399, where M66 puts the input it waited for: known
  /// only on the running machine (rs274 reads 0).
  std::vector<int> input_lines;
  std::vector<LineNote> problems;  ///< a NUL byte: nothing is numbered (not a text file)
  int lines = 0;                   ///< lines of the program
};
NumberedProgram number_lines(std::string_view text);

/// The line number a numbered line starts with, 0 when it has none (a line
/// of another file, or one left as it was).
int line_of(std::string_view numbered_line);

}  // namespace fatc::program
