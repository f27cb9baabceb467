#pragma once

#include <string>
#include <vector>

#include "point.hpp"

namespace fatc {

/// What the NGC step executor is asked to do next. The numbers are the
/// values of the `step-kind` pin that nc_files/fixed_atc_probe_execute.ngc
/// reads (tests/unit/protocol/codes_test.cpp holds the two together).
enum class StepKind {
  resync = 0,           ///< nothing to do, ask again: a dead executor's request was left high
  rapid = 1,            ///< G53 G0 to `target` on `axes`
  feed = 2,             ///< G53 G1 at `feed` to `target` on `axes`
  probe = 3,            ///< G38.3 toward `target.z` at `feed`; the result comes back as ProbeResult
  set_tool_length = 4,  ///< G10 L1 P`tool` Z`value`
  set_spindle_tool = 5,  ///< M61 Q`tool`: tell LinuxCNC what the spindle holds
  wait_operator = 6,     ///< end this executor run; the operator acts, Continue runs the next
  done = 7,              ///< the sequence is over; `tool` is in the spindle
  fail = 8,              ///< the sequence cannot go on; `label` says why
  /// The spindle at `value` rpm: > 0 forward (M3), < 0 reverse (M4), 0 stopped
  /// (M5); only a collet-nut changer over the pocket it serves turns it.
  spindle = 9,
};

/// Axis bits of Step::axes.
enum Axis : unsigned { axis_x = 1u, axis_y = 2u, axis_z = 4u, axis_xy = 3u, axis_xyz = 7u };

struct Step {
  StepKind kind = StepKind::done;
  unsigned axes = 0;      ///< which coordinates of `target` the move commands
  Point target;           ///< machine coordinates
  double feed = 0.0;      ///< units per minute, for feed and probe
  int tool = 0;           ///< for set_tool_length, set_spindle_tool and done
  double value = 0.0;     ///< tool length, for set_tool_length; signed rpm, for spindle
  int pocket = 0;         ///< the pocket this move serves (its number), 0 if none
  /// Part of the way into or out of `pocket`: the move may enter its keep-out column.
  bool may_enter_column = false;
  /// The tool the spindle holds during this move, 0 none: the keep-out
  /// counts its length below the nose (set as the step is published).
  int held = 0;
  std::string label;      ///< the machinist's name for the target ("side of pocket 3")
  /// A run of rapids published as one step (blend_tolerance): the rapids
  /// before this one, up to safe Z and across at it. Each of their corners,
  /// all at safe Z, is rounded within `blend` (G64 P); the run ends standing.
  std::vector<Step> before;
  double blend = 0.0;  ///< how far a corner of the run may be cut; 0: none is
};

/// `p`'s coordinate on one axis (axis_x, axis_y or axis_z).
inline double& coordinate(Point& p, unsigned axis) {
  return axis == axis_x ? p.x : axis == axis_y ? p.y : p.z;
}
inline double coordinate(const Point& p, unsigned axis) {
  return axis == axis_x ? p.x : axis == axis_y ? p.y : p.z;
}
/// 'X', 'Y' or 'Z'.
inline char axis_letter(unsigned axis) { return axis == axis_x ? 'X' : axis == axis_y ? 'Y' : 'Z'; }

/// A move (rapid, feed or probe) to `target` on `axes`, named `label`; part
/// of the way into or out of `pocket` when `may_enter_column`.
Step move_step(StepKind kind, unsigned axes, const Point& target, std::string label,
               int pocket = 0, bool may_enter_column = false, double feed = 0.0);

/// The spindle at `rpm` (signed: forward > 0, reverse < 0, 0 stopped), named `label`.
Step spindle_step(double rpm, std::string label, int pocket = 0);
/// The step that makes a waiting executor abort its program, saying `why`.
Step failure_step(std::string why);
/// Nothing to do: the executor asks again.
Step resync_step();

bool is_motion(StepKind kind);
/// Where `move` takes the spindle from `from`: its target on the axes it commands.
Point moved_to(const Point& from, const Step& move);
/// The moves `step` makes, in order: those of its run, then itself. In those
/// of the run, `blend` says the corner after each is rounded.
std::vector<Step> moves_of(const Step& step);
/// The codes of the `step-via` pin: what the executor does before the step's
/// own move (nc_files/fixed_atc_probe_execute.ngc reads them).
enum class Via { none = 0, up = 1, across = 2, up_and_across = 3 };
Via via_of(const Step& step);
const char* step_kind_name(StepKind kind);

/// One line, e.g. `rapid  Z=50.000            safe Z`.
std::string describe(const Step& step);

}  // namespace fatc
