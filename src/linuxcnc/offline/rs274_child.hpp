#pragma once

// rs274 as a child process: started with no shell, its canonical calls and
// its standard error read as they come (interpreter.cpp gives it its inputs).

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/program/interpreter_output.hpp"

namespace fatc::io {

/// How the child ended, for the report.
struct Rs274Ending {
  bool timed_out = false;
  bool too_much_output = false;
  int status = 0;
};

/// Where rs274's output file is in the child: /dev/fd/3.
constexpr int kCallsFd = 3;

/// Runs `argv` in `folder` and feeds `output` as it goes: the canonical
/// calls rs274 writes to its output file, here /dev/fd/3, a pipe (a file
/// given by name, rs274 buffers it, where on its standard output it writes
/// every few characters, four times slower), and its standard error. Nothing
/// of either is kept beyond the line under way. Stopped after `seconds` or
/// `max_output_bytes` printed.
std::optional<Rs274Ending> run_rs274(const std::vector<std::string>& argv, const std::string& folder,
                                     const std::string& home, double seconds,
                                     std::size_t max_output_bytes,
                                     program::InterpreterOutput& output, std::string& error);

}  // namespace fatc::io
