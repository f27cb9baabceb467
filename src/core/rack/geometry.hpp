#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "../config/config.hpp"
#include "../motion/step.hpp"
#include "keepout.hpp"

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

/// How far the tip of a tool may hang below the nose on the move from `from`
/// to `to` before it enters a holder: the least, over the pockets whose
/// column the move crosses, of the nose's lowest height in the column less
/// the holder's top (pocket Z plus pocket_above_chuck_offset_z). Infinity
/// where the move crosses no column. The pocket a move serves is left out
/// for its approach and for straight up or down in it (the tool goes in and
/// out of its own holder that way); a move straight up carries nothing into
/// anything. `pocket`: where the room is least.
struct TipRoom {
  double length = 0.0;
  int pocket = 0;
};
TipRoom tip_room(const Config& config, const Point& from, const Step& move);

/// What to change where a tool's tip would enter a holder, for messages.
const char* tip_remedy();

/// Checks every move of a step list against the rack keep-out and the soft
/// limits. The keep-out is a column per pocket (XY half-width
/// Config::keepout_margin(), up to its above_clearance height): only the
/// moves into or out of the pocket being served (Step::may_enter_column) may
/// enter that pocket's column, and no move may enter any other. A tool the
/// spindle holds (Step::held) hangs `held_length` below the nose: its tip may
/// not enter a holder (tip_room).
/// The problems of one move from `from` (of which the axes `known` are
/// known), against the same rules; empty when it is safe.
std::vector<std::string> check_move(const Config& config, const Point& from, unsigned known,
                                    const Step& step, const std::optional<SoftLimits>& limits,
                                    double held_length = 0.0);

/// Where a step list starts, and the lengths of the tools its moves carry.
struct StepsFrom {
  Point at;
  unsigned known = 0;  ///< the axes of `at` that are known; none: the start is not
  ToolLengths lengths;
  std::map<int, double> measured;  ///< the changer's own lengths (ToolState::lengths)
};

/// The same over a step list, each move with the length of the tool it holds.
std::vector<Violation> check_steps(const Config& config, const std::vector<Step>& steps,
                                   const std::optional<SoftLimits>& limits,
                                   const StepsFrom& from = {});

/// The least tip room (tip_room) of the moves of `steps` that carry a tool,
/// starting at `at`, and the step it is least at: the longest tool those
/// moves can carry.
struct StepRoom {
  TipRoom room;
  std::size_t step = 0;
};
StepRoom least_tip_room(const Config& config, const std::vector<Step>& steps, const Point& at);

}  // namespace fatc
