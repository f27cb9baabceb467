#pragma once

// The command line, declared once: the modes and options below are what
// parse_options (CLI11, parse_options.hpp) accepts, and --help, the man
// page's SYNOPSIS and OPTIONS and docs/command-line.md are generated from
// them (usage.hpp, fatc_docs).

#include <string>
#include <vector>

#include "options.hpp"

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

/// The option declared as `name` ("--ini"): one of options().
const OptionDeclaration& option(const std::string& name);
/// Whether `mode` needs or may read the option `name`.
bool reads(const ModeDeclaration& mode, const std::string& name);
/// "--ini FILE", or "--yes" for a flag.
std::string named_value(const char* name);

}  // namespace fatc::io
