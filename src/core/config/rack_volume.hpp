#pragma once

// The rack's volume as the config defines it: what config validation holds
// the rack to (the guard's boxes, the sensor outside it) and the keep-out
// (src/core/rack/keepout.hpp) keeps every motion out of.

#include <cstddef>
#include <optional>
#include <vector>

#include "../motion/point.hpp"
#include "settings.hpp"

namespace fatc {

/// An axis-aligned box in machine coordinates.
struct Box {
  Point low, high;
};

/// Where along the segment a→b (0 at a, 1 at b) it first enters the open
/// interior of `box` (touching a face is not entering); none when it does not.
std::optional<double> entry_along(const Point& a, const Point& b, const Box& box);

/// A pocket's keep-out column: XY half-width Config::keepout_margin() around
/// it, no floor (tools hang below their holders down to the table), its top
/// `top_offset` above the pocket's Z.
Box pocket_column(const Config& config, const Point& pocket, double top_offset);

/// The most boxes the realtime guard (src/rt/fatc_rack_guard.comp) holds.
constexpr std::size_t kGuardBoxes = 4;

/// A part of the rack's volume: pockets whose keep-out columns lie less than
/// twice the side offset apart, as one box (a row of pockets is one box; a
/// spindle has no business between two holders of a rack). The box has no
/// floor (tools hang below their holders down to the table) and reaches
/// Config::keepout_above() over the highest holder top of its pockets (a
/// pocket's Z plus pocket_above_chuck_offset_z: the nose clear of the pull
/// stud). Its XY: each column's, half-width Config::keepout_margin().
struct RackPart {
  struct PocketAt {
    int number = 0;
    Point at;
  };
  std::vector<PocketAt> pockets;  ///< by number
  Box box;
};

/// The rack's volume, kept out of every motion but the changer's own: what
/// the realtime guard holds and the lint checks programs against. Nothing the
/// changer does not know of (vises, fixtures) is in it.
std::vector<RackPart> rack_volume(const Config& config);

/// The pocket of `part` nearest to `at` in XY.
int nearest_pocket(const RackPart& part, const Point& at);

}  // namespace fatc
