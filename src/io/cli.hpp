#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace fatc::io {

/// The component's command line.
struct Options {
  enum class Mode { component, check, plan, dot, help } mode = Mode::component;
  std::string config_path;
  std::string state_path;
  std::string ini_path;
  std::optional<int> from_tool;
  std::optional<int> to_tool;
};

/// Parses argv; nullopt and one line in `error` on a usage mistake.
std::optional<Options> parse_options(const std::vector<std::string>& args, std::string& error);

extern const char* const kUsage;

/// --check: 0 valid, 1 invalid. --plan: 0 printed, 1 refused or invalid. --dot: 0.
int run_tool_mode(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace fatc::io
