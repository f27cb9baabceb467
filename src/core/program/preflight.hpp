#pragma once

#include <optional>
#include <string>
#include <vector>

#include "../config/config.hpp"
#include "../rack/point.hpp"
#include "tool_use.hpp"
#include "../plan/simulator.hpp"
#include "../rack/tool_state.hpp"
#include "tool_table.hpp"

namespace fatc {

/// How long the steps of a plan take: each move its distance at its feed
/// (rapids, and feeds above it, at `rapid_per_minute`), plus the dwells,
/// from `start`; acceleration is not counted. `operator_waits` counts the
/// prompts, whose time (the operator's) is not counted either.
double estimate_seconds(const Simulator& plan, const Point& start, double rapid_per_minute,
                        int& operator_waits);

/// What the machine's motion can do, in the config's units: per second
/// ([AXIS_x]MAX_VELOCITY, [TRAJ]MAX_LINEAR_VELOCITY) and per second squared
/// (MAX_ACCELERATION, [TRAJ]MAX_LINEAR_ACCELERATION).
struct MotionLimits {
  Point velocity;
  Point acceleration;
  double linear_velocity = 0.0;
  double linear_acceleration = 0.0;
};

/// The least time a straight move takes that starts and ends standing
/// still: a trapezoidal profile at the slowest of the limits of the axes it
/// moves (along its direction) and the linear ones, and at most
/// `feed_per_minute` (0: a rapid, no feed).
double move_seconds(const Point& from, const Point& to, double feed_per_minute,
                    const MotionLimits& limits);

/// The plan's steps at the machine's limits: every move an exact stop as
/// move_seconds has it, plus the dwells; no handshake, no latency, no
/// blending. Of the direct path's plan, the bound of a change.
double limits_seconds(const Simulator& plan, const Point& start, const MotionLimits& limits);

/// As limits_seconds, but each run of rapids with nothing between them (no
/// chuck, dwell or command) as fast as its axes allow if they never stopped:
/// the slowest of each axis covering its travel and the path its length, from
/// standing to standing. Less than any blending of the corners could reach,
/// so what blending is worth at most.
double blended_seconds(const Simulator& plan, const Point& start, const MotionLimits& limits);

struct PreflightInput {
  const Config* config = nullptr;
  ToolState tools;                   ///< at the program's start
  std::string state_name;            ///< the state file, as messages show it
  const ToolTable* table = nullptr;  ///< LinuxCNC's tool table, when given
  std::string table_name;
  double rapid_per_minute = 3000.0;  ///< in the config's units per minute
};

/// One M6 or M61 of the program, as the changer would meet it.
struct PreflightRow {
  program::ToolUse use;
  std::string code;               ///< "M6 T3", "M6", "M61 Q3"
  std::string where;              ///< "pocket 3", "manual: handed over at loading", ...
  std::string length;             ///< "30.0000 mm (state file)", "never measured", ...
  std::optional<double> seconds;  ///< nullopt: not estimated
};

struct Preflight {
  std::vector<PreflightRow> rows;
  std::vector<program::Finding> problems;
  std::vector<int> tools;  ///< every tool the program puts in the spindle, in order of first use
  /// The tool of every M6 in the order LinuxCNC runs them, repeats and T0
  /// included; nullopt where it is not known.
  std::vector<std::optional<int>> order;
  int changes = 0;         ///< M6 that change the tool (not to the tool already in the spindle)
  int manual = 0;          ///< of them, to a manual tool
  int not_estimated = 0;   ///< of them, with a tool or spindle not known
  int operator_waits = 0;  ///< waits for the operator in the estimated changes
  double seconds = 0.0;    ///< estimated time of all estimated changes
};

/// Follows the program's tool uses, as LinuxCNC's interpreter ran them,
/// through the rack (ToolState), the lengths (state file, or the tool table
/// when given) and the planned steps of each change (plan_change, the --plan
/// path).
Preflight preflight(const std::vector<program::ToolUse>& uses, const PreflightInput& input);

}  // namespace fatc
