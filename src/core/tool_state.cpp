#include "tool_state.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "json_text.hpp"
#include "quote.hpp"

namespace fatc {
namespace {

using Json = nlohmann::json;
constexpr int kFormatVersion = 1;
/// Measured lengths are bounded like config coordinates.
constexpr double kMaxLength = 100000.0;
/// in_progress texts are written by the component: short words, one line.
constexpr std::size_t kMaxProgressText = 200;

ToolStateResult failure(const std::string& path, const std::string& what) {
  return {std::nullopt, path + ": " + what};
}

bool is_zero(const Json& value) {
  return (value.is_number_integer() || value.is_number_unsigned()) &&
         value.get<std::int64_t>() == 0;
}

/// Why `value` is no in_progress text, or empty.
std::string text_problem(const Json& value) {
  if (!value.is_string()) return "expected text, got " + describe(value);
  const std::string& text = value.get_ref<const std::string&>();
  if (text.size() > kMaxProgressText) {
    return "expected at most " + std::to_string(kMaxProgressText) + " characters, got " +
           std::to_string(text.size()) + ": " + quote(text);
  }
  for (const char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) {
      return "expected one line of text without control characters, got " + quote(text);
    }
  }
  return "";
}

}  // namespace

ToolState ToolState::fresh(const Config& config) {
  ToolState state;
  for (const auto& pocket : config.pockets) state.in_pocket.insert(pocket.first);
  return state;
}

bool ToolState::operator==(const ToolState& other) const {
  return spindle == other.spindle && uncertain == other.uncertain && in_pocket == other.in_pocket &&
         lengths == other.lengths && in_progress == other.in_progress;
}

void ToolState::confirm(int spindle_tool, std::optional<bool> pocket_holds_tool) {
  const int pocket = in_progress ? in_progress->pocket : 0;
  if (pocket != 0 && pocket_holds_tool == true) in_pocket.insert(pocket);
  if (pocket != 0 && pocket_holds_tool == false) in_pocket.erase(pocket);
  spindle = spindle_tool;
  in_pocket.erase(spindle_tool);
  uncertain = false;
  in_progress.reset();
}

std::string to_json(const ToolState& state) {
  Json lengths = Json::object();
  for (const auto& [tool, length] : state.lengths) lengths[std::to_string(tool)] = length;
  Json root = {{"version", kFormatVersion},
               {"spindle", state.spindle},
               {"uncertain", state.uncertain},
               {"in_pocket", state.in_pocket},
               {"lengths", lengths}};
  if (state.in_progress) {
    root["in_progress"] = {{"sequence", state.in_progress->sequence},
                           {"step", state.in_progress->step},
                           {"pocket", state.in_progress->pocket}};
  }
  return root.dump(2) + "\n";
}

ToolStateResult tool_state_from_json(const std::string& text) {
  const JsonText parsed = parse_json_text(text);
  if (!parsed.value) return {std::nullopt, parsed.errors.front()};
  const Json& root = *parsed.value;
  if (!root.is_object()) return failure("state", "expected a JSON object, got " + describe(root));
  for (const auto& item : root.items()) {
    const auto& k = item.key();
    if (k != "version" && k != "spindle" && k != "uncertain" && k != "in_pocket" &&
        k != "lengths" && k != "in_progress") {
      return failure(join_path("", k), "unknown key");
    }
  }
  if (!root.contains("version") || root["version"] != kFormatVersion) {
    return failure("version",
                   "expected 1, got " + (root.contains("version") ? describe(root["version"])
                                                                  : std::string("nothing")));
  }
  ToolState state;
  if (!root.contains("spindle")) return failure("spindle", "missing");
  const Json& spindle = root["spindle"];
  if (!(is_zero(spindle) || is_tool_number(spindle))) {
    return failure("spindle", "expected 0 or a tool number, got " + describe(spindle));
  }
  state.spindle = spindle.get<int>();
  if (!root.contains("uncertain") || !root["uncertain"].is_boolean()) {
    return failure("uncertain", "expected true or false, got " + (root.contains("uncertain")
                                                                      ? describe(root["uncertain"])
                                                                      : std::string("nothing")));
  }
  state.uncertain = root["uncertain"].get<bool>();
  if (!root.contains("in_pocket") || !root["in_pocket"].is_array()) {
    return failure("in_pocket", "expected an array of tool numbers, got " +
                                    (root.contains("in_pocket") ? describe(root["in_pocket"])
                                                                : std::string("nothing")));
  }
  for (std::size_t i = 0; i < root["in_pocket"].size(); ++i) {
    const Json& tool = root["in_pocket"][i];
    const std::string path = "in_pocket." + std::to_string(i);
    if (!is_tool_number(tool))
      return failure(path, "expected a tool number, got " + describe(tool));
    if (!state.in_pocket.insert(tool.get<int>()).second) {
      return failure(path, "tool " + tool.dump() + " listed twice");
    }
  }
  if (state.spindle != 0 && state.in_pocket.count(state.spindle) != 0) {
    return failure("spindle", "tool " + std::to_string(state.spindle) +
                                  " is recorded both in the spindle and in its pocket");
  }
  if (!root.contains("lengths") || !root["lengths"].is_object()) {
    return failure("lengths", "expected an object of tool number to length, got " +
                                  (root.contains("lengths") ? describe(root["lengths"])
                                                            : std::string("nothing")));
  }
  for (const auto& item : root["lengths"].items()) {
    const std::string path = join_path("lengths", item.key());
    const auto tool = tool_number_key(item.key());
    if (!tool) return failure(path, "the key must be a tool number");
    const Json& length = item.value();
    if (!length.is_number() || !std::isfinite(length.get<double>())) {
      return failure(path, "expected a finite number, got " + describe(length));
    }
    if (std::fabs(length.get<double>()) > kMaxLength) {
      return failure(path, "must be from -100000 to 100000, got " + length.dump());
    }
    state.lengths[*tool] = length.get<double>();
  }
  if (root.contains("in_progress")) {
    const Json& progress = root["in_progress"];
    if (!progress.is_object()) {
      return failure("in_progress", "expected an object, got " + describe(progress));
    }
    for (const auto& item : progress.items()) {
      if (item.key() != "sequence" && item.key() != "step" && item.key() != "pocket") {
        return failure(join_path("in_progress", item.key()), "unknown key");
      }
    }
    for (const char* key : {"sequence", "step"}) {
      if (!progress.contains(key)) return failure(std::string("in_progress.") + key, "missing");
      if (const std::string why = text_problem(progress[key]); !why.empty()) {
        return failure(std::string("in_progress.") + key, why);
      }
    }
    if (!progress.contains("pocket")) return failure("in_progress.pocket", "missing");
    if (!(is_zero(progress["pocket"]) || is_tool_number(progress["pocket"]))) {
      return failure("in_progress.pocket",
                     "expected 0 or a tool number, got " + describe(progress["pocket"]));
    }
    state.in_progress =
        InProgress{progress["sequence"].get<std::string>(), progress["step"].get<std::string>(),
                   progress["pocket"].get<int>()};
    // A sequence cut off by a crash leaves nothing certain.
    state.uncertain = true;
  }
  return {state, ""};
}

}  // namespace fatc
