#include "preflight.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <tuple>
#include <utility>

namespace fatc {

namespace {

/// Walks the plan's moves from `start`: `move(from, to, step)` for each (a
/// probe ends where the plan's sensor touches); returns the dwells' seconds.
/// `between()` at each record that stops motion between two moves (a dwell,
/// the chuck, the cover, the blast, a step that is no move).
template <class Move, class Between = void (*)()>
double walk_moves(
    const Simulator& plan, const Point& start, Move move, Between between = [] {}) {
  Point at = start;
  double dwells = 0.0;
  for (const Record& record : plan.records) {
    if (record.kind == Record::Kind::dwell) dwells += record.seconds;
    const bool a_move = record.kind == Record::Kind::step && is_motion(record.step.kind);
    const bool no_stop = record.kind == Record::Kind::message || record.kind == Record::Kind::save;
    if (!a_move && !no_stop) between();
    if (!a_move) continue;
    const Step& step = record.step;
    Point to = at;
    if (step.axes & axis_x) to.x = step.target.x;
    if (step.axes & axis_y) to.y = step.target.y;
    if (step.axes & axis_z) to.z = step.target.z;
    if (step.kind == StepKind::probe && plan.sensor_z && *plan.sensor_z >= step.target.z) {
      to.z = std::min(*plan.sensor_z, at.z);
    }
    move(at, to, step);
    at = to;
  }
  return dwells;
}

}  // namespace

double estimate_seconds(const Simulator& plan, const Point& start, double rapid_per_minute,
                        int& operator_waits) {
  for (const Record& record : plan.records) {
    // Every wait for the operator is a prompt (in M6 for a manual tool, the only sign).
    if (record.kind == Record::Kind::message && record.message_kind == MessageKind::prompt) {
      ++operator_waits;
    }
  }
  double minutes = 0.0;
  const double dwells =
      walk_moves(plan, start, [&](const Point& from, const Point& to, const Step& step) {
        const double speed =
            step.kind == StepKind::rapid ? rapid_per_minute : std::min(step.feed, rapid_per_minute);
        if (speed > 0.0) minutes += std::hypot(to.x - from.x, to.y - from.y, to.z - from.z) / speed;
      });
  return dwells + minutes * 60.0;
}

namespace {

/// The speed and acceleration a straight move of `delta` can have: the
/// slowest of the limits of the axes it moves, along its direction, and the
/// linear ones.
std::pair<double, double> move_limits(const Point& delta, const MotionLimits& limits) {
  const double d[] = {delta.x, delta.y, delta.z};
  const double distance = std::hypot(d[0], d[1], d[2]);
  const double axis_velocity[] = {limits.velocity.x, limits.velocity.y, limits.velocity.z};
  const double axis_acceleration[] = {limits.acceleration.x, limits.acceleration.y,
                                      limits.acceleration.z};
  double velocity = limits.linear_velocity;
  double acceleration = limits.linear_acceleration;
  for (int axis = 0; axis < 3 && distance > 0.0; ++axis) {
    const double share = std::abs(d[axis]) / distance;
    if (share == 0.0) continue;
    velocity = std::min(velocity, axis_velocity[axis] / share);
    acceleration = std::min(acceleration, axis_acceleration[axis] / share);
  }
  return {velocity, acceleration};
}

/// Standing still to standing still over `distance`: accelerate, cruise,
/// decelerate; a triangle when it never reaches `velocity`.
double trapezoid_seconds(double distance, double velocity, double acceleration) {
  if (distance == 0.0 || !(velocity > 0.0) || !(acceleration > 0.0)) return 0.0;
  if (distance >= velocity * velocity / acceleration) {
    return distance / velocity + velocity / acceleration;
  }
  return 2.0 * std::sqrt(distance / acceleration);
}

}  // namespace

double move_seconds(const Point& from, const Point& to, double feed_per_minute,
                    const MotionLimits& limits) {
  const Point delta{to.x - from.x, to.y - from.y, to.z - from.z};
  auto [velocity, acceleration] = move_limits(delta, limits);
  if (feed_per_minute > 0.0) velocity = std::min(velocity, feed_per_minute / 60.0);
  return trapezoid_seconds(std::hypot(delta.x, delta.y, delta.z), velocity, acceleration);
}

double blended_seconds(const Simulator& plan, const Point& start, const MotionLimits& limits) {
  double seconds = 0.0;
  // The run of rapids under way: each axis's travel, and its whole length.
  Point travel;
  double length = 0.0;
  // However the corners are blended, each axis covers its travel within its
  // own limits and the path its length within the linear ones.
  auto end_run = [&] {
    seconds +=
        std::max({trapezoid_seconds(travel.x, limits.velocity.x, limits.acceleration.x),
                  trapezoid_seconds(travel.y, limits.velocity.y, limits.acceleration.y),
                  trapezoid_seconds(travel.z, limits.velocity.z, limits.acceleration.z),
                  trapezoid_seconds(length, limits.linear_velocity, limits.linear_acceleration)});
    travel = Point{};
    length = 0.0;
  };
  const double dwells = walk_moves(
      plan, start,
      [&](const Point& from, const Point& to, const Step& step) {
        if (step.kind != StepKind::rapid) {
          end_run();
          seconds += move_seconds(from, to, step.feed, limits);
          return;
        }
        travel.x += std::abs(to.x - from.x);
        travel.y += std::abs(to.y - from.y);
        travel.z += std::abs(to.z - from.z);
        length += std::hypot(to.x - from.x, to.y - from.y, to.z - from.z);
      },
      end_run);
  end_run();
  return seconds + dwells;
}

double limits_seconds(const Simulator& plan, const Point& start, const MotionLimits& limits) {
  double moves = 0.0;
  const double dwells =
      walk_moves(plan, start, [&](const Point& from, const Point& to, const Step& step) {
        moves += move_seconds(from, to, step.kind == StepKind::rapid ? 0.0 : step.feed, limits);
      });
  return moves + dwells;
}

namespace {

std::string tool_word(int tool) { return "T" + std::to_string(tool); }

/// One change planned by the changer itself, as --plan prints it.
struct PlannedChange {
  double seconds = 0.0;
  int operator_waits = 0;
  std::string refused;  ///< the changer's reason when it refuses the change
};

class Checker {
 public:
  explicit Checker(const PreflightInput& input) : in_(input), config_(*input.config) {
    tools_ = input.tools;
  }

