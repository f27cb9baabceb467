#pragma once

// What the keep-out check's two files (keepout_check.cpp, the moves;
// keepout_changes.cpp, the tool and its changes) share: the axes of a point
// by number and as bits of a set, and a machine position in words.

#include <string>

#include "../config/config.hpp"
#include "../formatted.hpp"
#include "../motion/point.hpp"

namespace fatc::keepout_axes {

constexpr unsigned kX = 1, kY = 2, kZ = 4, kAll = 7;

inline double& axis(Point& p, int a) { return a == 0 ? p.x : a == 1 ? p.y : p.z; }
inline double axis(const Point& p, int a) { return a == 0 ? p.x : a == 1 ? p.y : p.z; }

/// "X150.000 Y20.000 Z-25.000", machine coordinates in the config's units.
inline std::string machine_words(const Config& config, const Point& at) {
  return formatted(config.units == Units::inch ? "X%.4f Y%.4f Z%.4f" : "X%.3f Y%.3f Z%.3f", at.x,
                   at.y, at.z);
}

}  // namespace fatc::keepout_axes
