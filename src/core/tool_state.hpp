#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>

#include "config.hpp"

namespace fatc {

/// What the changer knows about where the tools are. Saved after every change.
struct ToolState {
  int spindle = 0;         ///< tool in the spindle, 0 = empty
  bool uncertain = false;  ///< an interrupted sequence: `spindle` is the last known, not a fact
  std::set<int> in_pocket; ///< tools sitting in their own pocket
  std::map<int, double> lengths;  ///< measured tool lengths, in the config's units

  /// First start: every configured pocket holds its tool, the spindle is empty.
  static ToolState fresh(const Config& config);

  bool operator==(const ToolState& other) const;
};

struct ToolStateResult {
  std::optional<ToolState> state;
  std::string error;  ///< names the JSON path, empty on success
};

std::string to_json(const ToolState& state);
ToolStateResult tool_state_from_json(const std::string& text);

}  // namespace fatc