  Preflight run(const std::vector<program::ToolUse>& uses) {
    for (const auto& use : uses) {
      PreflightRow row;
      row.use = use;
      if (use.kind == program::ToolUse::Kind::change) {
        result_.order.push_back(use.tool);
        change(row);
      } else {
        set_tool(row);
      }
      result_.rows.push_back(row);
    }
    return std::move(result_);
  }

 private:
  void problem(const program::Site& where, const std::string& text) {
    result_.problems.push_back({where, text});
  }

  void change(PreflightRow& row) {
    const program::ToolUse& use = row.use;
    row.code = use.tool ? "M6 " + tool_word(*use.tool) : "M6";
    if (!use.tool) {
      row.where = "not known";
      row.length = "-";
      ++result_.changes;
      ++result_.not_estimated;
      spindle_known_ = false;
      return;
    }
    const int tool = *use.tool;
    if (tools_.uncertain && !said_uncertain_) {
      said_uncertain_ = true;
      problem(use.where, "the state file " + in_.state_name +
                             " records a sequence that was cut off: the changer refuses M6 "
                             "until the fault is cleared (panel, or --confirm)");
    }
    row.length = length(use, tool);
    if (spindle_known_ && tool == tools_.spindle) {
      row.where = tool == 0 ? "the spindle is empty already" : "in the spindle already";
      row.seconds = 0.0;
      return;
    }
    ++result_.changes;
    if (tool != 0 &&
        std::find(result_.tools.begin(), result_.tools.end(), tool) == result_.tools.end()) {
      result_.tools.push_back(tool);
    }
    const auto pocket = tools_.home_of(tool);
    if (tool == 0) {
      row.where = "empties the spindle";
    } else if (tools_.pocket_holding(tool)) {
      row.where = "pocket " + std::to_string(*pocket);
    } else if (pocket) {
      row.where = "out of the rack (pocket " + std::to_string(*pocket) + " empty)";
      problem(use.where, "M6 " + tool_word(tool) + ": the state file " + in_.state_name +
                             " has pocket " + std::to_string(*pocket) + " empty (" +
                             tool_word(tool) +
                             " is not in it): the changer refuses the change; load it first");
    } else {
      row.where = "manual: handed over at loading";
      ++result_.manual;
    }
    if (!spindle_known_) {
      ++result_.not_estimated;
    } else {
      const PlannedChange& planned = plan(tools_.spindle, tool);
      if (!planned.refused.empty()) {
        // The changer stops the program there; the lint reads on with the spindle as it was.
        row.where = "refused: " + row.where;
        problem(use.where, planned.refused);
        return;
      } else {
        row.seconds = planned.seconds;
        result_.seconds += planned.seconds;
        result_.operator_waits += planned.operator_waits;
      }
    }
    // The rack after the change: the old tool home, the new one in the spindle.
    if (spindle_known_ && tools_.spindle != 0) {
      if (const auto back = return_pocket(tools_, config_, tools_.spindle)) {
        tools_.pockets[*back] = {tools_.spindle, true};
      }
    }
    tools_.put_in_spindle(tool);
    spindle_known_ = true;
  }

