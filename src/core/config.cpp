#include "config.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

namespace fatc {
namespace {

using Json = nlohmann::json;

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string join_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

std::string describe(const Json& value) {
  if (value.is_null()) return "null";
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_object()) return "an object";
  if (value.is_array()) return "an array";
  if (value.is_string()) return value.dump();
  return value.dump();
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

/// Reads values out of the parsed JSON, collecting one message per problem.
class Reader {
 public:
  std::vector<std::string> errors;

  void error(const std::string& path, const std::string& what) {
    errors.push_back((path.empty() ? std::string("config") : path) + ": " + what);
  }

  void reject_unknown_keys(const Json& object, const std::string& path,
                           std::initializer_list<const char*> known) {
    for (const auto& item : object.items()) {
      const std::string& key = item.key();
      if (std::any_of(known.begin(), known.end(), [&](const char* k) { return key == k; })) continue;
      std::string best;
      std::size_t best_distance = std::numeric_limits<std::size_t>::max();
      for (const char* candidate : known) {
        const std::size_t d = edit_distance(key, candidate);
        if (d < best_distance) {
          best_distance = d;
          best = candidate;
        }
      }
      std::string message = "unknown key";
      if (best_distance <= std::max<std::size_t>(2, key.size() / 3)) {
        message += ", did you mean \"" + best + "\"?";
      }
      error(join_path(path, key), message);
    }
  }

  /// The number at object[key]; nullopt and one message when it is missing
  /// (and required), not a number, or not finite.
  std::optional<double> number(const Json& object, const std::string& path, const char* key,
                               bool required) {
    const std::string here = join_path(path, key);
    const auto found = object.find(key);
    if (found == object.end()) {
      if (required) error(here, "missing");
      return std::nullopt;
    }
    if (!found->is_number()) {
      error(here, "expected a number, got " + describe(*found));
      return std::nullopt;
    }
    const double value = found->get<double>();
    if (!std::isfinite(value)) {
      error(here, "expected a finite number, got " + found->dump());
      return std::nullopt;
    }
    return value;
  }

  /// Like number(), with a lower bound: strictly above it, or at least it.
  void bounded(const Json& object, const std::string& path, const char* key, double& target,
               double bound, bool strictly, bool required) {
    const auto value = number(object, path, key, required);
    if (!value) return;
    if (strictly ? *value <= bound : *value < bound) {
      error(join_path(path, key), std::string("must be ") + (strictly ? "above " : "at least ") +
                                      format_number(bound) + ", got " + format_number(*value));
      return;
    }
    target = *value;
  }

  const Json* object(const Json& parent, const std::string& path, const char* key, bool required) {
    const auto found = parent.find(key);
    if (found == parent.end()) {
      if (required) error(join_path(path, key), "missing");
      return nullptr;
    }
    if (!found->is_object()) {
      error(join_path(path, key), "expected an object, got " + describe(*found));
      return nullptr;
    }
    return &*found;
  }

  /// A point whose axes may each be absent (pocket entries, pocket_default).
  struct PartialPoint {
    std::optional<double> x, y, z;
  };

  PartialPoint partial_point(const Json& object, const std::string& path) {
    reject_unknown_keys(object, path, {"x", "y", "z"});
    return {number(object, path, "x", false), number(object, path, "y", false),
            number(object, path, "z", false)};
  }

