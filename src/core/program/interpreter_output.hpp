#pragma once

#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "numbered_program.hpp"
#include "tool_use.hpp"

namespace fatc::program {

/// Interpreter errors kept: the next one stops the run (LinuxCNC stops at
/// the first; what rs274 -n 0 reads after a thousand is worth less than the
/// time it may take).
constexpr std::size_t kMaxErrors = 1000;

/// What InterpreterOutput needs to know of the program rs274 was given.
struct ProgramGiven {
  std::string name;           ///< as messages show it
  std::string numbered_path;  ///< the numbered copy rs274 read, shown as `name` in a message
  /// The folder of the empty subroutine files the program's undefined calls
  /// find (LineNumberer::undefined_calls); empty when there is none.
  std::string stub_folder;
  LineSet input_lines;  ///< LineNumberer's
  int lines = 0;        ///< LineNumberer's
};

/// What else reads the canonical calls as rs274 prints them (the rack
/// keep-out check), told of each as InterpreterOutput reads it.
class CallListener {
 public:
  virtual ~CallListener() = default;
  /// A call without its line number and count (`STRAIGHT_TRAVERSE(1.0000, ...)`),
  /// on `line`: its own, or, for a call of a subroutine file (`numbered`
  /// false), the program's line that ran it: the last line a call named
  /// (LineNumberer's kRunsSubroutine names the line before its subroutine runs).
  virtual void call(int line, bool numbered, std::string_view call) = 0;
  /// An M6 or M61 as InterpreterOutput reads it, kept or not.
  virtual void tool_use(const ToolUse& use) = 0;
};

/// Reads what rs274 prints of a program numbered by LineNumberer: the
/// canonical calls on its standard output, one a line
/// (`   12 N1000000004 SELECT_TOOL(3)`), and on its standard error each
/// error's message followed by the text of its line. Keeps at most
/// kMaxToolUses uses and kMaxErrors errors and unknowns, whatever it is fed.
class InterpreterOutput {
 public:
  /// `tool_of_row`: InterpreterTable's.
  InterpreterOutput(ProgramGiven program, std::vector<int> tool_of_row);

  /// One line of the standard output, without its line end.
  void canonical_call(std::string_view line);
  /// One line of the standard error, without its line end.
  void error_line(std::string_view line);
  /// What was read, once both streams have ended.
  InterpreterRun finish();
  /// Whether nothing more of rs274 is wanted, and it is stopped: it met the
  /// end of a program without M2, M30 or % (with -n 0 it then repeats that
  /// error for ever), or one error more than kMaxErrors.
  bool done() const { return past_the_end_ || stopped_at_.has_value(); }
  /// The line of the last canonical call that named one (0: none yet).
  int line() const { return line_; }
  /// Tells `listener` (which outlives this) of every call and tool use from now on.
  void listen(CallListener* listener) { listener_ = listener; }

 private:
  void use(ToolUse::Kind kind, std::optional<int> tool, int line);
  void error(int line, const std::string& message, std::string_view text);
  bool reads_input(int line) const;
  void unknown(int line, const std::string& text);

  std::string message_of(const std::string& message, int line) const;

  ProgramGiven program_;
  std::vector<int> tool_of_row_;
  /// Spindle 0 as canon last commanded motion: set by START_SPINDLE_*,
  /// SET_SPINDLE_SPEED and STOP_SPINDLE_TURNING; SET_SPINDLE_MODE only
  /// changes what the next of them commands.
  struct Spindle {
    int direction = 0;  ///< 1 M3, -1 M4, 0 stopped
    double speed = 0.0;
    double css_maximum = 0.0;
    bool turning = false;  ///< as last commanded
  } spindle_;
  /// A command to spindle 0 reaches motion: a start where it begins to turn.
  void spindle_commanded();
  InterpreterRun run_;
  int line_ = 0;                   ///< of the last call that named one
  std::optional<int> selected_;    ///< the last T, nullopt when it is not known
  int selected_line_ = 0;          ///< its line, 0 in a subroutine file
  bool any_selected_ = false;
  bool said_no_t_ = false;
  std::set<int> inputs_said_;  ///< at most kMaxErrors
  std::optional<std::string> pending_message_;
  /// M6 on lines the interpreter could not run; with run_.uses at most kMaxToolUses.
  std::vector<ToolUse> unknown_changes_;
  std::optional<int> stopped_at_;  ///< the line of the error beyond kMaxErrors
  bool past_the_end_ = false;
  bool said_no_end_ = false;
  CallListener* listener_ = nullptr;
};

/// Whether a line's text holds an M6 word (M6, m06, outside comments and
/// parameter names): a line the interpreter refused may change the tool.
bool holds_m6(std::string_view line);

}  // namespace fatc::program
