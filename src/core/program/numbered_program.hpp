#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tool_table.hpp"

namespace fatc::program {

/// The longest line LinuxCNC reads (its LINELEN 255, less the line end).
constexpr std::size_t kMaxLineLength = 252;

/// Line numbers are written as N words from this on, far above what
/// programs write themselves (LinuxCNC reads N words up to 2^31-1).
constexpr long long kFirstLineNumber = 1000000000;
/// Lines numbered; a longer program is cut there.
constexpr int kMaxLines = 1000000000;
/// Subroutine names kept of the calls and definitions of a program; the
/// calls beyond are left to rs274's own search.
constexpr std::size_t kMaxSubroutineNames = 10000;

/// The comment LineNumberer puts on a line of its own, numbered as the line
/// after it, before a line that may run a subroutine (an o-call, or an M-code
/// an INI may remap, M310, M101): its subroutine's calls, which rs274 prints without a
/// number, come after it and so are shown on its line.
constexpr std::string_view kRunsSubroutine = "fixed_atc_probe: this line runs a subroutine";

/// A set of line numbers, one bit a line up to the highest: bounded by the
/// program's lines whatever the program.
class LineSet {
 public:
  void insert(int line);
  bool contains(int line) const;

 private:
  std::vector<bool> bits_;
};

/// The program as the interpreter is given it, made piece by piece as the
/// file is read (neither the program nor its numbered copy is ever whole in
/// memory): each line that holds code starts with the N word kFirstLineNumber
/// + its line number, so that the canonical calls and the errors rs274 prints
/// name their line (it prints the N word of the line, not its number), and a
/// line that may run a subroutine has kRunsSubroutine before it. An N
/// word the line had is replaced; N words change nothing else in LinuxCNC. An
/// M2 on a line after the last ends a program that has no end of its own
/// (rs274 -n 0 would repeat its error for ever, and a stopped rs274 loses what
/// it had not yet written). A line that fits LinuxCNC only unnumbered loses
/// its own N word instead, which could name another line; a line too long for
/// LinuxCNC is numbered all the same (LinuxCNC refuses it and prints its start).
class LineNumberer {
 public:
  /// The next piece of the program.
  void add(std::string_view piece);
  /// The end of the program; `cut`: the file goes on beyond what was read,
  /// and its last line, cut in the middle, is dropped.
  void finish(bool cut);
  /// The numbered text made since the last call, handed over.
  std::string take_text();
  std::size_t text_size() const { return text_.size(); }

  /// A NUL byte: not a text file, nothing of it is to be read.
  const std::optional<LineNote>& nul() const { return nul_; }
  /// Lines that read #5399, where M66 puts the input it waited for: known
  /// only on the running machine (rs274 reads 0).
  const LineSet& input_lines() const { return input_lines_; }
  int lines() const { return lines_; }
  /// Bytes of the whole lines read (what the interpreter is given of a cut file).
  std::uint64_t bytes() const { return whole_bytes_; }
  /// The subroutines the program calls (`o<name> call`, `o100 call`, names as
  /// LinuxCNC reads them: lower case, no blanks) and never defines itself
  /// (`o<name> sub`), sorted; only names that can be file names (letters,
  /// digits, `_`, `-`, `.`, not first), at most kMaxSubroutineNames.
  std::vector<std::string> undefined_calls() const;

 private:
  void end_line();
  void line_of_code(std::string_view line);
  /// Not blank, not a '%' line: a line to number.
  static bool holds_code(std::string_view line);
  /// Where the line's own N word starts and ends (start == end: none).
  static std::pair<std::size_t, std::size_t> own_line_number(std::string_view line);
  /// The line with `number` as its N word in place of its own.
  void append_numbered(std::string_view line, int number);
  /// Notes the subroutine the line calls or defines; whether it may run one.
  bool note_subroutine(std::string_view line);

  std::string text_;
  std::string line_;        ///< the line under way while it may still be numbered
  bool passing_ = false;    ///< the line under way is too long: its rest passed on as it is
  std::size_t column_ = 0;  ///< bytes of the line under way
  std::uint64_t whole_bytes_ = 0;
  int lines_ = 0;
  bool ended_ = false;  ///< a NUL byte, kMaxLines or finish(): nothing more is taken
  std::optional<LineNote> nul_;
  LineSet input_lines_;
  std::set<std::string> called_;
  std::set<std::string> defined_;
};

/// The line number a numbered line starts with, 0 when it has none (a line
/// of another file, or one left as it was).
int line_of(std::string_view numbered_line);

}  // namespace fatc::program