  std::optional<Point> point(const Json& parent, const std::string& path, const char* key) {
    const Json* object = this->object(parent, path, key, true);
    if (!object) return std::nullopt;
    const std::string here = join_path(path, key);
    reject_unknown_keys(*object, here, {"x", "y", "z"});
    const auto x = number(*object, here, "x", true);
    const auto y = number(*object, here, "y", true);
    const auto z = number(*object, here, "z", true);
    if (!x || !y || !z) return std::nullopt;
    return Point{*x, *y, *z};
  }
};

std::optional<int> tool_number(const std::string& key) {
  if (key.empty() || key.size() > 9 || key[0] == '0') return std::nullopt;
  if (!std::all_of(key.begin(), key.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return std::nullopt;
  }
  return std::stoi(key);
}

void read_pockets(Reader& reader, const Json& root, Config& config) {
  Reader::PartialPoint fallback;
  if (const Json* defaults = reader.object(root, "", "pocket_default", false)) {
    fallback = reader.partial_point(*defaults, "pocket_default");
  }
  const Json* pockets = reader.object(root, "", "pockets", true);
  if (!pockets) return;
  if (pockets->empty()) {
    reader.error("pockets", "no pockets defined; add at least one, e.g. \"1\": {\"x\": 10}");
    return;
  }
  for (const auto& item : pockets->items()) {
    const std::string here = "pockets." + item.key();
    const auto tool = tool_number(item.key());
    if (!tool) {
      reader.error(here, "the key must be a tool number, a positive integer like \"7\"");
      continue;
    }
    if (!item.value().is_object()) {
      reader.error(here, "expected an object, got " + describe(item.value()));
      continue;
    }
    const auto own = reader.partial_point(item.value(), here);
    bool complete = true;
    auto merge = [&](const std::optional<double>& mine, const std::optional<double>& common,
                     const char* axis) {
      if (mine) return *mine;
      if (common) return *common;
      reader.error(join_path(here, axis), std::string("missing, and pocket_default has no ") + axis);
      complete = false;
      return 0.0;
    };
    const Point position{merge(own.x, fallback.x, "x"), merge(own.y, fallback.y, "y"),
                         merge(own.z, fallback.z, "z")};
    if (complete) config.pockets[*tool] = position;
  }
}

void read_flush(Reader& reader, const Json& root, Config& config) {
  const Json* flush = reader.object(root, "", "flush", false);
  if (!flush) return;
  reader.reject_unknown_keys(*flush, "flush", {"pulses", "pulse_seconds", "pause_seconds"});
  if (const auto pulses = reader.number(*flush, "flush", "pulses", false)) {
    if (*pulses < 0 || *pulses > 20 || std::floor(*pulses) != *pulses) {
      reader.error("flush.pulses", "must be a whole number from 0 to 20, got " + format_number(*pulses));
    } else {
      config.flush.pulses = static_cast<int>(*pulses);
    }
  }
  reader.bounded(*flush, "flush", "pulse_seconds", config.flush.pulse_seconds, 0.0, true, false);
  reader.bounded(*flush, "flush", "pause_seconds", config.flush.pause_seconds, 0.0, true, false);
}

void read_probe_after_change(Reader& reader, const Json& root, Config& config) {
  if (const auto mode = root.find("probe_after_change"); mode != root.end()) {
    if (*mode == "off") {
      config.probe_after_change = ProbeAfterChange::off;
    } else if (*mode == "measure") {
      config.probe_after_change = ProbeAfterChange::measure;
    } else if (*mode == "check") {
      config.probe_after_change = ProbeAfterChange::check;
    } else {
      reader.error("probe_after_change",
                   "expected \"off\", \"measure\" or \"check\", got " + describe(*mode));
    }
  }
  if (root.contains("probe_check_tolerance")) {
    double tolerance = 0.0;
    const std::size_t before = reader.errors.size();
    reader.bounded(root, "", "probe_check_tolerance", tolerance, 0.0, true, false);
    if (reader.errors.size() == before) config.probe_check_tolerance = tolerance;
  }
}

void check_geometry(Reader& reader, Config& config) {
  if (config.pocket_above_clearance_offset_z <= config.pocket_above_chuck_offset_z) {
    reader.error("pocket_above_clearance_offset_z",
                 "must be above pocket_above_chuck_offset_z (" +
                     format_number(config.pocket_above_chuck_offset_z) + "), got " +
                     format_number(config.pocket_above_clearance_offset_z));
  }
  const double side = std::hypot(config.pocket_side_offset.x, config.pocket_side_offset.y);
  if (side == 0.0) {
    reader.error("pocket_side_offset", "must not be zero in both x and y: the side is where the "
                                       "spindle slows down before entering a pocket");
  }
  for (auto a = config.pockets.begin(); a != config.pockets.end(); ++a) {
    for (auto b = std::next(a); b != config.pockets.end(); ++b) {
      const double distance = std::hypot(a->second.x - b->second.x, a->second.y - b->second.y);
      if (distance < side) {
        reader.error("pockets." + std::to_string(b->first),
                     "only " + format_number(distance) + " from pocket " + std::to_string(a->first) +
                         ", closer than the side offset (" + format_number(side) + ")");
      }
    }
  }
  if (config.probe_limit.z > config.loading.z) {
    reader.error("probe_limit.z", "must not be above loading.z (" + format_number(config.loading.z) +
                                      "), got " + format_number(config.probe_limit.z));
  }
  if (config.rack_keepout_margin && *config.rack_keepout_margin >= side && side > 0.0) {
    reader.error("rack_keepout_margin", "must be smaller than the side offset (" +
                                            format_number(side) + "), got " +
                                            format_number(*config.rack_keepout_margin));
  }
}

/// Names and line/column of a JSON syntax error, from the byte offset.
std::string syntax_error(const std::string& text, const nlohmann::json::parse_error& e) {
  std::size_t line = 1;
  std::size_t column = 1;
  const std::size_t end = std::min<std::size_t>(e.byte == 0 ? 0 : e.byte - 1, text.size());
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  std::string what = e.what();
  const auto colon = what.rfind(": ");
  if (colon != std::string::npos) what = what.substr(colon + 2);
  return "line " + std::to_string(line) + ", column " + std::to_string(column) +
         ": invalid JSON: " + what;
}

/// nlohmann keeps the last of two equal keys; a config must not lose one
/// silently. Watches the parse and notes every key an object already had.
class DuplicateKeys {
 public:
  std::vector<std::string> found;

  Json::parser_callback_t callback() {
    return [this](int, Json::parse_event_t event, Json& parsed) {
      if (event == Json::parse_event_t::object_start) {
        levels_.emplace_back();
      } else if (event == Json::parse_event_t::object_end && !levels_.empty()) {
        levels_.pop_back();
      } else if (event == Json::parse_event_t::key && !levels_.empty()) {
        const std::string key = parsed.get<std::string>();
        std::string path;
        for (std::size_t i = 0; i + 1 < levels_.size(); ++i) path = join_path(path, levels_[i].last_key);
        path = join_path(path, key);
        if (!levels_.back().keys.insert(key).second) found.push_back(path + ": appears twice");
        levels_.back().last_key = key;
      }
      return true;
    };
  }

 private:
  struct Level {
    std::set<std::string> keys;
    std::string last_key;
  };
  std::vector<Level> levels_;
};

}  // namespace

const char* units_name(Units units) { return units == Units::mm ? "mm" : "inch"; }

std::string format_length(const Config& config, double length) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, config.units == Units::inch ? "%.5f inch" : "%.4f mm",
                length);
  return buffer;
}

