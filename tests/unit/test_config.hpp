#pragma once

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/config/config.hpp"
#include "core/rack/tool_state.hpp"

namespace fatc::test {

/// The sample config (sample_config.json): six pockets along X, side offset
/// +Y. The rack tests and make_hostile_corpus.py build theirs on it.
inline const std::string kValidConfig = [] {
  const char* const path = FATC_SOURCE_DIR "/tests/unit/sample_config.json";
  std::ifstream in(path);
  if (!in) throw std::runtime_error(std::string("cannot read ") + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}();

/// The sample config with `patch` merged into it (RFC 7386: null removes a key).
inline std::string sample_config_with(const char* patch) {
  auto config = nlohmann::ordered_json::parse(kValidConfig);
  config.merge_patch(nlohmann::ordered_json::parse(patch));
  return config.dump(2);
}

/// The sample config with `pockets` for its pockets, written as given, so a
/// test spoiling them finds its words in the text (pockets is the last key).
inline std::string sample_config_with_pockets(const std::string& pockets) {
  const std::string key = "\"pockets\": ";
  std::string text = kValidConfig;
  const std::size_t at = text.find(key) + key.size();
  const std::size_t end = text.rfind('}', text.rfind('}') - 1) + 1;
  return text.replace(at, end - at, pockets);
}

/// Pockets 1-4 entered from the top, T1-T4 in them, safe placed between
/// pockets 2 and 3 at a Z the nose clears (5 mm over every above-clearance):
/// the sequences leave 45 mm below the nose over the holders, so a longer
/// tool drags its tip through them on the way back to safe (issue 32).
inline const std::string kTopRack = sample_config_with(R"({
  "path": "direct",
  "safe": {"x": 125.0, "y": 20.0, "z": -15.0},
  "pocket_default": {"approach": "top"},
  "pockets": {"5": null, "6": null}
})");

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
