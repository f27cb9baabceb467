#pragma once

// Reading config.json into a Config (parse_config.cpp), with the readers of
// config/ (reader.hpp, keys.hpp, tool_rules.hpp, ...) behind it.

#include <optional>
#include <string>
#include <vector>

#include "settings.hpp"

namespace fatc {

/// Either a Config or every problem found, one line each, each naming the
/// JSON path it is about.
struct ConfigResult {
  std::optional<Config> config;
  std::vector<std::string> errors;
};

/// Parses and validates the text of a config.json.
ConfigResult parse_config(const std::string& json_text);

}  // namespace fatc
