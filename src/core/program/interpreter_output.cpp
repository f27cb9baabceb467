#include "interpreter_output.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <utility>

#include "../config/quote.hpp"
#include "canonical_call.hpp"
#include "numbered_program.hpp"

namespace fatc::program {
namespace {

/// How much of the interpreter's own message a finding repeats.
constexpr std::size_t kMessageText = 300;

/// The whole number in `CALL(n)`; nullopt when there is none.
std::optional<long> argument_of(std::string_view call, std::string_view name) {
  if (!starts_with(call, name) || call.size() <= name.size() + 1 || call[name.size()] != '(') {
    return std::nullopt;
  }
  const std::string digits(call.substr(name.size() + 1));
  char* end = nullptr;
  const long value = std::strtol(digits.c_str(), &end, 10);
  if (end == digits.c_str() || *end != ')') return std::nullopt;
  return value;
}

/// `CALL()` or `CALL(n)`: LinuxCNC 2.10's rs274 prints CHANGE_TOOL() (the
/// tool is the one selected before), 2.9's CHANGE_TOOL(n).
bool calls(std::string_view call, std::string_view name) {
  return argument_of(call, name) ||
         (starts_with(call, name) && call.substr(name.size(), 2) == "()");
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

}  // namespace

bool holds_m6(std::string_view line) {
  std::string packed;
  int depth = 0;  // inside a comment, or a parameter's name
  for (const char c : line) {
    if (c == ';' && depth == 0) break;
    if (c == '(' || c == '<') ++depth;
    if (depth == 0 && c != ' ' && c != '\t') {
      packed.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
    }
    if ((c == ')' || c == '>') && depth > 0) --depth;
  }
  for (std::size_t at = packed.find('m'); at != std::string::npos; at = packed.find('m', at + 1)) {
    if (at > 0 && std::isalpha(static_cast<unsigned char>(packed[at - 1]))) continue;
    std::size_t digit = at + 1;
    while (digit < packed.size() && packed[digit] == '0') ++digit;
    if (digit < packed.size() && packed[digit] == '6' &&
        (digit + 1 == packed.size() ||
         (!std::isdigit(static_cast<unsigned char>(packed[digit + 1])) &&
          packed[digit + 1] != '.'))) {
      return true;
    }
  }
  return false;
}

InterpreterOutput::InterpreterOutput(ProgramGiven program, std::vector<int> tool_of_row)
    : program_(std::move(program)), tool_of_row_(std::move(tool_of_row)) {}

bool InterpreterOutput::reads_input(int line) const {
  return line > 0 && program_.input_lines.contains(line);
}

void InterpreterOutput::unknown(int line, const std::string& text) {
  if (run_.unknowns.size() < kMaxErrors)
    run_.unknowns.push_back(finding(program_.name, line, text));
}

void InterpreterOutput::canonical_call(std::string_view line) {
  // "   12 N1000000004 SELECT_TOOL(3)", or "N....." for a line with no N word.
  std::size_t at = line.find('N');
  if (at == std::string_view::npos) return;
  const std::string_view from_n = line.substr(at);
  const int number = line_of(from_n);
  if (number > program_.lines && program_.lines > 0) {
    // The M2 LineNumberer put after the last line: the program has no end of its own.
    if (!said_no_end_) {
      said_no_end_ = true;
      error(program_.lines, "File ended with no percent sign or program end", "");
    }
    return;
  }
  const bool numbered = number > 0;
  if (numbered) line_ = number;
  ++at;
  while (at < line.size() && (line[at] == '.' || std::isdigit(static_cast<unsigned char>(line[at])))) {
    ++at;
  }
  while (at < line.size() && line[at] == ' ') ++at;
  const std::string_view call = line.substr(at);
  if (numbered && starts_with(call, "COMMENT(\"") && call.substr(9, kRunsSubroutine.size()) == kRunsSubroutine) {
    return;
  }
  if (listener_) listener_->call(line_, numbered, call);
  if (const auto tool = argument_of(call, "SELECT_TOOL")) {
    any_selected_ = true;
    selected_ = static_cast<int>(*tool);
    // A remapped M6 runs in its subroutine, on lines without a number: the
    // change is shown on its T word's line.
    selected_line_ = numbered ? line_ : 0;
    if (reads_input(line_)) {
      selected_.reset();
      if (run_.unknowns.size() < kMaxErrors && inputs_said_.insert(line_).second) {
        unknown(line_,
                "the tool number reads #5399, the input M66 waited for: known only when the "
                "program runs on the machine (rs274 reads 0)");
      }
    }
  } else if (calls(call, "CHANGE_TOOL")) {
    if (!any_selected_ && !said_no_t_) {
      said_no_t_ = true;
      if (run_.problems.size() < kMaxErrors) {
        run_.problems.push_back(
            finding(program_.name, line_, "M6 without a T word since the start"));
      }
    }
    use(ToolUse::Kind::change, any_selected_ ? selected_ : std::nullopt,
        any_selected_ ? selected_line_ : line_);
  } else if (starts_with(call, "SET_SPINDLE_SPEED(0, ")) {
    spindle_.speed = std::fabs(std::strtod(std::string(call.substr(21)).c_str(), nullptr));
    spindle_commanded();
  } else if (starts_with(call, "SET_SPINDLE_MODE(0")) {
    // 2.9 prints "SET_SPINDLE_MODE(0 1000.0000)": no comma.
    std::string value(call.substr(18));
    if (!value.empty() && value[0] == ',') value.erase(0, 1);
    spindle_.css_maximum = std::fabs(std::strtod(value.c_str(), nullptr));
  } else if (call == "START_SPINDLE_CLOCKWISE(0)" || call == "START_SPINDLE_COUNTERCLOCKWISE(0)") {
    spindle_.direction = call == "START_SPINDLE_CLOCKWISE(0)" ? 1 : -1;
    spindle_commanded();
  } else if (call == "STOP_SPINDLE_TURNING(0)") {
    spindle_.direction = 0;
    spindle_commanded();
  } else if (starts_with(call, "ORIENT_SPINDLE(0, ")) {
    if (run_.spindle_starts.size() < kMaxToolUses) {
      SpindleStart start;
      start.where = {program_.name, line_};
      start.before_use = run_.uses.size();
      start.orients = true;
      start.speed = spindle_.speed;
      run_.spindle_starts.push_back(start);
    }
  } else if (const auto row = argument_of(call, "CHANGE_TOOL_NUMBER")) {
    std::optional<int> tool;
    if (*row >= 0 && static_cast<std::size_t>(*row) < tool_of_row_.size() && !reads_input(line_)) {
      tool = tool_of_row_[static_cast<std::size_t>(*row)];
    }
    use(ToolUse::Kind::set, tool, numbered ? line_ : 0);
  }
}

void InterpreterOutput::spindle_commanded() {
  // Canon's EMC_SPINDLE_ON: the direction times G96's D when there is one
  // (motion runs at D while the surface speed gives it no factor), else times S.
  const double speed = spindle_.css_maximum != 0.0 ? spindle_.css_maximum : spindle_.speed;
  const bool turning = spindle_.direction != 0 && speed != 0.0;
  if (turning && !spindle_.turning && run_.spindle_starts.size() < kMaxToolUses) {
    SpindleStart start;
    start.where = {program_.name, line_};
    start.before_use = run_.uses.size();
    start.clockwise = spindle_.direction > 0;
    start.speed = spindle_.speed;
    start.css_maximum = spindle_.css_maximum;
    run_.spindle_starts.push_back(start);
  }
  spindle_.turning = turning;
}

void InterpreterOutput::use(ToolUse::Kind kind, std::optional<int> tool, int line) {
  ToolUse use;
  use.kind = kind;
  use.tool = tool;
  use.where = {program_.name, line};
  if (listener_) listener_->tool_use(use);
  if (run_.uses.size() + unknown_changes_.size() >= kMaxToolUses) {
    ++run_.uses_not_kept;
    return;
  }
  run_.uses.push_back(use);
}

void InterpreterOutput::error_line(std::string_view line) {
  if (line == "executing") return;
  // Each error is its message, then the text of the line it stopped on.
  if (const int number = line_of(line); number > 0) {
    error(number, pending_message_.value_or(""), line);
    pending_message_.reset();
  } else if (pending_message_) {
    error(0, *pending_message_, line);
    pending_message_.reset();
  } else {
    pending_message_ = replaced(std::string(line), program_.numbered_path, program_.name);
  }
}

void InterpreterOutput::error(int line, const std::string& message, std::string_view text) {
  if (done()) return;
  // The M2 LineNumberer added is no line of the program.
  if (program_.lines > 0 && line > program_.lines) line = program_.lines;
  past_the_end_ = starts_with(message, "File ended with no percent sign or program end");
  if (message.find("#<_hal[") != std::string::npos) {
    unknown(line, escape(message, kMessageText) +
                      ": a HAL pin, read only when the program runs on the machine: " +
                      "what the line does is not known");
    if (holds_m6(text) && run_.uses.size() + unknown_changes_.size() >= kMaxToolUses) {
      ++run_.uses_not_kept;
    } else if (holds_m6(text)) {
      ToolUse change;
      change.where = {program_.name, line};
      change.ran = false;
      unknown_changes_.push_back(change);
    }
    return;
  }
  if (run_.problems.size() >= kMaxErrors) {
    stopped_at_ = line;
    return;
  }
  // The interpreter's words hold the program's own text: escaped as any file's.
  std::string said =
      "LinuxCNC stops the program here: " + escape(message_of(message, line), kMessageText);
  if (line == 0 && !text.empty()) {
    // No number of ours on the line: one of a subroutine file, or one that fits
    // LinuxCNC only unnumbered.
    std::string_view shown = text;
    while (!shown.empty() && (shown.back() == '\r' || shown.back() == ' ')) shown.remove_suffix(1);
    said += " (at " + quote(shown) + ")";
  }
  run_.problems.push_back(finding(program_.name, line, said));
}

std::string InterpreterOutput::message_of(const std::string& message, int line) const {
  // An undefined call found its empty file in the stub folder, where it
  // stopped at once (rs274 would read the program to its end for each):
  // said as LinuxCNC says it of the program.
  const std::string stub = "EOF in file:" + program_.stub_folder + "/";
  const auto seeking = message.find(" seeking o-word: ");
  if (program_.stub_folder.empty() || message.rfind(stub, 0) != 0 || seeking == std::string::npos) {
    return message;
  }
  const auto from = message.find(" from line: ", seeking);
  const std::string oword = message.substr(seeking, from - seeking);
  return line > 0 ? "EOF in file:" + program_.name + oword + " from line: " + std::to_string(line)
                  : "EOF" + oword;
}

InterpreterRun InterpreterOutput::finish() {
  if (pending_message_) error(0, *pending_message_, "");
  pending_message_.reset();
  if (stopped_at_) {
    // Said of the program as a whole: a report lists it first, not after a thousand lines.
    const std::string stopped = "more than " + std::to_string(kMaxErrors) +
                                " errors: LinuxCNC's interpreter (rs274) was stopped at line " +
                                std::to_string(*stopped_at_);
    run_.problems.push_back(
        finding(program_.name, 0, stopped + "; tool changes after that are not known"));
  }
  // The interpreter never ran these lines: each goes before the first use
  // from a later line, where a program without loops would have it.
  if (!unknown_changes_.empty()) {
    std::stable_sort(
        unknown_changes_.begin(), unknown_changes_.end(),
        [](const ToolUse& a, const ToolUse& b) { return a.where.line < b.where.line; });
    std::vector<ToolUse> merged;
    merged.reserve(run_.uses.size() + unknown_changes_.size());
    auto change = unknown_changes_.begin();
    int highest = 0;  // of the uses so far: a change below it goes before this use
    for (ToolUse& use : run_.uses) {
      highest = std::max(highest, use.where.line);
      for (; change != unknown_changes_.end() && change->where.line < highest; ++change) {
        merged.push_back(std::move(*change));
      }
      merged.push_back(std::move(use));
    }
    std::move(change, unknown_changes_.end(), std::back_inserter(merged));
    run_.uses = std::move(merged);
  }
  unknown_changes_.clear();
  return std::move(run_);
}

}  // namespace fatc::program
