#include "chuck.hpp"

#include <cmath>

namespace fatc::reading {
namespace {

constexpr const char* kHere = "chuck";
constexpr const char* kCollet = "\"collet_nut\"";

/// A collet-nut key `key` the drawbar has no use for: refused rather than ignored.
void refuse_for_drawbar(Reader& reader, const Json& chuck) {
  for (const std::string& name : keys_below(kHere)) {
    if (name != "kind" && chuck.contains(name)) {
      reader.error(join_path(kHere, name), std::string("only for \"kind\": ") + kCollet +
                                               " (a drawbar has no use for it)");
    }
  }
}

/// A key "collet_nut" needs: one line where it is missing.
std::optional<double> needed(Reader& reader, const Json& chuck, const char* key) {
  if (!chuck.contains(key)) {
    reader.error(join_path(kHere, key), std::string("missing: \"kind\": ") + kCollet + " needs it");
    return std::nullopt;
  }
  return reader.declared(chuck, kHere, key);
}

void read_recognition(Reader& reader, const Json& chuck, Config& config) {
  const Json* zones = reader.object(chuck, kHere, "recognition", false);
  if (!zones) return;
  const std::string here = join_path(kHere, "recognition");
  reader.reject_unknown_keys(*zones, here);
  const auto zone_1 = reader.declared(*zones, here, "zone_1_z");
  const auto zone_2 = reader.declared(*zones, here, "zone_2_z");
  if (zone_1 && zone_2) config.chuck.recognition = Recognition{*zone_1, *zone_2};
  config.sensors.wire(Sensor::nut_seen, true);
}

/// Every pocket of a collet-nut magazine is entered from the top: a side
/// approach said anywhere is refused.
void enter_from_the_top(Reader& reader, const Json& root, Config& config) {
  const auto says_side = [](const Json& object) {
    const auto approach = object.find("approach");
    return approach != object.end() && *approach == "side";
  };
  if (const auto common = root.find("pocket_default");
      common != root.end() && common->is_object() && says_side(*common)) {
    reader.error("pocket_default.approach", std::string("\"side\" cannot serve \"chuck\": ") +
                                                kCollet + " (its nuts are screwed from the top)");
  }
  if (const auto pockets = root.find("pockets"); pockets != root.end() && pockets->is_object()) {
    for (const auto& [number, pocket] : pockets->items()) {
      if (pocket.is_object() && says_side(pocket)) {
        reader.error("pockets." + number + ".approach",
                     std::string("\"side\" cannot serve \"chuck\": ") + kCollet +
                         " (its nuts are screwed from the top)");
      }
    }
  }
  for (auto& [number, pocket] : config.pockets) pocket.approach = Approach::top;
}

/// The highest spin-off of the pockets, and whose: no zone may lie below it.
struct SpinOff {
  int pocket = 0;
  double z = 0.0;
};
SpinOff highest_spin_off(const Config& config) {
  SpinOff highest{0, -1e300};
  for (const auto& [number, pocket] : config.pockets) {
    const double z = pocket.at.z + config.chuck.spin_off_offset_z;
    if (z > highest.z) highest = {number, z};
  }
  return highest;
}

}  // namespace

void read_chuck(Reader& reader, const Json& root, Config& config) {
  const Json* chuck = reader.object(root, "", kHere, false);
  if (!chuck) return;
  reader.reject_unknown_keys(*chuck, kHere);
  if (const auto kind = chuck->find("kind"); kind != chuck->end()) {
    if (*kind == "collet_nut") {
      config.chuck.kind = ChuckKind::collet_nut;
    } else if (*kind != "drawbar") {
      reader.error(join_path(kHere, "kind"),
                   "expected \"drawbar\" or \"collet_nut\", got " + describe(*kind));
      return;
    }
  }
  if (!config.screws_nuts()) {
    refuse_for_drawbar(reader, *chuck);
    return;
  }
  ChuckConfig& nut = config.chuck;
  if (const auto z = needed(reader, *chuck, "spin_off_offset_z")) nut.spin_off_offset_z = *z;
  nut.rise_after_unload_offset_z = nut.spin_off_offset_z;
  reader.read(*chuck, kHere, "rise_after_unload_offset_z", nut.rise_after_unload_offset_z);
  if (const auto feed = needed(reader, *chuck, "engage_feed")) nut.engage_feed = *feed;
  if (const auto rpm = needed(reader, *chuck, "unload_rpm")) nut.unload_rpm = *rpm;
  if (const auto rpm = needed(reader, *chuck, "load_rpm")) nut.load_rpm = *rpm;
  if (const auto plunges = reader.declared(*chuck, kHere, "tighten_plunges")) {
    if (std::floor(*plunges) != *plunges) {
      reader.error(join_path(kHere, "tighten_plunges"),
                   "must be a whole number, got " + format_number(*plunges));
    } else {
      nut.tighten_plunges = static_cast<int>(*plunges);
    }
  }
  reader.read(*chuck, kHere, "spindle_ramp_seconds", nut.spindle_ramp_seconds);
  read_recognition(reader, *chuck, config);
  enter_from_the_top(reader, root, config);
}

void check_chuck(Reader& reader, const Config& config) {
  if (!config.screws_nuts()) return;
  const ChuckConfig& nut = config.chuck;
  const auto at = [](const char* key) { return join_path(kHere, key); };
  if (nut.rise_after_unload_offset_z < nut.spin_off_offset_z) {
    reader.error(at("rise_after_unload_offset_z"),
                 "must not be below chuck.spin_off_offset_z (" +
                     format_number(nut.spin_off_offset_z) + "), got " +
                     format_number(nut.rise_after_unload_offset_z));
  }
  for (const auto& [number, pocket] : config.pockets) {
    const double top = pocket.at.z + nut.rise_after_unload_offset_z;
    if (top >= config.safe.z) {
      reader.error(at("rise_after_unload_offset_z"),
                   "pocket " + std::to_string(number) + "'s z plus it (" + format_number(top) +
                       ") must be below safe Z (" + format_number(config.safe.z) + ")");
      break;
    }
  }
  if (nut.recognition) {
    const Recognition& zones = *nut.recognition;
    if (zones.zone_2_z <= zones.zone_1_z) {
      reader.error(at("recognition.zone_2_z"),
                   "must be above zone_1_z (" + format_number(zones.zone_1_z) +
                       "): a nut not screwed home hangs lower, so zone 2 is the higher one, got " +
                       format_number(zones.zone_2_z));
    } else if (const auto low = highest_spin_off(config); zones.zone_1_z < low.z) {
      reader.error(at("recognition.zone_1_z"),
                   "must not be below pocket " + std::to_string(low.pocket) + "'s spin-off (" +
                       format_number(low.z) +
                       "): there the nose reaches into the nut left in the pocket, got " +
                       format_number(zones.zone_1_z));
    } else if (zones.zone_2_z >= config.safe.z) {
      reader.error(at("recognition.zone_2_z"), "must be below safe Z (" +
                                                   format_number(config.safe.z) + "), got " +
                                                   format_number(zones.zone_2_z));
    }
  }
  for (const Sensor drawbar : {Sensor::drawbar_open, Sensor::drawbar_closed, Sensor::air_pressure}) {
    if (config.sensors.wired(drawbar)) {
      reader.error(declared(drawbar).words.key,
                   std::string("a collet-nut spindle (\"chuck\": ") + kCollet + ") has no drawbar");
    }
  }
  if (config.air_blast) {
    reader.error("air_blast", std::string("a collet-nut spindle (\"chuck\": ") + kCollet +
                                  ") has no open taper to blow");
  }
  for (const auto& [number, pocket] : config.pockets) {
    if (pocket.first_tool != 0 && config.is_probe(pocket.first_tool)) {
      reader.error("pockets." + std::to_string(number) + ".tool",
                   "tool " + std::to_string(pocket.first_tool) +
                       " is a touch probe: a collet-nut magazine cannot hold it (the spindle "
                       "would turn it to screw it); leave it out of the rack, it is handed in at "
                       "loading");
    }
  }
}

}  // namespace fatc::reading
