// The rack the Simulator models (simulator.hpp): where the tools are, and
// what its sensors read.

#include <cmath>

#include "../rack/geometry.hpp"
#include "simulator.hpp"

namespace fatc {

int Rack::pocket_at(const Config& config) const {
  if (known_axes != axis_xyz) return 0;
  for (const auto& entry : config.pockets) {
    const Point p = pocket_waypoints(config, entry.first).pocket;
    if (std::abs(p.x - at.x) < 1e-6 && std::abs(p.y - at.y) < 1e-6 && std::abs(p.z - at.z) < 1e-6) {
      return entry.first;
    }
  }
  return 0;
}

void Rack::screw(const Config& config) {
  const int pocket = pocket_at(config);
  if (pocket == 0 || spindle_rpm == 0.0 || stalled || screwed) return;
  screwed = true;
  int& in_pocket = pockets[pocket];
  if (spindle_rpm < 0.0 && spindle != 0 && in_pocket == 0) {
    if (screwings_failing > 0) {
      --screwings_failing;
      return;
    }
    in_pocket = spindle;
    spindle = 0;
  } else if (spindle_rpm > 0.0 && spindle == 0 && in_pocket != 0) {
    if (screwings_failing > 0) {
      --screwings_failing;
      return;
    }
    spindle = in_pocket;
    in_pocket = 0;
    seated = !nut_hangs_low;
  }
}

bool Rack::holds(Fact fact) const {
  const auto stands_at = [this](double z) {
    return (known_axes & axis_z) != 0 && std::abs(at.z - z) < 1e-6;
  };
  switch (fact) {
    case Fact::spindle_still:
      return spindle_still;
    case Fact::tool_in_spindle:
      return spindle != 0;
    case Fact::drawbar_released:
      return drawbar_released;
    case Fact::air:
      return air;
    case Fact::cover_open:
      return cover_open;
    case Fact::spindle_at_speed:
      return spindle_rpm != 0.0 && !stalled;
    case Fact::nut_in_beam:
      return spindle != 0 && zones &&
             (stands_at(zones->zone_1_z) || (!seated && stands_at(zones->zone_2_z)));
  }
  return false;
}

}  // namespace fatc
