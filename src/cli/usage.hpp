#pragma once

// What is said of the command line (command_line.hpp's declarations): --help,
// the man page's sections, docs/command-line.md.

#include <string>

namespace fatc::io {

/// --help: a synopsis line and a summary for each mode, then each option.
std::string usage();
/// The man page's SYNOPSIS and OPTIONS sections' bodies.
std::string synopsis_man();
std::string options_man();
/// docs/command-line.md's body.
std::string command_line_markdown();

}  // namespace fatc::io
