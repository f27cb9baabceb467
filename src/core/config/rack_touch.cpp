#include "rack_touch.hpp"

#include <cmath>

namespace fatc::reading {
namespace {

constexpr const char* kHere = "rack_touch";

/// An object of x and y within `rack_touch` ("top", "x_face").
std::optional<PlanarOffset> planar(Reader& reader, const Json& touch, const char* key,
                                   bool required) {
  const Json* object = reader.object(touch, kHere, key, required);
  if (!object) return std::nullopt;
  const std::string here = join_path(kHere, key);
  reader.reject_unknown_keys(*object, here);
  const auto x = reader.declared(*object, here, "x");
  const auto y = reader.declared(*object, here, "y");
  if (!x || !y) return std::nullopt;
  return PlanarOffset{*x, *y};
}

std::optional<TouchFeature> feature(Reader& reader, const Json& touch) {
  const std::string here = join_path(kHere, "feature");
  const auto given = touch.find("feature");
  if (given == touch.end()) {
    reader.error(here, "missing");
    return std::nullopt;
  }
  for (const TouchFeature kind : {TouchFeature::bore, TouchFeature::fork, TouchFeature::faces}) {
    if (*given == feature_name(kind)) return kind;
  }
  const std::string pin = given->is_string() && *given == "pin"
                              ? " (pins are not supported: docs/sequences.md, teach by touch)"
                              : "";
  reader.error(here, "expected \"bore\", \"fork\" or \"faces\", got " + describe(*given) + pin);
  return std::nullopt;
}

/// `datum`: the pocket whose feature it is and, once taught, where it was found.
void read_datum(Reader& reader, const Json& touch, RackTouch& rack) {
  const Json* datum = reader.object(touch, kHere, "datum", false);
  if (!datum) return;
  const std::string here = join_path(kHere, "datum");
  reader.reject_unknown_keys(*datum, here);
  const auto pocket = datum->find("pocket");
  if (pocket == datum->end()) {
    reader.error(join_path(here, "pocket"), "missing");
  } else if (!is_tool_number(*pocket)) {
    reader.error(join_path(here, "pocket"),
                 "expected a pocket number (1 to 999999999), got " + describe(*pocket));
  } else {
    rack.datum_pocket = pocket->get<int>();
  }
  const auto x = reader.declared(*datum, here, "x");
  const auto y = reader.declared(*datum, here, "y");
  const auto z = reader.declared(*datum, here, "z");
  const int given = (datum->contains("x") ? 1 : 0) + (datum->contains("y") ? 1 : 0) +
                    (datum->contains("z") ? 1 : 0);
  if (given != 0 && given != 3) {
    reader.error(here, "needs x, y and z together (teach-datum writes them), or none");
  } else if (x && y && z) {
    rack.datum = Point{*x, *y, *z};
  }
}

}  // namespace

void read_rack_touch(Reader& reader, const Json& root, Config& config) {
  const Json* touch = reader.object(root, "", kHere, false);
  if (!touch) return;
  reader.reject_unknown_keys(*touch, kHere);
  RackTouch rack;
  if (const auto kind = feature(reader, *touch)) rack.feature = *kind;
  rack.bore_tolerance = unit_default::bore_tolerance.in(config.units);
  rack.search = unit_default::touch_search.in(config.units);
  rack.clear = unit_default::touch_clear.in(config.units);
  rack.drift_tolerance = unit_default::touch_drift_tolerance.in(config.units);
  for (const char* key : {"bore_tolerance", "search", "clear", "drift_tolerance"}) {
    if (touch->find(key) == touch->end()) config.defaulted.push_back(join_path(kHere, key));
  }
  reader.read(*touch, kHere, "stylus_radius", rack.stylus_radius);
  rack.bore_diameter = reader.declared(*touch, kHere, "bore_diameter");
  reader.read(*touch, kHere, "bore_tolerance", rack.bore_tolerance);
  if (const auto top = planar(reader, *touch, "top", true)) rack.top = *top;
  reader.read(*touch, kHere, "pocket_above_top", rack.pocket_above_top);
  reader.read(*touch, kHere, "depth", rack.depth);
  const bool faces = rack.feature == TouchFeature::faces;
  if (const auto face = planar(reader, *touch, "x_face", faces)) rack.x_face = *face;
  if (const auto face = planar(reader, *touch, "y_face", faces)) rack.y_face = *face;
  reader.read(*touch, kHere, "search", rack.search);
  reader.read(*touch, kHere, "clear", rack.clear);
  reader.read(*touch, kHere, "drift_tolerance", rack.drift_tolerance);
  read_datum(reader, *touch, rack);
  if (const auto every = reader.declared(*touch, kHere, "check_every_changes")) {
    if (std::floor(*every) != *every) {
      reader.error(join_path(kHere, "check_every_changes"),
                   "must be a whole number, got " + format_number(*every));
    } else {
      rack.check_every_changes = static_cast<int>(*every);
    }
  }
  if (const auto start = touch->find("check_at_start"); start != touch->end()) {
    if (start->is_boolean()) {
      rack.check_at_start = start->get<bool>();
    } else {
      reader.error(join_path(kHere, "check_at_start"),
                   "expected true or false, got " + describe(*start));
    }
  }
  config.rack_touch = rack;
}

void check_rack_touch(Reader& reader, const Config& config) {
  if (!config.rack_touch) return;
  const RackTouch& rack = *config.rack_touch;
  const auto at = [](const char* key) { return join_path(kHere, key); };
  if (rack.stylus_radius >= rack.depth) {
    reader.error(at("stylus_radius"), "must be below rack_touch.depth (" +
                                          format_number(rack.depth) + "), got " +
                                          format_number(rack.stylus_radius));
  }
  if (rack.feature == TouchFeature::faces) {
    if (rack.x_face.x == 0.0) {
      reader.error(at("x_face.x"), "must not be 0: its sign says on which side of the pocket "
                                   "the face lies");
    }
    if (rack.y_face.y == 0.0) {
      reader.error(at("y_face.y"), "must not be 0: its sign says on which side of the pocket "
                                   "the face lies");
    }
  } else if (!rack.bore_diameter) {
    reader.error(at("bore_diameter"),
                 std::string("missing: rack_touch.feature \"") + feature_name(rack.feature) +
                     "\" needs it");
  } else if (*rack.bore_diameter <= 2.0 * rack.stylus_radius) {
    reader.error(at("bore_diameter"), "must be above twice rack_touch.stylus_radius (" +
                                          format_number(2.0 * rack.stylus_radius) + "), got " +
                                          format_number(*rack.bore_diameter));
  }
  if (rack.feature == TouchFeature::fork) {
    for (const auto& [number, pocket] : config.pockets) {
      if (std::fabs(pocket.side_offset.x) == std::fabs(pocket.side_offset.y)) {
        reader.error("pockets." + std::to_string(number) + ".side_offset",
                     "a fork (rack_touch.feature) needs a side offset longer in X or in Y: "
                     "the jaws are touched across the other axis");
        break;
      }
    }
  }
  if (rack.datum_pocket != 0 && !config.has_pocket(rack.datum_pocket)) {
    reader.error(at("datum.pocket"),
                 "pocket " + std::to_string(rack.datum_pocket) + " is not in pockets");
  }
  if (rack.datum_pocket == 0 && (rack.check_every_changes > 0 || rack.check_at_start)) {
    reader.error(at(rack.check_at_start ? "check_at_start" : "check_every_changes"),
                 "needs rack_touch.datum: the drift check touches it");
  }
}

}  // namespace fatc::reading
