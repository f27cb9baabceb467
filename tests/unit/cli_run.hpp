#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "cli/cli.hpp"
#include "cli/parse_options.hpp"

namespace fatc::test {

/// What the command line printed and returned.
struct CliRun {
  int code;
  std::string out;
  std::string err;
};

/// fixed_atc_probe with `args`, as main() runs it: a usage mistake is exit 2
/// with its line, anything else the mode's own exit status.
inline CliRun run_cli(const std::vector<std::string>& args) {
  std::string error;
  const auto options = io::parse_options(args, error);
  if (!options) return {2, "", error};
  std::ostringstream out, err;
  const int code = io::run_tool_mode(*options, out, err);
  return {code, out.str(), err.str()};
}

}  // namespace fatc::test
