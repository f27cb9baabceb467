#include "tool_state.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

namespace fatc {
namespace {

using Json = nlohmann::json;
constexpr int kFormatVersion = 1;

bool is_tool_number(const Json& value) {
  return value.is_number_integer() && value.get<long long>() > 0 &&
         value.get<long long>() <= 999999999;
}

ToolStateResult failure(const std::string& path, const std::string& what) {
  return {std::nullopt, path + ": " + what};
}

}  // namespace

ToolState ToolState::fresh(const Config& config) {
  ToolState state;
  for (const auto& pocket : config.pockets) state.in_pocket.insert(pocket.first);
  return state;
}

bool ToolState::operator==(const ToolState& other) const {
  return spindle == other.spindle && uncertain == other.uncertain && in_pocket == other.in_pocket &&
         lengths == other.lengths;
}

std::string to_json(const ToolState& state) {
  Json lengths = Json::object();
  for (const auto& [tool, length] : state.lengths) lengths[std::to_string(tool)] = length;
  const Json root = {{"version", kFormatVersion},
                     {"spindle", state.spindle},
                     {"uncertain", state.uncertain},
                     {"in_pocket", state.in_pocket},
                     {"lengths", lengths}};
  return root.dump(2) + "\n";
}

ToolStateResult tool_state_from_json(const std::string& text) {
  Json root;
  try {
    root = Json::parse(text);
  } catch (const Json::parse_error& e) {
    return failure("state", std::string("not valid JSON (") + e.what() + ")");
  }
  if (!root.is_object()) return failure("state", "expected a JSON object");
  for (const auto& item : root.items()) {
    const auto& k = item.key();
    if (k != "version" && k != "spindle" && k != "uncertain" && k != "in_pocket" && k != "lengths") {
      return failure(k, "unknown key");
    }
  }
  if (!root.contains("version") || root["version"] != kFormatVersion) {
    return failure("version", "expected 1, got " + (root.contains("version") ? root["version"].dump()
                                                                               : std::string("nothing")));
  }
  ToolState state;
  if (!root.contains("spindle")) return failure("spindle", "missing");
  const Json& spindle = root["spindle"];
  if (!(spindle == 0 || is_tool_number(spindle))) {
    return failure("spindle", "expected 0 or a tool number, got " + spindle.dump());
  }
  state.spindle = spindle.get<int>();
  if (!root.contains("uncertain") || !root["uncertain"].is_boolean()) {
    return failure("uncertain", "expected true or false");
  }
  state.uncertain = root["uncertain"].get<bool>();
  if (!root.contains("in_pocket") || !root["in_pocket"].is_array()) {
    return failure("in_pocket", "expected an array of tool numbers");
  }
  for (std::size_t i = 0; i < root["in_pocket"].size(); ++i) {
    const Json& tool = root["in_pocket"][i];
    if (!is_tool_number(tool)) {
      return failure("in_pocket." + std::to_string(i), "expected a tool number, got " + tool.dump());
    }
    if (!state.in_pocket.insert(tool.get<int>()).second) {
      return failure("in_pocket." + std::to_string(i), "tool " + tool.dump() + " listed twice");
    }
  }
  if (state.spindle != 0 && state.in_pocket.count(state.spindle) != 0) {
    return failure("spindle", "tool " + std::to_string(state.spindle) +
                                  " is recorded both in the spindle and in its pocket");
  }
  if (!root.contains("lengths") || !root["lengths"].is_object()) {
    return failure("lengths", "expected an object of tool number to length");
  }
  for (const auto& item : root["lengths"].items()) {
    const std::string path = "lengths." + item.key();
    Json key_as_number;
    try {
      key_as_number = Json::parse(item.key());
    } catch (const Json::parse_error&) {
      return failure(path, "the key must be a tool number");
    }
    if (!is_tool_number(key_as_number) || key_as_number.dump() != item.key()) {
      return failure(path, "the key must be a tool number");
    }
    if (!item.value().is_number() || !std::isfinite(item.value().get<double>())) {
      return failure(path, "expected a finite number, got " + item.value().dump());
    }
    state.lengths[key_as_number.get<int>()] = item.value().get<double>();
  }
  return {state, ""};
}

}  // namespace fatc
