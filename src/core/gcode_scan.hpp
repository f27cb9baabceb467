#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace fatc::gcode {

/// The longest line LinuxCNC reads: its buffer (LINELEN 255) holds 254
/// characters with the line ending, and it refuses a line that fills it
/// ("Command too long").
constexpr std::size_t kMaxLineLength = 252;
/// How many problems one file reports before the reader gives up on it.
constexpr std::size_t kMaxProblemsPerFile = 20;

/// A word's value: a number written out, or something LinuxCNC computes when
/// it runs the line (a parameter, an expression, a function).
struct Value {
  bool literal = false;
  double number = 0.0;  ///< the literal's value
  std::string text;     ///< as LinuxCNC reads it: lower case, no spaces ("3.", "#<tool>")
};

/// The keyword after an o-word.
enum class OWord {
  sub,
  endsub,
  call,
  do_loop,
  while_loop,  ///< opens a loop, or closes an `o.. do`
  repeat,
  if_block,
  elseif,
  else_block,
  endif,
  break_loop,
  continue_loop,
  endwhile,
  endrepeat,
  return_sub,
};

/// One thing a line does that matters to a tool changer, in the order
/// LinuxCNC executes it within the line (T before M6 and M61).
struct Event {
  enum class Kind {
    select_tool,  ///< a T word: `value`
    change_tool,  ///< M6
    set_tool,     ///< M61 Q`value`: LinuxCNC is told what the spindle holds
    o_word,       ///< `o_word` of the o-word (or M98 P, bare O, M99 in a sub) named `name`
    end,          ///< M2, M30, M99 outside a subroutine, the closing %: `name` says which
    code,         ///< an M or G code LinuxCNC does not define itself, or M100-M199: `name`
  } kind = Kind::code;
  int line = 0;               ///< from 1, in its file
  bool block_delete = false;  ///< the line starts with `/`
  OWord o_word = OWord::call;
  std::string name;  ///< o-word as LinuxCNC names it ("probe" for o<Probe>, "100"); "M101", "G66"
  Value value;
};

struct LineNote {
  int line = 0;  ///< 0: the file as a whole
  std::string text;
};

/// What one G-code file says, read without running it.
struct ScannedFile {
  std::vector<Event> events;
  /// Lines LinuxCNC would refuse, and parts of the file not read.
  std::vector<LineNote> problems;
  /// Subroutine name -> index in `events` of its `sub`; its body runs to the matching endsub.
  std::map<std::string, std::size_t> subs;
  /// Subroutine name -> index in `events` of its `endsub` (or the end of the events).
  std::map<std::string, std::size_t> sub_ends;
  int lines = 0;  ///< lines read
};

/// Reads one file's text as LinuxCNC's interpreter would (case, spaces,
/// comments, block delete, line numbers, `%`, o-words), stopping at the
/// closing `%`, at a NUL byte or after kMaxProblemsPerFile problems. Lines
/// after M2/M30 count only inside subroutine definitions. Never throws on
/// any input; linear in the text's length.
ScannedFile scan(std::string_view text);

/// "o<probe>", "o100": an o-word name as a program writes it, for messages.
std::string o_word_name(const std::string& name);

}  // namespace fatc::gcode
