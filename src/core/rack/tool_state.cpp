#include "tool_state.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "../config/json_text.hpp"
#include "../config/quote.hpp"

namespace fatc {
namespace {

using Json = nlohmann::json;
/// Version 2 names each pocket's tool; version 1 (pocket N is tool N's) is still read.
constexpr int kFormatVersion = 2;
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
  // The text is shown to the operator after a crash: it must read as it is.
  if (has_invisible_characters(text)) {
    return "expected text without invisible or direction-changing characters, got " + quote(text);
  }
  return "";
}

/// `datum`: {"changes": n, "drift": "..."}, both optional.
std::string read_datum(const Json& datum, DatumWatch& watch) {
  if (!datum.is_object()) return "datum: expected an object, got " + describe(datum);
  for (const auto& item : datum.items()) {
    if (item.key() != "changes" && item.key() != "drift") {
      return join_path("datum", item.key()) + ": unknown key";
    }
  }
  if (datum.contains("changes")) {
    const Json& changes = datum["changes"];
    if (!(changes.is_number_integer() || changes.is_number_unsigned()) ||
        changes.get<std::int64_t>() < 0 || changes.get<std::int64_t>() > 1000000000) {
      return "datum.changes: expected a count from 0 to 1000000000, got " + describe(changes);
    }
    watch.changes = changes.get<int>();
  }
  if (datum.contains("drift")) {
    if (const std::string why = text_problem(datum["drift"]); !why.empty()) {
      return "datum.drift: " + why;
    }
    watch.drift = datum["drift"].get<std::string>();
  }
  return "";
}

/// Version 1's `in_pocket`: the tools sitting in their own pocket (pocket N is tool N's).
std::string read_in_pocket(const Json& root, ToolState& state) {
  if (!root.contains("in_pocket") || !root["in_pocket"].is_array()) {
    return "in_pocket: expected an array of tool numbers, got " +
           (root.contains("in_pocket") ? describe(root["in_pocket"]) : std::string("nothing"));
  }
  for (std::size_t i = 0; i < root["in_pocket"].size(); ++i) {
    const Json& tool = root["in_pocket"][i];
    const std::string path = "in_pocket." + std::to_string(i);
    if (!is_tool_number(tool)) return path + ": expected a tool number, got " + describe(tool);
    if (!state.pockets.emplace(tool.get<int>(), PocketState{tool.get<int>(), true}).second) {
      return path + ": tool " + tool.dump() + " listed twice";
    }
  }
  return "";
}

/// `pockets`: {"3": {"tool": 7, "in_pocket": true}, ...}.
std::string read_pockets(const Json& root, ToolState& state) {
  if (!root.contains("pockets") || !root["pockets"].is_object()) {
    return "pockets: expected an object of pocket number to {tool, in_pocket}, got " +
           (root.contains("pockets") ? describe(root["pockets"]) : std::string("nothing"));
  }
  std::map<int, int> pocket_of_tool;
  for (const auto& item : root["pockets"].items()) {
    const std::string path = join_path("pockets", item.key());
    const auto number = tool_number_key(item.key());
    if (!number) return path + ": the key must be a pocket number";
    const Json& entry = item.value();
    if (!entry.is_object()) return path + ": expected {\"tool\": N, \"in_pocket\": true|false}";
    for (const auto& key : entry.items()) {
      if (key.key() != "tool" && key.key() != "in_pocket") {
        return join_path(path, key.key()) + ": unknown key";
      }
    }
    if (!entry.contains("tool") || !(is_zero(entry["tool"]) || is_tool_number(entry["tool"]))) {
      return path + ".tool: expected 0 or a tool number, got " +
             (entry.contains("tool") ? describe(entry["tool"]) : std::string("nothing"));
    }
    if (!entry.contains("in_pocket") || !entry["in_pocket"].is_boolean()) {
      return path + ".in_pocket: expected true or false, got " +
             (entry.contains("in_pocket") ? describe(entry["in_pocket"]) : std::string("nothing"));
    }
    const PocketState pocket{entry["tool"].get<int>(), entry["in_pocket"].get<bool>()};
    if (pocket.tool == 0 && pocket.holds) {
      return path + ".in_pocket: a free pocket (tool 0) cannot hold its tool";
    }
    if (pocket.tool != 0) {
      if (const auto [other, fresh] = pocket_of_tool.emplace(pocket.tool, *number); !fresh) {
        return path + ".tool: tool " + std::to_string(pocket.tool) + " is recorded in pocket " +
               std::to_string(other->second) + " too";
      }
    }
    state.pockets[*number] = pocket;
  }
  return "";
}

}  // namespace

