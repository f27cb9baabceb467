#include "numbered_program.hpp"

#include <cctype>

namespace fatc::program {
namespace {

bool blank(char c) { return c == ' ' || c == '\t'; }

/// Whether the line reads #5399: LinuxCNC drops spaces inside words, so
/// "# 5399" is the same parameter.
bool reads_m66_input(std::string_view line) {
  if (line.find('9') == std::string_view::npos) return false;
  std::string packed;
  for (const char c : line) {
    if (!blank(c)) packed.push_back(c);
  }
  for (std::size_t at = packed.find("#5399"); at != std::string::npos;
       at = packed.find("#5399", at + 1)) {
    const std::size_t after = at + 5;
    if (after == packed.size() ||
        (!std::isdigit(static_cast<unsigned char>(packed[after])) && packed[after] != '.')) {
      return true;
    }
  }
  return false;
}

}  // namespace

NumberedProgram number_lines(std::string_view text) {
  NumberedProgram numbered;
  if (const auto nul = text.find('\0'); nul != std::string_view::npos) {
    const std::string_view before = text.substr(0, nul);
    int line = 1;
    std::size_t line_start = 0;
    for (std::size_t i = 0; i < before.size(); ++i) {
      if (before[i] == '\n') {
        ++line;
        line_start = i + 1;
      }
    }
    numbered.problems.push_back(
        {line, "NUL byte at column " + std::to_string(nul - line_start + 1) +
                   ": not a G-code text file (LinuxCNC stops reading a line at a NUL); "
                   "nothing of it read"});
    return numbered;
  }
  numbered.text.reserve(text.size() + text.size() / 4);
  int number = 0;
  std::size_t start = 0;
  while (start < text.size() && number < kMaxLines) {
    std::size_t end = text.find('\n', start);
    const bool last = end == std::string_view::npos;
    if (last) end = text.size();
    const std::string_view line = text.substr(start, end - start);
    start = end + 1;
    ++number;
    if (reads_m66_input(line)) numbered.input_lines.push_back(number);
    std::size_t at = 0;
    while (at < line.size() && blank(line[at])) ++at;
    // '%' marks the program's ends; a blank line holds nothing to number.
    const bool code = at < line.size() && line[at] != '%' && line[at] != '\r';
    const std::size_t size_before = numbered.text.size();
    if (code) {
      if (line[at] == '/') ++at;  // block delete comes first, before any N word
      numbered.text.append(line.substr(0, at));
      numbered.text += "N" + std::to_string(kFirstLineNumber + number) + " ";
      if (at < line.size() && (line[at] == 'n' || line[at] == 'N')) {
        ++at;
        // LinuxCNC reads "N50.5" as a line number too.
        while (at < line.size() && (blank(line[at]) || line[at] == '.' ||
                                    std::isdigit(static_cast<unsigned char>(line[at])))) {
          ++at;
        }
      }
      numbered.text.append(line.substr(at));
      if (numbered.text.size() - size_before > kMaxLineLength) {
        numbered.text.resize(size_before);
        numbered.text.append(line);
      }
    } else {
      numbered.text.append(line);
    }
    if (!last) numbered.text.push_back('\n');
  }
  numbered.lines = number;
  if (!numbered.text.empty() && numbered.text.back() != '\n') numbered.text.push_back('\n');
  numbered.text += "N" + std::to_string(kFirstLineNumber + number + 1) + " M2\n";
  return numbered;
}

int line_of(std::string_view numbered_line) {
  std::size_t at = 0;
  while (at < numbered_line.size() && (blank(numbered_line[at]) || numbered_line[at] == '/')) ++at;
  if (at >= numbered_line.size() || numbered_line[at] != 'N') return 0;
  long long number = 0;
  std::size_t digits = 0;
  for (++at; at < numbered_line.size() && digits < 12 &&
             std::isdigit(static_cast<unsigned char>(numbered_line[at]));
       ++at, ++digits) {
    number = number * 10 + (numbered_line[at] - '0');
  }
  // Below the offset: an N word of the program's own (a line left as it
  // was) or of a subroutine file, not a line number.
  if (number <= kFirstLineNumber || number > kFirstLineNumber + kMaxLines) return 0;
  return static_cast<int>(number - kFirstLineNumber);
}

}  // namespace fatc::program
