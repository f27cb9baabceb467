#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "tool_use.hpp"

namespace fatc::program {

/// Interpreter errors kept; the rest are counted.
constexpr std::size_t kMaxErrors = 1000;

/// Reads what rs274 prints of a program numbered by number_lines: the
/// canonical calls on its standard output, one a line
/// (`   12 N1000000004 SELECT_TOOL(3)`), and on its standard error each
/// error's message followed by the text of its line.
class InterpreterOutput {
 public:
  /// `program`: the name messages give the program; `numbered_path`: the
  /// file rs274 read, shown as `program` where a message names it;
  /// `tool_of_row`: InterpreterTable's; `input_lines` and `lines`: NumberedProgram's.
  InterpreterOutput(std::string program, std::string numbered_path, std::vector<int> tool_of_row,
                    std::vector<int> input_lines, int lines);

  /// One line of the standard output, without its line end.
  void canonical_call(std::string_view line);
  /// One line of the standard error, without its line end.
  void error_line(std::string_view line);
  /// What was read, once both streams have ended.
  InterpreterRun finish();
  /// Whether rs274 met the end of a program without M2, M30 or %: with -n 0
  /// it then repeats that error for ever, and is stopped.
  bool past_the_end() const { return past_the_end_; }

 private:
  void use(ToolUse::Kind kind, std::optional<int> tool, int line);
  void error(int line, const std::string& message, std::string_view text);
  bool reads_input(int line) const;
  void unknown(int line, const std::string& text);

  std::string program_;
  std::string numbered_path_;
  std::vector<int> tool_of_row_;
  std::vector<int> input_lines_;  ///< sorted
  InterpreterRun run_;
  int line_ = 0;                   ///< of the last call that named one
  std::optional<int> selected_;    ///< the last T, nullopt when it is not known
  int selected_line_ = 0;          ///< its line, 0 in a subroutine file
  bool any_selected_ = false;
  bool said_no_t_ = false;
  std::vector<int> inputs_said_;
  std::optional<std::string> pending_message_;
  std::vector<ToolUse> unknown_changes_;  ///< M6 on lines the interpreter could not run
  std::size_t errors_not_kept_ = 0;
  bool past_the_end_ = false;
  int lines_ = 0;
  bool said_no_end_ = false;
};

/// Whether a line's text holds an M6 word (M6, m06, outside comments and
/// parameter names): a line the interpreter refused may change the tool.
bool holds_m6(std::string_view line);

}  // namespace fatc::program
