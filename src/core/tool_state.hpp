#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>

#include "config.hpp"

namespace fatc {

/// A sequence under way, saved before the motion it describes, so that a
/// restart after a crash knows what may have happened and where.
struct InProgress {
  std::string sequence;  ///< "M6 T3", "load of tool 4", "unload of tool 4"
  std::string step;      ///< "returning tool 1 to pocket 1"
  int pocket = 0;        ///< the pocket involved (its tool number), 0 if none
  bool operator==(const InProgress& other) const {
    return sequence == other.sequence && step == other.step && pocket == other.pocket;
  }
};

/// What the changer knows about where the tools are. Saved after every change.
struct ToolState {
  int spindle = 0;          ///< tool in the spindle, 0 = empty
  bool uncertain = false;   ///< an interrupted sequence: `spindle` is the last known, not a fact
  std::set<int> in_pocket;  ///< tools sitting in their own pocket
  std::map<int, double> lengths;          ///< measured tool lengths, in the config's units
  std::optional<InProgress> in_progress;  ///< a sequence was under way when this was saved

  /// First start: every configured pocket holds its tool, the spindle is empty.
  static ToolState fresh(const Config& config);

  bool operator==(const ToolState& other) const;

  /// The operator's word after a fault or a cut-off sequence: the spindle
  /// holds `spindle_tool` (0 empty) and, when a sequence was cut off at a
  /// pocket, whether that pocket holds its tool. Clears the uncertainty.
  void confirm(int spindle_tool, std::optional<bool> pocket_holds_tool);
};

struct ToolStateResult {
  std::optional<ToolState> state;
  std::string error;  ///< names the JSON path, empty on success
};

std::string to_json(const ToolState& state);
ToolStateResult tool_state_from_json(const std::string& text);

}  // namespace fatc
