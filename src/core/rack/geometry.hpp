#pragma once

#include <optional>
#include <string>
#include <vector>

#include "../config/config.hpp"
#include "../protocol/step.hpp"

namespace fatc {

/// The stations of one pocket, in the order the spindle passes them.
struct PocketWaypoints {
  Point pocket;  ///< where the tool holder sits in the rack
  Point
      side;  ///< beside the pocket, at pocket height: where the slow move in starts (side approach)
  Point above_chuck;      ///< where the chuck opens or closes over the holder
  Point above_clearance;  ///< high enough to move in XY over the rack
  /// On the way from the side to the pocket, where the pocket's keep-out
  /// column begins: outside it nothing of the pocket is engaged.
  Point column_edge;
};

/// The waypoints of pocket `number` (a key of Config::pockets).
PocketWaypoints pocket_waypoints(const Config& config, int number);

struct AxisLimits {
  double min = 0.0;
  double max = 0.0;
};

/// The machine's soft limits ([AXIS_X] MIN_LIMIT/MAX_LIMIT ...), in the config's units.
struct SoftLimits {
  AxisLimits x, y, z;
};

struct Violation {
  std::size_t step = 0;  ///< index into the checked step list
  std::string what;
};

/// Checks every move of a step list against the rack keep-out and the soft
/// limits. The keep-out is a column per pocket (XY half-width
/// Config::keepout_margin(), up to its above_clearance height): only the
/// approach moves of the pocket being served may enter that pocket's column,
/// and no move may enter any other.
/// The problems of one move from `from` (of which the axes `known` are
/// known), against the same rules; empty when it is safe.
std::vector<std::string> check_move(const Config& config, const Point& from, unsigned known,
                                    const Step& step, const std::optional<SoftLimits>& limits);

std::vector<Violation> check_steps(const Config& config, const std::vector<Step>& steps,
                                   const std::optional<SoftLimits>& limits);

}  // namespace fatc