ToolState ToolState::fresh(const Config& config) {
  ToolState state;
  for (const auto& [number, pocket] : config.pockets) {
    state.pockets[number] = {pocket.first_tool, pocket.first_tool != 0};
  }
  return state;
}

bool ToolState::operator==(const ToolState& other) const {
  return spindle == other.spindle && uncertain == other.uncertain && pockets == other.pockets &&
         lengths == other.lengths && in_progress == other.in_progress && datum == other.datum;
}

std::optional<int> ToolState::home_of(int tool) const {
  if (tool == 0) return std::nullopt;
  for (const auto& [number, pocket] : pockets) {
    if (pocket.tool == tool) return number;
  }
  return std::nullopt;
}

std::optional<int> ToolState::pocket_holding(int tool) const {
  const auto home = home_of(tool);
  if (home && pockets.at(*home).holds) return home;
  return std::nullopt;
}

int ToolState::tool_of(int number) const {
  const auto found = pockets.find(number);
  return found == pockets.end() ? 0 : found->second.tool;
}

bool ToolState::holds(int number) const {
  const auto found = pockets.find(number);
  return found != pockets.end() && found->second.tool != 0 && found->second.holds;
}

std::vector<int> ToolState::rack_tools() const {
  std::vector<int> tools;
  for (const auto& [number, pocket] : pockets) {
    if (holds(number)) tools.push_back(pocket.tool);
  }
  return tools;
}

void ToolState::put_in_spindle(int tool) {
  spindle = tool;
  if (const auto home = home_of(tool)) pockets[*home].holds = false;
}

std::vector<int> ToolState::free_pockets() const {
  std::vector<int> free;
  for (const auto& [number, pocket] : pockets) {
    if (pocket.tool == 0) free.push_back(number);
  }
  return free;
}

void ToolState::confirm(int spindle_tool, std::optional<bool> pocket_holds_tool) {
  const int cut_off = in_progress ? in_progress->pocket : 0;
  if (cut_off != 0 && pocket_holds_tool && pockets.count(cut_off) != 0 &&
      pockets[cut_off].tool != 0) {
    pockets[cut_off].holds = *pocket_holds_tool;
  }
  put_in_spindle(spindle_tool);
  uncertain = false;
  in_progress.reset();
}

std::optional<std::string> ToolState::contradiction(int spindle_tool,
                                                    std::optional<bool> pocket_holds_tool) const {
  const int cut_off = in_progress ? in_progress->pocket : 0;
  if (cut_off == 0 || !pocket_holds_tool || !*pocket_holds_tool) return std::nullopt;
  const int own = tool_of(cut_off);
  if (own == 0) {
    return "no tool belongs in pocket " + std::to_string(cut_off) +
           ", where the sequence was cut off";
  }
  if (spindle_tool == own) {
    return "tool " + std::to_string(own) + " cannot be both in the spindle and in its pocket " +
           std::to_string(cut_off);
  }
  return std::nullopt;
}

std::optional<int> return_pocket(const ToolState& tools, const Config& config, int tool) {
  if (const auto home = tools.home_of(tool)) return home;
  const auto first = config.first_pocket_of(tool);
  if (first && tools.tool_of(*first) == 0) return first;
  return std::nullopt;
}

std::string pocket_list(const std::vector<int>& numbers) {
  if (numbers.empty()) return "no pocket";
  std::vector<std::string> names;
  for (const int number : numbers) names.push_back(std::to_string(number));
  return (numbers.size() == 1 ? "pocket " : "pockets ") + listed(names);
}

std::string to_json(const ToolState& state) {
  Json lengths = Json::object();
  for (const auto& [tool, length] : state.lengths) lengths[std::to_string(tool)] = length;
  Json pockets = Json::object();
  for (const auto& [number, pocket] : state.pockets) {
    pockets[std::to_string(number)] = {{"tool", pocket.tool}, {"in_pocket", pocket.holds}};
  }
  Json root = {{"version", kFormatVersion},
               {"spindle", state.spindle},
               {"uncertain", state.uncertain},
               {"pockets", pockets},
               {"lengths", lengths}};
  if (state.in_progress) {
    root["in_progress"] = {{"sequence", state.in_progress->sequence},
                           {"step", state.in_progress->step},
                           {"pocket", state.in_progress->pocket}};
  }
  if (!(state.datum == DatumWatch{})) {
    root["datum"] = {{"changes", state.datum.changes}, {"drift", state.datum.drift}};
  }
  return root.dump(2) + "\n";
}