  void set_tool(PreflightRow& row) {
    const program::ToolUse& use = row.use;
    row.code = use.tool ? "M61 Q" + std::to_string(*use.tool) : "M61";
    row.seconds = 0.0;
    if (!use.tool) {
      row.where = "LinuxCNC is told a tool not known; nothing moves";
      row.length = "-";
      return;
    }
    const int tool = *use.tool;
    row.length = length(use, tool);
    row.where = "LinuxCNC is told " + (tool == 0 ? std::string("nothing") : tool_word(tool)) +
                " is in the spindle; nothing moves";
    if (spindle_known_ && tool != tools_.spindle) {
      problem(use.where,
              "M61 Q" + std::to_string(tool) + ": tells LinuxCNC the spindle holds " +
                  (tool == 0 ? std::string("nothing") : tool_word(tool)) +
                  " while the changer has " +
                  (tools_.spindle == 0 ? std::string("nothing") : tool_word(tools_.spindle)) +
                  " in it: the next G43 would apply the wrong length");
    }
  }

  /// The Length column; a problem, once per tool, when the tool has no length
  /// and the change does not measure it.
  std::string length(const program::ToolUse& use, int tool) {
    if (tool == 0) return "-";
    const bool measures = config_.probe_after_change != ProbeAfterChange::off &&
                          use.kind == program::ToolUse::Kind::change;
    std::optional<std::string> stored;  // the length as the column shows it
    std::string missing;                // why there is none
    if (in_.table != nullptr) {
      // The table is in the machine's units, which may not be the config's.
      const auto entry = in_.table->tools.find(tool);
      if (entry == in_.table->tools.end()) {
        missing = "not in the tool table " + in_.table_name;
      } else if (!entry->second.z) {
        missing = "no Z in the tool table " + in_.table_name + " (line " +
                  std::to_string(entry->second.line) + ")";
      } else if (*entry->second.z == 0.0) {
        missing = "Z0 in the tool table " + in_.table_name + " (line " +
                  std::to_string(entry->second.line) + ")";
      } else {
        char z[48];
        std::snprintf(z, sizeof z, "Z%.4f (tool table)", *entry->second.z);
        stored = z;
      }
    } else {
      const auto entry = tools_.lengths.find(tool);
      if (entry == tools_.lengths.end()) {
        missing = "no length in the state file " + in_.state_name;
      } else {
        stored = format_length(config_, entry->second) + " (state file)";
      }
    }
    if (measures) {
      return std::string(config_.probe_after_change == ProbeAfterChange::check ? "checked"
                                                                               : "measured") +
             " at the change" + (stored ? ", stored " + *stored : "");
    }
    if (stored) return *stored;
    if (never_measured_.insert(tool).second) {
      problem(use.where, tool_word(tool) + " was never measured: " + missing +
                             ", and M6 measures nothing (probe_after_change is off)");
    }
    return "never measured";
  }

  /// The probe touches at the stored length, or at its limit when none is known.
  double sensor_z(int tool) const {
    const auto stored = tools_.lengths.find(tool);
    if (stored == tools_.lengths.end()) return config_.probe_limit.z;
    return std::max(config_.probe_length_compensation_offset + stored->second,
                    config_.probe_limit.z);
  }

  /// M6 T`to` from the rack as it is now (`from` in the spindle).
  const PlannedChange& plan(int from, int to) {
    const double touch = sensor_z(to);
    // The same change plans the same while the pockets involved are the same.
    const auto key =
        std::make_tuple(from, to, touch, return_pocket(tools_, config_, from).value_or(0),
                        tools_.pocket_holding(to).value_or(0));
    const auto known = plans_.find(key);
    if (known != plans_.end()) return known->second;
    // The problems the lint reports itself (a state cut off, a tool not in
    // its pocket) do not stop the estimate: it plans as if they were resolved.
    ToolState resolved = tools_;
    resolved.uncertain = false;
    resolved.in_progress.reset();
    if (const auto home = resolved.home_of(to); home && to != from)
      resolved.pockets[*home].holds = true;
    const Simulator sim = plan_change(config_, resolved, to, touch);
    PlannedChange planned;
    for (const Step& step : sim.steps()) {
      if (step.kind == StepKind::fail) planned.refused = step.label;
    }
    planned.seconds =
        estimate_seconds(sim, config_.safe, in_.rapid_per_minute, planned.operator_waits);
    return plans_.emplace(key, planned).first->second;
  }

  const PreflightInput& in_;
  const Config& config_;
  ToolState tools_;
  bool spindle_known_ = true;
  bool said_uncertain_ = false;
  std::set<int> never_measured_;
  std::map<std::tuple<int, int, double, int, int>, PlannedChange> plans_;
  Preflight result_;
};

}  // namespace

Preflight preflight(const std::vector<program::ToolUse>& uses, const PreflightInput& input) {
  return Checker(input).run(uses);
}

}  // namespace fatc
