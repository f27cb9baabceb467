#include "numbered_program.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <iterator>

namespace fatc::program {
namespace {

bool blank(char c) { return c == ' ' || c == '\t'; }

/// The line as LinuxCNC reads its words: lower case, no blanks, no comments.
std::string packed(std::string_view line) {
  std::string result;
  bool in_comment = false;
  for (const char c : line) {
    if (in_comment) {
      in_comment = c != ')';
    } else if (c == '(') {
      in_comment = true;
    } else if (c == ';') {
      break;
    } else if (!blank(c) && c != '\r') {
      result.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
    }
  }
  return result;
}

/// Whether the line reads #5399: LinuxCNC drops spaces inside words, so
/// "# 5399" is the same parameter.
bool reads_m66_input(std::string_view line) {
  if (line.find('9') == std::string_view::npos) return false;
  std::string packed_line;
  for (const char c : line) {
    if (!blank(c)) packed_line.push_back(c);
  }
  for (std::size_t at = packed_line.find("#5399"); at != std::string::npos;
       at = packed_line.find("#5399", at + 1)) {
    const std::size_t after = at + 5;
    if (after == packed_line.size() ||
        (!std::isdigit(static_cast<unsigned char>(packed_line[after])) &&
         packed_line[after] != '.')) {
      return true;
    }
  }
  return false;
}

/// A name a subroutine file can have in a folder of our own: no path, no
/// hidden file, nothing a shell or a file system reads otherwise.
bool file_name(std::string_view name) {
  if (name.empty() || name.size() > 200 || name[0] == '.') return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
}

/// Whether an M-code is one LinuxCNC's interpreter runs itself (M6 and M61
/// are shown on their T word's line whatever runs them).
bool built_in_m_code(long code) {
  return (code >= 0 && code <= 9) || code == 19 || code == 30 || (code >= 48 && code <= 53) ||
         (code >= 60 && code <= 73) || code == 98 || code == 99;
}

/// Whether packed words hold an M word an INI may remap to a subroutine
/// (`m310`, `m[#1]`; not `m3`, nor `#<_m310>`).
bool holds_remappable_m_word(std::string_view words) {
  int depth = 0;  // inside a parameter's name
  for (std::size_t at = 0; at + 1 < words.size(); ++at) {
    if (words[at] == '<') ++depth;
    if (words[at] == '>' && depth > 0) --depth;
    if (depth > 0 || words[at] != 'm' ||
        (at > 0 && std::isalpha(static_cast<unsigned char>(words[at - 1])))) {
      continue;
    }
    const char next = words[at + 1];
    if (next == '[' || next == '#') return true;  // known only when it runs
    if (!std::isdigit(static_cast<unsigned char>(next))) continue;
    std::size_t end = at + 1;
    while (end < words.size() && std::isdigit(static_cast<unsigned char>(words[end]))) ++end;
    if (!built_in_m_code(std::strtol(std::string(words.substr(at + 1, end - at - 1)).c_str(), nullptr, 10))) {
      return true;
    }
  }
  return false;
}

}  // namespace

void LineSet::insert(int line) {
  if (line < 0) return;
  const auto at = static_cast<std::size_t>(line);
  if (bits_.size() <= at) bits_.resize(at + 1);
  bits_[at] = true;
}

bool LineSet::contains(int line) const {
  return line >= 0 && static_cast<std::size_t>(line) < bits_.size() &&
         bits_[static_cast<std::size_t>(line)];
}

void LineNumberer::add(std::string_view piece) {
  if (ended_) return;
  if (const auto nul = piece.find('\0'); nul != std::string_view::npos) {
    int line = lines_ + 1;
    std::size_t column = column_;
    for (std::size_t i = 0; i < nul; ++i) {
      column = piece[i] == '\n' ? 0 : column + 1;
      if (piece[i] == '\n') ++line;
    }
    nul_ = LineNote{line, "NUL byte at column " + std::to_string(column + 1) +
                              ": not a G-code text file (LinuxCNC stops reading a line at a "
                              "NUL); nothing of it read"};
    ended_ = true;
    text_.clear();
    return;
  }
  while (!piece.empty() && !ended_) {
    const std::size_t newline = piece.find('\n');
    const std::string_view part = piece.substr(0, newline);
    column_ += part.size();
    if (!passing_ && line_.size() + part.size() > kMaxLineLength) {
      // Too long for LinuxCNC, which refuses it and prints its start: numbered
      // all the same, so that the refusal names this line.
      line_.append(part);
      if (holds_code(line_)) {
        append_numbered(line_, lines_ + 1);
      } else {
        text_ += line_;
      }
      line_.clear();
      passing_ = true;
    } else {
      (passing_ ? text_ : line_).append(part);
    }
    if (newline == std::string_view::npos) break;
    piece.remove_prefix(newline + 1);
    whole_bytes_ += column_ + 1;
    end_line();
  }
}

void LineNumberer::end_line() {
  ++lines_;
  if (!passing_) line_of_code(line_);
  text_.push_back('\n');
  line_.clear();
  passing_ = false;
  column_ = 0;
  if (lines_ >= kMaxLines) ended_ = true;
}

void LineNumberer::line_of_code(std::string_view line) {
  if (reads_m66_input(line)) input_lines_.insert(lines_);
  if (!holds_code(line)) {
    text_.append(line);
    return;
  }
  const std::size_t size_before = text_.size();
  if (note_subroutine(line)) {
    // Skipped with the line under block delete.
    const auto [word, end] = own_line_number(line);
    if (line.substr(0, word).find('/') != std::string_view::npos) text_ += '/';
    text_ += "N" + std::to_string(kFirstLineNumber + lines_) + " (" + std::string(kRunsSubroutine) + ")\n";
  }
  const std::size_t line_start = text_.size();
  append_numbered(line, lines_);
  if (text_.size() - line_start > kMaxLineLength) {
    // Left unnumbered, and without an N word of its own, which could name another line.
    text_.resize(size_before);
    const auto [word, end] = own_line_number(line);
    text_.append(line.substr(0, word));
    text_.append(line.substr(end));
  }
}

bool LineNumberer::holds_code(std::string_view line) {
  std::size_t at = 0;
  while (at < line.size() && blank(line[at])) ++at;
  // '%' marks the program's ends; a blank line holds nothing to number.
  return at < line.size() && line[at] != '%' && line[at] != '\r';
}

std::pair<std::size_t, std::size_t> LineNumberer::own_line_number(std::string_view line) {
  std::size_t at = 0;
  while (at < line.size() && blank(line[at])) ++at;
  if (at < line.size() && line[at] == '/') ++at;  // block delete comes first, before any N word
  const std::size_t word = at;
  if (at < line.size() && (line[at] == 'n' || line[at] == 'N')) {
    ++at;
    // LinuxCNC reads "N50.5" as a line number too.
    while (at < line.size() && (blank(line[at]) || line[at] == '.' ||
                                std::isdigit(static_cast<unsigned char>(line[at])))) {
      ++at;
    }
  }
  return {word, at};
}

void LineNumberer::append_numbered(std::string_view line, int number) {
  const auto [word, end] = own_line_number(line);
  text_.append(line.substr(0, word));
  text_ += "N" + std::to_string(kFirstLineNumber + number) + " ";
  text_.append(line.substr(end));
}

bool LineNumberer::note_subroutine(std::string_view line) {
  const std::string words = packed(line);
  std::size_t at = words.rfind('/', 0) == 0 ? 1 : 0;
  if (at < words.size() && words[at] == 'n') {
    ++at;
    while (at < words.size() &&
           (words[at] == '.' || std::isdigit(static_cast<unsigned char>(words[at]))))
      ++at;
  }
  if (at >= words.size() || words[at] != 'o') return holds_remappable_m_word(words);
  ++at;
  std::string name;
  if (at < words.size() && words[at] == '<') {
    const std::size_t close = words.find('>', at);
    if (close == std::string::npos) return false;
    name = words.substr(at + 1, close - at - 1);
    at = close + 1;
  } else {
    const std::size_t start = at;
    while (at < words.size() && std::isdigit(static_cast<unsigned char>(words[at]))) ++at;
    name = words.substr(start, at - start);
  }
  const std::string_view rest = std::string_view(words).substr(at);
  const bool calls = rest.rfind("call", 0) == 0;
  if (!file_name(name)) return calls;
  std::set<std::string>* names = calls                       ? &called_
                                 : rest.rfind("sub", 0) == 0 ? &defined_
                                                             : nullptr;
  if (names != nullptr && names->size() < kMaxSubroutineNames) names->insert(std::move(name));
  return calls;
}

void LineNumberer::finish(bool cut) {
  if (nul_) return;
  if (!ended_) {
    if (!cut && column_ > 0) {
      whole_bytes_ += column_;
      end_line();
    } else if (passing_) {
      // The start of a line too long to number went out already: it ends here.
      text_.push_back('\n');
    }
  }
  ended_ = true;
  text_ += "N" + std::to_string(kFirstLineNumber + lines_ + 1) + " M2\n";
}

std::string LineNumberer::take_text() {
  std::string text;
  text.swap(text_);
  return text;
}

std::vector<std::string> LineNumberer::undefined_calls() const {
  std::vector<std::string> names;
  std::set_difference(called_.begin(), called_.end(), defined_.begin(), defined_.end(),
                      std::back_inserter(names));
  return names;
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
