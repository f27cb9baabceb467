#include "parse_config.hpp"

#include <cmath>
#include <initializer_list>
#include <set>
#include <tuple>

#include "json_text.hpp"
#include "pocket_reading.hpp"
#include "chuck.hpp"
#include "rack_touch.hpp"
#include "reader.hpp"
#include "relations.hpp"
#include "tool_rules.hpp"

namespace fatc {
namespace {

using namespace reading;

void read_flush(Reader& reader, const Json& root, Config& config) {
  const Json* flush = reader.object(root, "", "flush", false);
  if (!flush) return;
  reader.reject_unknown_keys(*flush, "flush");
  if (const auto pulses = reader.number(*flush, "flush", "pulses", false)) {
    const Range bounds = *key("flush.pulses").bounds;
    if (*pulses < bounds.min || *pulses > bounds.max || std::floor(*pulses) != *pulses) {
      reader.error("flush.pulses", "must be a whole number from " + format_number(bounds.min) +
                                       " to " + format_number(bounds.max) + ", got " +
                                       format_number(*pulses));
    } else {
      config.flush.pulses = static_cast<int>(*pulses);
    }
  }
  reader.read(*flush, "flush", "pulse_seconds", config.flush.pulse_seconds);
  reader.read(*flush, "flush", "pause_seconds", config.flush.pause_seconds);
}

/// A top-level key naming one of a few words: `target` takes the value of the
/// word given, left as it was when absent; anything else is one message
/// listing the words.
template <class T>
void read_choice(Reader& reader, const Json& root, const char* key,
                 std::initializer_list<std::pair<const char*, T>> words, T& target) {
  const auto given = root.find(key);
  if (given == root.end()) return;
  std::string listed;
  std::size_t i = 0;
  for (const auto& [word, value] : words) {
    if (*given == word) {
      target = value;
      return;
    }
    ++i;
    listed += std::string(i == 1 ? "" : i == words.size() ? " or " : ", ") + "\"" + word + "\"";
  }
  reader.error(key, "expected " + listed + ", got " + describe(*given));
}

void read_probe_after_change(Reader& reader, const Json& root, Config& config) {
  if (const auto rule = read_rule(reader, root, "", "probe_after_change")) {
    config.probe_after_change = *rule;
  }
  config.probe_check_tolerance =
      reader.declared(root, "", "probe_check_tolerance");
}

/// `true` or `false`, one message otherwise.
std::optional<bool> boolean(Reader& reader, const Json& value, const std::string& path) {
  if (value.is_boolean()) return value.get<bool>();
  reader.error(path, "expected true or false, got " + describe(value));
  return std::nullopt;
}

/// `pocket_occupancy`: true (every pocket has a sensor), false, or the
/// pockets that have one, by their numbers: [1, 2, 5].
void read_pocket_occupancy(Reader& reader, const Json& root, const Json& value, Config& config) {
  const std::string here = "sensors.pocket_occupancy";
  if (value.is_boolean()) {
    if (value.get<bool>()) {
      for (const auto& pocket : config.pockets)
        config.sensors.pocket_occupancy.insert(pocket.first);
    }
    return;
  }
  if (!value.is_array()) {
    reader.error(here,
                 "expected true, false or a list of pockets like [1, 2], got " + describe(value));
    return;
  }
  // Compared with the keys as written, so a pocket that failed for another
  // reason is not reported twice.
  std::set<int> configured;
  if (const auto pockets = root.find("pockets"); pockets != root.end() && pockets->is_object()) {
    for (const auto& item : pockets->items()) {
      if (const auto number = tool_number_key(item.key())) configured.insert(*number);
    }
  }
  for (std::size_t i = 0; i < value.size() && !reader.full(); ++i) {
    const std::string at = here + "[" + std::to_string(i) + "]";
    const Json& entry = value[i];
    if (!is_tool_number(entry)) {
      reader.error(at, "expected a pocket number (1 to 999999999), got " + describe(entry));
      continue;
    }
    const int number = entry.get<int>();
    if (configured.count(number) == 0) {
      reader.error(at, "pocket " + std::to_string(number) + " is not in pockets");
    } else if (!config.sensors.pocket_occupancy.insert(number).second) {
      reader.error(at, "pocket " + std::to_string(number) + " is listed twice");
    }
  }
}

/// The sensors of sensor_list.hpp the object at `path` wires ("sensors",
/// "rack_cover"), each off unless it says true; read in the order of the
/// reference (keys.cpp), so several problems are listed in that order.
void read_wired(Reader& reader, const Json& object, const std::string& path, SensorConfig& wired) {
  for (const std::string& name : keys_below(path)) {
    const std::string here = join_path(path, name);
    const auto sensor =
        std::find_if(std::begin(kSensors), std::end(kSensors),
                     [&](const SensorDeclaration& s) { return here == s.words.key; });
    const auto found = object.find(name);
    if (sensor == std::end(kSensors) || found == object.end()) continue;
    if (const auto value = boolean(reader, *found, here)) wired.wire(sensor->sensor, *value);
  }
}

/// `sensors`: which optional sensors are wired.
void read_sensors(Reader& reader, const Json& root, Config& config) {
  const Json* sensors = reader.object(root, "", "sensors", false);
  if (!sensors) return;
  reader.reject_unknown_keys(*sensors, "sensors");
  read_wired(reader, *sensors, "sensors", config.sensors);
  if (const auto occupancy = sensors->find("pocket_occupancy"); occupancy != sensors->end()) {
    read_pocket_occupancy(reader, root, *occupancy, config);
  }
}

/// `rack_cover`: present (even `{}`) means the rack has a cover to drive.
void read_rack_cover(Reader& reader, const Json& root, Config& config) {
  const Json* cover = reader.object(root, "", "rack_cover", false);
  if (!cover) return;
  reader.reject_unknown_keys(*cover, "rack_cover");
  RackCoverConfig rack_cover;
  read_wired(reader, *cover, "rack_cover", config.sensors);
  reader.read(*cover, "rack_cover", "seconds", rack_cover.seconds);
  reader.read(*cover, "rack_cover", "timeout_seconds", rack_cover.timeout_seconds);
  config.rack_cover = rack_cover;
}

/// The keys whose default has a unit: each takes its default in the config's
/// units where left out, and is named in `defaulted`.
void read_unit_defaulted(Reader& reader, const Json& root, Config& config) {
  const std::tuple<const char*, double Config::*, UnitDefault> keys[] = {
      {"pocket_feed", &Config::pocket_feed, unit_default::pocket_feed},
      {"probe_seek_feed", &Config::probe_seek_feed, unit_default::probe_seek_feed},
      {"probe_latch_feed", &Config::probe_latch_feed, unit_default::probe_latch_feed},
      {"probe_backoff", &Config::probe_backoff, unit_default::probe_backoff}};
  for (const auto& [key, member, fallback] : keys) {
    config.*member = fallback.in(config.units);
    if (root.find(key) == root.end()) config.defaulted.push_back(key);
    reader.read(root, "", key, config.*member);
  }
  for (const char* key : {"verify_feed", "probe_check_tolerance", "probe_window",
                          "rack_keepout_margin", "rack_keepout_above"}) {
    if (root.find(key) == root.end()) config.defaulted.push_back(key);
  }
}

}  // namespace

ConfigResult parse_config(const std::string& json_text) {
  ConfigResult result;
  JsonText parsed = parse_json_text(json_text);
  if (!parsed.value) {
    result.errors = std::move(parsed.errors);
    return result;
  }
  const Json& root = *parsed.value;
  if (!root.is_object()) {
    result.errors.push_back("config: expected a JSON object at the top, got " + describe(root));
    return result;
  }
  Reader reader;
  reader.reject_unknown_keys(root, "");

  Config config;
  read_choice(reader, root, "units", {std::pair{"mm", Units::mm}, std::pair{"inch", Units::inch}},
              config.units);
  reader.units = config.units;
  reader.read(root, "", "probe_length_compensation_offset", config.probe_length_compensation_offset);
  reader.read(root, "", "probe_retract_offset_z", config.probe_retract_offset_z);
  if (const Json* side = reader.object(root, "", "pocket_side_offset", true)) {
    reader.reject_unknown_keys(*side, "pocket_side_offset");
    const auto x = reader.declared(*side, "pocket_side_offset", "x");
    const auto y = reader.declared(*side, "pocket_side_offset", "y");
    if (x && y) config.pocket_side_offset = {*x, *y};
  }
  reader.read(root, "", "pocket_above_chuck_offset_z", config.pocket_above_chuck_offset_z);
  reader.read(root, "", "pocket_above_clearance_offset_z", config.pocket_above_clearance_offset_z);
  reader.read(root, "", "chuck_seconds", config.chuck_seconds);
  const auto loading = reader.point(root, "", "loading");
  const auto probe_limit = reader.point(root, "", "probe_limit");
  const auto safe = reader.point(root, "", "safe");
  if (loading) config.loading = *loading;
  if (probe_limit) config.probe_limit = *probe_limit;
  if (safe) config.safe = *safe;
  read_pockets(reader, root, config);

  read_unit_defaulted(reader, root, config);
  config.verify_feed = reader.declared(root, "", "verify_feed");
  read_flush(reader, root, config);
  reader.read(root, "", "spindle_stop_timeout_seconds", config.spindle_stop_timeout_seconds);
  if (const auto overlap = root.find("move_while_spindle_stops"); overlap != root.end()) {
    if (const auto value = boolean(reader, *overlap, "move_while_spindle_stops")) {
      config.move_while_spindle_stops = *value;
    }
  }
  reader.read(root, "", "blend_tolerance", config.blend_tolerance);
  config.rack_keepout_margin = reader.declared(root, "", "rack_keepout_margin");
  if (const auto all = root.find("rack_keepout_all_motion"); all != root.end()) {
    if (const auto value = boolean(reader, *all, "rack_keepout_all_motion")) {
      config.rack_keepout_all_motion = *value;
    }
  }
  config.rack_keepout_above = reader.declared(root, "", "rack_keepout_above");

  read_probe_after_change(reader, root, config);
  read_tools(reader, root, config);
  read_choice(reader, root, "path",
              {std::pair{"prototype", Path::prototype}, std::pair{"direct", Path::direct}},
              config.path);
  if (const auto manual = root.find("manual_tools"); manual != root.end()) {
    if (const auto value = boolean(reader, *manual, "manual_tools")) config.manual_tools = *value;
  }
  read_sensors(reader, root, config);
  reader.read(root, "", "sensor_timeout_seconds", config.sensor_timeout_seconds);
  config.probe_window = reader.declared(root, "", "probe_window");
  read_rack_cover(reader, root, config);
  if (const auto blast = root.find("air_blast"); blast != root.end()) {
    if (const auto value = boolean(reader, *blast, "air_blast")) config.air_blast = *value;
  }
  read_rack_touch(reader, root, config);
  read_chuck(reader, root, config);

  // Relations between keys only mean something once every key read cleanly.
  if (reader.count() == 0) check_relations(reader, config);
  if (reader.count() == 0) check_tools(reader, config);
  if (reader.count() == 0) check_rack_touch(reader, config);
  if (reader.count() == 0) check_chuck(reader, config);
  if (reader.count() == 0) {
    result.config = config;
  } else {
    result.errors = reader.errors;
    if (reader.unlisted > 0) {
      result.errors.push_back("and " + std::to_string(reader.unlisted) + " more problems");
    }
  }
  return result;
}

}  // namespace fatc
