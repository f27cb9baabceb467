#include "settings.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "../formatted.hpp"

namespace fatc {

const char* units_name(Units units) { return units == Units::mm ? "mm" : "inch"; }

double machine_per_unit(Units units, double machine_per_mm) {
  return (units == Units::inch ? 25.4 : 1.0) * machine_per_mm;
}

const char* approach_name(Approach approach) { return approach == Approach::top ? "top" : "side"; }

const char* feature_name(TouchFeature feature) {
  switch (feature) {
    case TouchFeature::bore:
      return "bore";
    case TouchFeature::fork:
      return "fork";
    case TouchFeature::faces:
      return "faces";
  }
  return "?";
}

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

}  // namespace fatc
