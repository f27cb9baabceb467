#include "timing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "simulator.hpp"

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

/// A move's feed as move_seconds takes it: none for a rapid.
double feed_of(const Step& step) { return step.kind == StepKind::rapid ? 0.0 : step.feed; }

}  // namespace

double trapezoid_seconds(double distance, double velocity, double acceleration) {
  if (distance == 0.0 || !(velocity > 0.0) || !(acceleration > 0.0)) return 0.0;
  if (distance >= velocity * velocity / acceleration) {
    return distance / velocity + velocity / acceleration;
  }
  return 2.0 * std::sqrt(distance / acceleration);
}

double move_seconds(const Point& from, const Point& to, double feed_per_minute,
                    const MotionLimits& limits) {
  const Point delta{to.x - from.x, to.y - from.y, to.z - from.z};
  auto [velocity, acceleration] = move_limits(delta, limits);
  if (feed_per_minute > 0.0) velocity = std::min(velocity, feed_per_minute / 60.0);
  return trapezoid_seconds(std::hypot(delta.x, delta.y, delta.z), velocity, acceleration);
}

MotionLimits planner_limits(const MotionLimits& limits) {
  MotionLimits planned = limits;
  planned.linear_acceleration = std::numeric_limits<double>::infinity();
  return planned;
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
        moves += move_seconds(from, to, feed_of(step), limits);
      });
  return moves + dwells;
}

double limits_seconds_while_running_down(const Simulator& plan, const Point& start,
                                         const MotionLimits& limits) {
  Simulator before = plan;
  before.records.resize(std::min(plan.spindle_stood, plan.records.size()));
  return limits_seconds(before, start, limits);
}

ChangeTime change_time(const Simulator& plan, const Point& start, const MachineTiming& machine) {
  ChangeTime time;
  const MotionLimits planned = planner_limits(machine.limits);
  time.iocontrol = kIocontrolCycles * machine.iocontrol_cycle_seconds;
  time.dwells = walk_moves(plan, start, [&](const Point& from, const Point& to, const Step& step) {
    time.moves += move_seconds(from, to, feed_of(step), planned);
  });
  for (const Record& record : plan.records) {
    // A run of rapids is one step of the executor: its moves run on into each other.
    if (record.kind == Record::Kind::step && record.step.blend == 0.0) ++time.steps;
    // Every wait for the operator is a prompt (in M6 for a manual tool, the only sign).
    if (record.kind == Record::Kind::message && record.message_kind == MessageKind::prompt) {
      ++time.operator_waits;
    }
  }
  return time;
}

}  // namespace fatc