std::string fit_to_config(ToolState& state, const Config& config, int version) {
  // Recovery asks whether that pocket holds its tool: it must be one the rack has.
  if (const int cut_off = state.in_progress ? state.in_progress->pocket : 0;
      cut_off != 0 && !config.has_pocket(cut_off)) {
    return "in_progress.pocket: the sequence was cut off at pocket " + std::to_string(cut_off) +
           ", which config.json does not have";
  }
  for (const auto& [number, pocket] : state.pockets) {
    // A pocket taken out of the config may go if its tool is not sitting in it.
    if (config.has_pocket(number) || !pocket.holds) continue;
    return "pockets." + std::to_string(number) + ": tool " + std::to_string(pocket.tool) +
           " is recorded in pocket " + std::to_string(number) + ", which config.json does not have";
  }
  for (auto it = state.pockets.begin(); it != state.pockets.end();) {
    it = config.has_pocket(it->first) ? std::next(it) : state.pockets.erase(it);
  }
  for (const auto& [number, pocket] : config.pockets) {
    if (state.pockets.count(number) != 0) continue;
    if (version == 1) {
      state.pockets[number] = {number, false};
      continue;
    }
    const int tool = pocket.first_tool;
    const bool known = tool != 0 && (state.spindle == tool || state.home_of(tool));
    state.pockets[number] = known ? PocketState{} : PocketState{tool, tool != 0};
  }
  return "";
}

ToolStateResult tool_state_from_json(const std::string& text) {
  const JsonText parsed = parse_json_text(text);
  if (!parsed.value) return {std::nullopt, parsed.errors.front()};
  const Json& root = *parsed.value;
  if (!root.is_object()) return failure("state", "expected a JSON object, got " + describe(root));
  if (!root.contains("version") || (root["version"] != 1 && root["version"] != kFormatVersion)) {
    return failure("version",
                   "expected 1 or 2, got " + (root.contains("version") ? describe(root["version"])
                                                                       : std::string("nothing")));
  }
  const int version = root["version"].get<int>();
  const char* rack_key = version == 1 ? "in_pocket" : "pockets";
  for (const auto& item : root.items()) {
    const auto& k = item.key();
    if (k != "version" && k != "spindle" && k != "uncertain" && k != rack_key && k != "lengths" &&
        k != "in_progress" && k != "datum") {
      return failure(join_path("", k), "unknown key");
    }
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
  const std::string why = version == 1 ? read_in_pocket(root, state) : read_pockets(root, state);
  if (!why.empty()) return {std::nullopt, why};
  if (const auto home = state.pocket_holding(state.spindle); home && state.spindle != 0) {
    return failure("spindle", "tool " + std::to_string(state.spindle) +
                                  " is recorded both in the spindle and in pocket " +
                                  std::to_string(*home));
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
                     "expected 0 or a pocket number, got " + describe(progress["pocket"]));
    }
    state.in_progress =
        InProgress{progress["sequence"].get<std::string>(), progress["step"].get<std::string>(),
                   progress["pocket"].get<int>()};
    // A sequence cut off by a crash leaves nothing certain.
    state.uncertain = true;
  }
  if (root.contains("datum")) {
    if (const std::string why = read_datum(root["datum"], state.datum); !why.empty()) {
      return {std::nullopt, why};
    }
  }
  return {state, "", version};
}

int spindle_probe(const Config& config, const ToolState& tools) {
  if (config.is_probe(tools.spindle)) return tools.spindle;
  if (!tools.uncertain) return 0;
  // Cut off: a probe is taken to be out of the spindle only when it is known
  // to sit in its pocket, and that pocket is not the one the sequence was at
  // (a fetch grips before the record says so; a hand-in has no pocket).
  const int cut_at = tools.in_progress ? tools.in_progress->pocket : 0;
  for (const auto& [tool, own] : config.tools) {
    if (own.kind != ToolKind::probe) continue;
    const auto home = tools.home_of(tool);
    if (!home || !tools.holds(*home) || *home == cut_at) return tool;
  }
  return 0;
}

}  // namespace fatc
