#include "config.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <tuple>

#include "../formatted.hpp"
#include "rack_volume.hpp"
#include "json_text.hpp"
#include "reader.hpp"
#include "tool_rules.hpp"

namespace fatc {
namespace {

using namespace reading;

/// A fixed rack with more pockets than this is a mistake, and checking every
/// pair of pockets and every planned move against every pocket is quadratic.
constexpr std::size_t kMaxPockets = 200;

/// The side offset's length (x and y combined).
constexpr double kMinSideOffset = 0.1;

/// What a pocket entry and pocket_default may say besides x, y and z.
struct PocketExtras {
  std::optional<Approach> approach;
  std::optional<PlanarOffset> side_offset;
  bool failed = false;  ///< one of them was given but refused (reported)
};

PocketExtras pocket_extras(Reader& reader, const Json& entry, const std::string& here) {
  PocketExtras extras;
  // Both x and y, each within pocket_side_offset's bounds.
  const Range side_bounds = bounds_in(key("pocket_side_offset.x"), reader.units);
  if (const auto approach = entry.find("approach"); approach != entry.end()) {
    if (*approach == "side") {
      extras.approach = Approach::side;
    } else if (*approach == "top") {
      extras.approach = Approach::top;
    } else {
      reader.error(join_path(here, "approach"),
                   "expected \"side\" or \"top\", got " + describe(*approach));
      extras.failed = true;
    }
  }
  if (entry.contains("side_offset")) {
    const Json* side = reader.object(entry, here, "side_offset", true);
    const std::string at = join_path(here, "side_offset");
    if (side) reader.reject_unknown_keys(*side, at);
    const auto x = side ? reader.ranged(*side, at, "x", side_bounds, true) : std::nullopt;
    const auto y = side ? reader.ranged(*side, at, "y", side_bounds, true) : std::nullopt;
    if (x && y) {
      extras.side_offset = PlanarOffset{*x, *y};
    } else {
      extras.failed = true;
    }
  }
  return extras;
}

/// `tool` of a pocket entry: the tool it holds at first start, 0 for none.
std::optional<int> first_tool(Reader& reader, const Json& entry, const std::string& here,
                              int pocket) {
  const auto tool = entry.find("tool");
  if (tool == entry.end()) return pocket;
  if (tool->is_number_integer() && tool->get<std::int64_t>() == 0) return 0;
  if (!is_tool_number(*tool)) {
    reader.error(
        join_path(here, "tool"),
        "expected a tool number (1 to 999999999) or 0 (starts empty), got " + describe(*tool));
    return std::nullopt;
  }
  return tool->get<int>();
}

void read_pockets(Reader& reader, const Json& root, Config& config) {
  Reader::PartialPoint fallback;
  PocketExtras common;
  if (const Json* defaults = reader.object(root, "", "pocket_default", false)) {
    reader.reject_unknown_keys(*defaults, "pocket_default");
    fallback = reader.partial_point(*defaults, "pocket_default");
    common = pocket_extras(reader, *defaults, "pocket_default");
  }
  const auto defaults = root.find("pocket_default");
  auto default_given = [&](const char* axis) {
    return defaults != root.end() && (!defaults->is_object() || defaults->contains(axis));
  };
  const Json* pockets = reader.object(root, "", "pockets", true);
  if (!pockets) return;
  if (pockets->empty()) {
    reader.error("pockets", "no pockets defined; add at least one, e.g. \"1\": {\"x\": 10}");
    return;
  }
  if (pockets->size() > kMaxPockets) {
    reader.error("pockets", "must hold at most " + std::to_string(kMaxPockets) + " pockets, got " +
                                std::to_string(pockets->size()));
    return;
  }
  std::map<int, int> pocket_of_tool;  // first-start tool -> its pocket, for duplicates
  for (const auto& item : pockets->items()) {
    const std::string here = join_path("pockets", item.key());
    const auto number = tool_number_key(item.key());
    if (!number) {
      reader.error(here, "the key must be a pocket number, a positive integer like \"7\"");
      continue;
    }
    if (!item.value().is_object()) {
      reader.error(here, "expected an object, got " + describe(item.value()));
      continue;
    }
    reader.reject_unknown_keys(item.value(), here);
    const auto own = reader.partial_point(item.value(), here);
    const PocketExtras extras = pocket_extras(reader, item.value(), here);
    const auto tool = first_tool(reader, item.value(), here, *number);
    bool complete = tool.has_value() && !extras.failed && !common.failed;
    auto merge = [&](const std::optional<double>& mine, const std::optional<double>& shared,
                     const char* axis) {
      if (mine) return *mine;
      if (shared) return *shared;
      // A pocket_default that has the axis but failed was reported once already.
      if (!default_given(axis)) {
        reader.error(join_path(here, axis),
                     std::string("missing, and pocket_default has no ") + axis);
      }
      complete = false;
      return 0.0;
    };
    Pocket pocket;
    pocket.at = {merge(own.x, fallback.x, "x"), merge(own.y, fallback.y, "y"),
                 merge(own.z, fallback.z, "z")};
    if (tool && *tool != 0) {
      if (const auto [other, fresh] = pocket_of_tool.emplace(*tool, *number); !fresh) {
        reader.error(join_path(here, "tool"), "tool " + std::to_string(*tool) +
                                                  " already starts in pocket " +
                                                  std::to_string(other->second));
        complete = false;
      }
    }
    if (!complete) continue;
    pocket.first_tool = *tool;
    pocket.approach = extras.approach.value_or(common.approach.value_or(Approach::side));
    pocket.side_offset =
        extras.side_offset.value_or(common.side_offset.value_or(config.pocket_side_offset));
    config.pockets[*number] = pocket;
  }
}

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

/// A side offset says where the spindle slows down before entering a pocket:
/// it must lead out of the pocket's keep-out.
/// (pocket_side_offset itself is held against rack_keepout_margin below.)
void check_side_offset(Reader& reader, const Config& config, const PlanarOffset& offset,
                       const std::string& path, bool pockets_own) {
  const double length = std::hypot(offset.x, offset.y);
  if (length == 0.0) {
    reader.error(path,
                 "must not be zero in both x and y: the side is where the "
                 "spindle slows down before entering a pocket");
  } else if (length < kMinSideOffset) {
    reader.error(path, "must be at least " + format_number(kMinSideOffset) + " " +
                           units_name(config.units) + " long (x and y combined), got " +
                           format_number(length));
  } else if (pockets_own && length <= config.keepout_margin()) {
    reader.error(path, "must lead out of the pocket's keep-out (rack_keepout_margin " +
                           format_number(config.keepout_margin()) + "), got " +
                           format_number(length) + " long");
  }
}

/// A value in a relation between keys, as the user knows it: what they wrote,
/// or the default of a key they left out, which they never typed: "1: its
/// default, left out".
std::string said(const Config& config, const char* key, double value) {
  const bool left_out = std::find(config.defaulted.begin(), config.defaulted.end(), key) !=
                        config.defaulted.end();
  return format_number(value) + (left_out ? ": its default, left out" : "");
}

void check_geometry(Reader& reader, Config& config) {
  if (config.pocket_above_clearance_offset_z <= config.pocket_above_chuck_offset_z) {
    reader.error("pocket_above_clearance_offset_z",
                 "must be above pocket_above_chuck_offset_z (" +
                     format_number(config.pocket_above_chuck_offset_z) + "), got " +
                     format_number(config.pocket_above_clearance_offset_z));
  }
  const double side = std::hypot(config.pocket_side_offset.x, config.pocket_side_offset.y);
  check_side_offset(reader, config, config.pocket_side_offset, "pocket_side_offset", false);
  for (const auto& [number, pocket] : config.pockets) {
    if (pocket.approach != Approach::side) continue;
    const PlanarOffset& own = pocket.side_offset;
    if (own.x != config.pocket_side_offset.x || own.y != config.pocket_side_offset.y) {
      check_side_offset(reader, config, own, "pockets." + std::to_string(number) + ".side_offset",
                        true);
    }
  }
  for (auto a = config.pockets.begin(); a != config.pockets.end(); ++a) {
    for (auto b = std::next(a); b != config.pockets.end(); ++b) {
      const double distance =
          std::hypot(a->second.at.x - b->second.at.x, a->second.at.y - b->second.at.y);
      if (distance < side) {
        reader.error("pockets." + std::to_string(b->first),
                     "only " + format_number(distance) + " from pocket " +
                         std::to_string(a->first) + ", closer than the side offset (" +
                         format_number(side) + ")");
      }
    }
  }
  if (config.probe_limit.z > config.loading.z) {
    reader.error("probe_limit.z", "must not be above loading.z (" +
                                      format_number(config.loading.z) + "), got " +
                                      format_number(config.probe_limit.z));
  }
  // Load and measure-all probe there whatever probe_after_change says: a
  // sensor in the rack would take the tool down between the holders.
  const Point sensor = config.probe_limit;
  for (const RackPart& part : rack_volume(config)) {
    const Box& box = part.box;
    if (sensor.x > box.low.x && sensor.x < box.high.x && sensor.y > box.low.y &&
        sensor.y < box.high.y) {
      reader.error("probe_limit", "the touch-off sensor at X" + format_number(sensor.x) + " Y" +
                                      format_number(sensor.y) + " lies in the rack's keep-out at pocket " +
                                      std::to_string(nearest_pocket(part, sensor)) +
                                      " (rack_keepout_margin " +
                                      format_number(config.keepout_margin()) +
                                      "): place it clear of the rack");
      break;
    }
  }
  if (const double floor = bounds_in(key("rack_keepout_margin"), config.units).min;
      !config.rack_keepout_margin && config.keepout_margin() < floor) {
    reader.error("rack_keepout_margin", "missing, and its default, half the side offset (" +
                                            format_number(config.keepout_margin()) +
                                            "), is below " + format_number(floor) + " " +
                                            units_name(config.units) +
                                            ": give the tool holder's half-width");
  }
  if (config.rack_keepout_margin && *config.rack_keepout_margin >= side && side > 0.0) {
    reader.error("rack_keepout_margin", "must be smaller than the side offset (" +
                                            format_number(side) + "), got " +
                                            format_number(*config.rack_keepout_margin));
  }
  if (const auto parts = rack_volume(config).size();
      config.rack_keepout_all_motion && parts > kGuardBoxes) {
    reader.error("rack_keepout_all_motion",
                 "the pockets lie in " + std::to_string(parts) +
                     " groups apart from each other, and the realtime guard holds " +
                     std::to_string(kGuardBoxes) + ": move pockets together or set it false");
  }
  if (std::string why; config.blend_tolerance > config.blend_room(&why)) {
    reader.error("blend_tolerance", "must not be more than " +
                                        format_number(config.blend_room()) + ", " + why +
                                        ": a rounded corner would cut into the rack; got " +
                                        format_number(config.blend_tolerance));
  }
  if (uses_default_tolerance(config) && config.window() <= config.check_tolerance()) {
    reader.error("probe_window", "must be larger than probe_check_tolerance (" +
                                     said(config, "probe_check_tolerance", config.check_tolerance()) +
                                     "), got " + said(config, "probe_window", config.window()));
  }
  if (config.probe_latch_feed > config.probe_seek_feed) {
    reader.error("probe_latch_feed",
                 "must not be above probe_seek_feed (" +
                     said(config, "probe_seek_feed", config.probe_seek_feed) + "), got " +
                     said(config, "probe_latch_feed", config.probe_latch_feed));
  }
}

}  // namespace

const char* units_name(Units units) { return units == Units::mm ? "mm" : "inch"; }

double machine_per_unit(Units units, double machine_per_mm) {
  return (units == Units::inch ? 25.4 : 1.0) * machine_per_mm;
}

const char* approach_name(Approach approach) { return approach == Approach::top ? "top" : "side"; }

std::optional<int> Config::first_pocket_of(int tool) const {
  if (tool == 0) return std::nullopt;
  for (const auto& [number, pocket] : pockets) {
    if (pocket.first_tool == tool) return number;
  }
  return std::nullopt;
}

std::string format_length(const Config& config, double length) {
  return formatted(config.units == Units::inch ? "%.5f inch" : "%.4f mm", length);
}

double Config::blend_room(std::string* why) const {
  double room = std::numeric_limits<double>::infinity();
  for (const auto& [number, pocket] : pockets) {
    const double above = safe.z - (pocket.at.z + pocket_above_clearance_offset_z);
    if (above < room) {
      room = above;
      if (why) *why = "how far safe.z lies above pocket " + std::to_string(number) + "'s above-clearance";
    }
  }
  return std::max(room, 0.0);
}

double Config::blend_over_columns() const {
  return std::min(blend_tolerance, blend_room() / 3.5);
}

double Config::check_tolerance() const {
  return probe_check_tolerance.value_or(unit_default::probe_check_tolerance.in(units));
}

double Config::window() const {
  return probe_window.value_or(unit_default::probe_window.in(units));
}

double Config::keepout_margin() const {
  if (rack_keepout_margin) return *rack_keepout_margin;
  return std::hypot(pocket_side_offset.x, pocket_side_offset.y) / 2.0;
}

double Config::keepout_above() const {
  return rack_keepout_above.value_or(unit_default::rack_keepout_above.in(units));
}

namespace {

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

  // Relations between keys only mean something once every key read cleanly.
  if (reader.count() == 0) check_geometry(reader, config);
  if (reader.count() == 0) check_tools(reader, config);
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
