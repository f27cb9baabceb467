#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "core/tool_state.hpp"

namespace fatc::io {

/// Reads and validates a config.json; every message starts with the file's path.
ConfigResult load_config_file(const std::string& path);

/// Reads the saved tool state. A missing file is a first start (every pocket
/// full, spindle empty); anything unreadable or inconsistent with the config
/// is an error naming the file, never a silent reset.
ToolStateResult load_state_file(const std::string& path, const Config& config);

/// Writes the tool state crash-safe: temporary file, fsync, rename, fsync of
/// the folder. Throws std::runtime_error naming the file on failure.
void save_state_file(const std::string& path, const ToolState& state);

}  // namespace fatc::io
