#pragma once

// The command line, declared once: the modes and options below are what
// parse_options (CLI11) accepts, and --help, the man page's SYNOPSIS and
// OPTIONS and docs/command-line.md are generated from them (fatc_docs).

#include <string>
#include <vector>

#include "cli.hpp"

namespace fatc::io {

struct OptionDeclaration {
  const char* name;   ///< "--config"
  const char* value;  ///< "FILE"
  const char* doc;    ///< what it is, for the references
  const char* hint;   ///< said when a mode needs it and it is missing; may be ""
};

struct ModeDeclaration {
  Options::Mode mode;
  const char* flag;   ///< "--check"; "" for the component
  const char* value;  ///< what the flag itself takes ("PROGRAM.ngc"), "" nothing
  std::vector<const char*> needs;  ///< options it requires
  std::vector<const char*> may;    ///< options it reads when given
  const char* summary;             ///< one line for --help
  const char* doc;                 ///< what it does, its exits, for the references
};

const std::vector<ModeDeclaration>& modes();
const std::vector<OptionDeclaration>& options();

/// --help: a synopsis line and a summary for each mode, then each option.
std::string usage();
/// The man page's SYNOPSIS and OPTIONS sections' bodies.
std::string synopsis_man();
std::string options_man();
/// `text` for the man page: a backslash escaped, `code` in bold.
std::string man_text(const std::string& text);
/// docs/command-line.md's body.
std::string command_line_markdown();

}  // namespace fatc::io
