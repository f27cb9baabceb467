#pragma once

#include <set>
#include <string>

#include "core/config/config.hpp"
#include "core/rack/tool_state.hpp"

namespace fatc::test {

/// A small valid config: six pockets along X, side offset +Y.
inline const char* const kValidConfig = R"({
  "probe_length_compensation_offset": -95.0,
  "probe_retract_offset_z": 5.0,
  "pocket_side_offset": {"x": 0.0, "y": 40.0},
  "pocket_above_chuck_offset_z": 20.0,
  "pocket_above_clearance_offset_z": 60.0,
  "chuck_seconds": 0.5,
  "loading": {"x": 20.0, "y": 150.0, "z": -10.0},
  "probe_limit": {"x": 20.0, "y": 150.0, "z": -90.0},
  "safe": {"x": 120.0, "y": 80.0, "z": -5.0},
  "pocket_default": {"y": 20.0, "z": -80.0},
  "pockets": {"1": {"x": 50.0}, "2": {"x": 100.0}, "3": {"x": 150.0},
              "4": {"x": 200.0}, "5": {"x": 250.0}, "6": {"x": 300.0, "z": -82.5}}
})";

/// Pockets 1-4 entered from the top, T1-T4 in them, safe placed between
/// pockets 2 and 3 at a Z the nose clears (5 mm over every above-clearance):
/// the sequences leave 45 mm below the nose over the holders, so a longer
/// tool drags its tip through them on the way back to safe (issue 32).
inline const char* const kTopRack = R"({
  "probe_length_compensation_offset": -95.0,
  "probe_retract_offset_z": 5.0,
  "pocket_side_offset": {"x": 0.0, "y": 40.0},
  "pocket_above_chuck_offset_z": 20.0,
  "pocket_above_clearance_offset_z": 60.0,
  "chuck_seconds": 0.5,
  "path": "direct",
  "loading": {"x": 20.0, "y": 150.0, "z": -10.0},
  "probe_limit": {"x": 20.0, "y": 150.0, "z": -90.0},
  "safe": {"x": 125.0, "y": 20.0, "z": -15.0},
  "pocket_default": {"y": 20.0, "z": -80.0, "approach": "top"},
  "pockets": {"1": {"x": 50.0}, "2": {"x": 100.0}, "3": {"x": 150.0}, "4": {"x": 200.0}}
})";

/// The valid config with `extra` keys added at the top level, e.g. R"("manual_tools": false)".
inline Config valid_config(const std::string& extra = "") {
  std::string text = kValidConfig;
  if (!extra.empty()) text.insert(text.rfind('}'), "," + extra);
  return *parse_config(text).config;
}

/// `tool` is out of its pocket (in the spindle, or lost): the pocket stays its.
inline void take_out(ToolState& tools, int tool) {
  if (const auto home = tools.home_of(tool)) tools.pockets[*home].holds = false;
}

/// The tools sitting in their pockets.
inline std::set<int> tools_in_rack(const ToolState& tools) {
  std::set<int> in_rack;
  for (const auto& [number, pocket] : tools.pockets) {
    if (tools.holds(number)) in_rack.insert(pocket.tool);
  }
  return in_rack;
}

}  // namespace fatc::test
