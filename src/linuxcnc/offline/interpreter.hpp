#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "core/program/interpreter_output.hpp"
#include "core/program/tool_use.hpp"

namespace fatc::io {

/// G-code given to the interpreter; what lies beyond is said to be not read.
constexpr std::size_t kMaxProgramBytes = 64 * 1024 * 1024;
/// How long rs274 may run: a program that loops without end must not hang
/// --lint or the panel (which gives up on --lint after 20 s).
constexpr double kInterpreterSeconds = 15.0;
/// What rs274 may print: read as it comes and never kept, so only a bound
/// on the work behind the time limit, far above the four bytes it prints for
/// each byte of kMaxProgramBytes of moves.
constexpr std::size_t kMaxInterpreterOutput = 1024u * 1024 * 1024;

struct InterpreterInput {
  std::string rs274;  ///< the binary, from find_rs274()
  std::string program_path;
  std::optional<std::string> ini_path;         ///< remaps, subroutine folders, parameters
  std::optional<std::string> tool_table_path;  ///< none: tools 1-1000 are taken as listed
  std::optional<std::string> subroutine_path;  ///< folders searched before the INI's, ':' between
  bool inch_machine = false;  ///< the tool table's units without an INI to say them
  std::size_t max_program_bytes = kMaxProgramBytes;
  double seconds = kInterpreterSeconds;
  std::size_t max_output_bytes = kMaxInterpreterOutput;
  /// Told of every canonical call and tool use as they are read; may be null.
  program::CallListener* listener = nullptr;
};

/// LinuxCNC's standalone interpreter: $FATC_RS274 when set, else `rs274` on
/// the PATH. nullopt and one line in `error` when there is none.
std::optional<std::string> find_rs274(std::string& error);

/// Runs the program through rs274 (LinuxCNC's interpreter) as the machine
/// would: in the INI's folder with its INI, its tool table and a copy of its
/// parameter file (rs274 writes the parameters back on exit: never the
/// machine's own), the program's lines numbered (program::LineNumberer). No
/// shell; stopped after `seconds` or `max_output_bytes` printed, which is
/// then a problem. Memory stays small whatever the program: it is numbered
/// and rs274's output read piece by piece, nothing of either kept but the
/// bounded findings. nullopt and one line in `error` when an input cannot be
/// read or rs274 cannot be started.
std::optional<program::InterpreterRun> run_interpreter(const InterpreterInput& input,
                                                       std::string& error);

}  // namespace fatc::io
