// Any bytes as what reads a program for --lint: the program numbered piece by
// piece (pieces of a size the input chooses) the same as whole, every line of
// code numbered with its own number or left unnumbered (a line that may run a
// subroutine has a note of that number before it), never made too long
// for LinuxCNC; the same bytes as rs274's output (calls and
// errors) and as a tool table, each read within its bounds. run.sh runs it
// under a memory limit (libFuzzer's -rss_limit_mb and -malloc_limit_mb): the
// reader must stay small whatever it is fed. Never a crash, an exception, a
// leak or undefined behaviour.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/program/interpreter_output.hpp"
#include "core/program/numbered_program.hpp"
#include "core/program/tool_table.hpp"
#include "invariants.hpp"

namespace {

using namespace fatc::program;

std::string numbered(std::string_view text, std::size_t piece, LineNumberer& numberer) {
  std::string out;
  for (std::size_t at = 0; at < text.size(); at += piece) {
    numberer.add(text.substr(at, piece));
    out += numberer.take_text();
  }
  numberer.finish(false);
  return out + numberer.take_text();
}

/// LineNumberer's note before a line that may run a subroutine, and nothing
/// else: "N1000000007 (fixed_atc_probe: this line runs a subroutine)", after
/// a block delete where the line has one.
bool is_note(std::string_view line) {
  std::size_t at = !line.empty() && line[0] == '/' ? 1 : 0;
  if (at >= line.size() || line[at] != 'N') return false;
  ++at;
  const std::size_t digits = at;
  while (at < line.size() && line[at] >= '0' && line[at] <= '9') ++at;
  return at > digits && line.substr(at) == " (" + std::string(kRunsSubroutine) + ")";
}

void check_numbering(std::string_view text, std::size_t piece) {
  LineNumberer whole;
  LineNumberer pieces;
  const std::string once = numbered(text, text.size() + 1, whole);
  const std::string again = numbered(text, piece, pieces);
  // A NUL byte: not a text file, whatever was numbered before it is thrown away.
  if (whole.nul().has_value() != pieces.nul().has_value() ||
      (whole.nul() && (whole.nul()->line != pieces.nul()->line ||
                       whole.nul()->text != pieces.nul()->text))) {
    fatc::fuzz::broken("a NUL byte found on the same line whatever the pieces",
                       std::string(text.substr(0, 200)));
  }
  if (whole.nul()) {
    fatc::fuzz::check_messages({whole.nul()->text});
    return;
  }
  if (once != again || whole.lines() != pieces.lines() || whole.bytes() != pieces.bytes()) {
    fatc::fuzz::broken("the numbering is the same whatever the pieces",
                       std::string(text.substr(0, 200)));
  }
  if (whole.bytes() != text.size())
    fatc::fuzz::broken("every byte read", std::to_string(whole.bytes()));
  // Each line as rs274 is given it: the program's own or its number added, then the M2.
  std::size_t start = 0;
  std::size_t given = 0;  // where the program's own line starts
  int line = 0;
  while (start < once.size()) {
    const std::size_t end = once.find('\n', start);
    if (end == std::string::npos)
      fatc::fuzz::broken("the copy ends with a line end", once.substr(start, 200));
    const std::string_view got(once.data() + start, end - start);
    if (is_note(got)) {
      // The note before a line that may run a subroutine: no line of the
      // program's own, numbered with the number of the line it stands before.
      if (line_of(got) != line + 1) {
        fatc::fuzz::broken("a note numbered with its line's number", std::string(got.substr(0, 200)));
      }
      start = end + 1;
      continue;
    }
    ++line;
    const int number = line_of(got);
    if (number != 0 && number != line) {
      fatc::fuzz::broken("a line numbered with its own number", std::string(got.substr(0, 200)));
    }
    const std::size_t given_end = std::min(text.find('\n', given), text.size());
    if (number != 0 && got.size() > kMaxLineLength && given_end - given <= kMaxLineLength) {
      fatc::fuzz::broken("a line LinuxCNC reads whole stays whole numbered",
                         std::string(got.substr(0, 200)));
    }
    given = std::min(given_end + 1, text.size());
    start = end + 1;
  }
  if (line != whole.lines() + 1)
    fatc::fuzz::broken("one line more than the program: the M2", std::to_string(line));
  for (const std::string& name : whole.undefined_calls()) {
    if (name.empty() || name.find('/') != std::string::npos || name[0] == '.') {
      fatc::fuzz::broken("an undefined call is a file name", name);
    }
  }
}

void check_output(std::string_view text) {
  ProgramGiven program;
  program.name = "p.ngc";
  program.numbered_path = "/tmp/x/program.ngc";
  program.stub_folder = "/tmp/x/undefined";
  program.input_lines.insert(3);
  program.lines = 100;
  InterpreterOutput output(program, {0, 1, 2, 3});
  std::size_t start = 0;
  bool calls = true;
  while (start < text.size() && !output.done()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string_view line = text.substr(start, end - start);
    calls ? output.canonical_call(line) : output.error_line(line);
    calls = !calls;
    start = end + 1;
  }
  const InterpreterRun run = output.finish();
  if (run.uses.size() > kMaxToolUses || run.problems.size() > kMaxErrors + 1 ||
      run.unknowns.size() > kMaxErrors || run.spindle_starts.size() > kMaxToolUses) {
    fatc::fuzz::broken("what rs274 prints is kept within its bounds",
                       std::to_string(run.uses.size()));
  }
}

void check_table(std::string_view text) {
  const fatc::ToolTable table = fatc::parse_tool_table(text);
  for (const auto& [tool, entry] : table.tools) {
    if (entry.z && !(std::abs(*entry.z) <= 100000.0)) {
      fatc::fuzz::broken("a tool's length is a number a tool can have", std::to_string(*entry.z));
    }
  }
  // A line over LinuxCNC's 255 characters is said in one line, its pieces included.
  for (const fatc::LineNote& note : table.problems) fatc::fuzz::check_messages({note.text});
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t piece = 1 + data[0] % 64;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  check_numbering(text, piece);
  check_output(text);
  check_table(text);
  return 0;
}