double Config::check_tolerance() const {
  if (probe_check_tolerance) return *probe_check_tolerance;
  return units == Units::inch ? 0.004 : 0.1;
}

double Config::keepout_margin() const {
  if (rack_keepout_margin) return *rack_keepout_margin;
  return std::hypot(pocket_side_offset.x, pocket_side_offset.y) / 2.0;
}

ConfigResult parse_config(const std::string& json_text) {
  ConfigResult result;
  Json root;
  DuplicateKeys duplicates;
  try {
    root = Json::parse(json_text, duplicates.callback());
  } catch (const Json::parse_error& e) {
    result.errors.push_back(syntax_error(json_text, e));
    return result;
  } catch (const Json::exception& e) {
    std::string what = e.what();
    what = what.substr(what.find("] ") + 2);
    result.errors.push_back("config: invalid JSON: " + what);
    return result;
  }
  if (!root.is_object()) {
    result.errors.push_back("config: expected a JSON object at the top, got " + describe(root));
    return result;
  }
  Reader reader;
  reader.errors = duplicates.found;
  reader.reject_unknown_keys(root, "",
                             {"units",
                              "probe_length_compensation_offset",
                              "probe_retract_offset_z",
                              "pocket_side_offset",
                              "pocket_above_chuck_offset_z",
                              "pocket_above_clearance_offset_z",
                              "chuck_seconds",
                              "loading",
                              "probe_limit",
                              "safe",
                              "pocket_default",
                              "pockets",
                              "pocket_feed",
                              "probe_seek_feed",
                              "probe_latch_feed",
                              "probe_backoff",
                              "flush",
                              "spindle_stop_timeout_seconds",
                              "rack_keepout_margin",
                              "probe_after_change",
                              "probe_check_tolerance",
                              "manual_tools"});

  Config config;
  if (const auto units = root.find("units"); units != root.end()) {
    if (*units == "mm") {
      config.units = Units::mm;
    } else if (*units == "inch") {
      config.units = Units::inch;
    } else {
      reader.error("units", "expected \"mm\" or \"inch\", got " + describe(*units));
    }
  }
  if (const auto v = reader.number(root, "", "probe_length_compensation_offset", true)) {
    config.probe_length_compensation_offset = *v;
  }
  reader.bounded(root, "", "probe_retract_offset_z", config.probe_retract_offset_z, 0.0, true, true);
  if (const Json* side = reader.object(root, "", "pocket_side_offset", true)) {
    reader.reject_unknown_keys(*side, "pocket_side_offset", {"x", "y"});
    const auto x = reader.number(*side, "pocket_side_offset", "x", true);
    const auto y = reader.number(*side, "pocket_side_offset", "y", true);
    if (x && y) config.pocket_side_offset = {*x, *y};
  }
  reader.bounded(root, "", "pocket_above_chuck_offset_z", config.pocket_above_chuck_offset_z, 0.0,
                 true, true);
  reader.bounded(root, "", "pocket_above_clearance_offset_z",
                 config.pocket_above_clearance_offset_z, 0.0, true, true);
  reader.bounded(root, "", "chuck_seconds", config.chuck_seconds, 0.0, true, true);
  const auto loading = reader.point(root, "", "loading");
  const auto probe_limit = reader.point(root, "", "probe_limit");
  const auto safe = reader.point(root, "", "safe");
  if (loading) config.loading = *loading;
  if (probe_limit) config.probe_limit = *probe_limit;
  if (safe) config.safe = *safe;
  read_pockets(reader, root, config);

  reader.bounded(root, "", "pocket_feed", config.pocket_feed, 0.0, true, false);
  reader.bounded(root, "", "probe_seek_feed", config.probe_seek_feed, 0.0, true, false);
  reader.bounded(root, "", "probe_latch_feed", config.probe_latch_feed, 0.0, true, false);
  reader.bounded(root, "", "probe_backoff", config.probe_backoff, 0.0, true, false);
  read_flush(reader, root, config);
  reader.bounded(root, "", "spindle_stop_timeout_seconds", config.spindle_stop_timeout_seconds, 0.0,
                 true, false);
  double margin = 0.0;
  if (root.contains("rack_keepout_margin")) {
    const std::size_t before = reader.errors.size();
    reader.bounded(root, "", "rack_keepout_margin", margin, 0.0, false, false);
    if (reader.errors.size() == before) config.rack_keepout_margin = margin;
  }

  read_probe_after_change(reader, root, config);
  if (const auto manual = root.find("manual_tools"); manual != root.end()) {
    if (manual->is_boolean()) {
      config.manual_tools = manual->get<bool>();
    } else {
      reader.error("manual_tools", "expected true or false, got " + describe(*manual));
    }
  }

  // Relations between keys only mean something once every key read cleanly.
  if (reader.errors.empty()) check_geometry(reader, config);
  if (reader.errors.empty()) {
    result.config = config;
  } else {
    result.errors = reader.errors;
  }
  return result;
}

}  // namespace fatc
