#pragma once

#include <ostream>
#include <streambuf>
#include <string>
#include <string_view>
#include <vector>

#include "core/config/quote.hpp"

namespace fatc::io {

/// `line` safe to show on a terminal: a C0 control character other than tab
/// and newline, DEL, a C1 control and a byte that is not UTF-8 become visible
/// escapes (\r, \x1b, \u{009b}, \xff), so that no text a file held can clear,
/// recolour or move about the terminal it is printed on. An escape sequence
/// is left as its harmless letters after the visible \x1b.
std::string terminal_safe(std::string_view line);

/// Passes text on to `out` a line at a time, each line made terminal_safe
/// and cut to kMaxMessageLine characters: no line the command line prints is
/// longer, or acts on the terminal, whatever a file held.
class CappedLines : public std::streambuf {
 public:
  explicit CappedLines(std::ostream& out) : out_(out) {}
  ~CappedLines() override { sync(); }

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    line_ += traits_type::to_char_type(c);
    if (c == '\n') sync();
    return c;
  }
  int sync() override {
    out_ << capped_lines(terminal_safe(line_));
    line_.clear();
    return out_.flush() ? 0 : -1;
  }

 private:
  std::ostream& out_;
  std::string line_;
};

/// How many lines of one list of a file's problems (a tool table's skipped
/// lines, the violations) are printed before the rest are only counted.
constexpr std::size_t kMaxListedLines = 50;

/// `lines`, each indented on a line of its own: the first kMaxListedLines,
/// then "... and N more" for the rest, so that a file of 100,000 problems
/// prints a screenful.
void print_capped(std::ostream& out, const std::vector<std::string>& lines);

}  // namespace fatc::io
