#include "geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "../formatted.hpp"

namespace fatc {

PocketWaypoints pocket_waypoints(const Config& config, int number) {
  const Pocket& entry = config.pockets.at(number);
  const Point pocket = entry.at;
  // The side lies outside the column (config validation): the edge is short of it.
  const double edge =
      config.keepout_margin() / std::hypot(entry.side_offset.x, entry.side_offset.y);
  return {pocket,
          {pocket.x + entry.side_offset.x, pocket.y + entry.side_offset.y, pocket.z},
          {pocket.x, pocket.y, pocket.z + config.pocket_above_chuck_offset_z},
          {pocket.x, pocket.y, pocket.z + config.pocket_above_clearance_offset_z},
          {pocket.x + entry.side_offset.x * edge, pocket.y + entry.side_offset.y * edge, pocket.z}};
}

TipRoom tip_room(const Config& config, const Point& from, const Step& move) {
  TipRoom least{std::numeric_limits<double>::infinity(), 0};
  if (!is_motion(move.kind)) return least;
  const Point to = moved_to(from, move);
  const bool vertical = to.x == from.x && to.y == from.y;
  if (vertical && to.z >= from.z) return least;
  constexpr double kAllHeights = 1e12;
  for (const auto& [number, pocket] : config.pockets) {
    if (number == move.pocket && (move.may_enter_column || vertical)) continue;
    Box footprint = pocket_column(config, pocket.at, 0.0);
    footprint.low.z = -kAllHeights;
    footprint.high.z = kAllHeights;
    const auto enter = entry_along(from, to, footprint);
    if (!enter) continue;
    const auto enter_backwards = entry_along(to, from, footprint);
    const double leave = enter_backwards ? 1.0 - *enter_backwards : 1.0;
    // The nose is lowest over the column where the move enters or leaves it.
    const double lowest =
        std::min(from.z + (to.z - from.z) * *enter, from.z + (to.z - from.z) * leave);
    const double room = lowest - (pocket.at.z + config.pocket_above_chuck_offset_z);
    if (room < least.length) least = {room, number};
  }
  return least;
}

const char* tip_remedy() {
  return "raise safe Z or pocket_above_clearance_offset_z, use the side approach, or place safe "
         "away from over the rack";
}

std::vector<std::string> check_move(const Config& config, const Point& from, unsigned known,
                                    const Step& step, const std::optional<SoftLimits>& limits,
                                    double held_length) {
  std::vector<std::string> problems;
  if (!is_motion(step.kind)) return problems;
  const Point target = moved_to(from, step);
  if (limits) {
    const char* names[] = {"X", "Y", "Z"};
    const double values[] = {target.x, target.y, target.z};
    const AxisLimits axes[] = {limits->x, limits->y, limits->z};
    for (int axis = 0; axis < 3; ++axis) {
      if (!(step.axes & (1u << axis))) continue;
      if (values[axis] < axes[axis].min - 1e-9 || values[axis] > axes[axis].max + 1e-9) {
        problems.push_back(std::string(names[axis]) + formatted("=%.3f", values[axis]) +
                           " is outside the soft limits " + formatted("%.3f", axes[axis].min) +
                           " .. " + formatted("%.3f", axes[axis].max));
      }
    }
  }
  // The keep-out needs the start of the move: only once every axis is known.
  // Straight up enters nothing: it is the way out of a column a sequence cut
  // off in a pocket left the spindle in.
  const bool straight_up = target.x == from.x && target.y == from.y && target.z >= from.z;
  if (known == axis_xyz && !straight_up) {
    for (const auto& [number, pocket] : config.pockets) {
      // Touching a face, as at above_clearance, is no entry.
      const Box column = pocket_column(config, pocket.at, config.pocket_above_clearance_offset_z);
      if (!entry_along(from, target, column)) continue;
      if (number == step.pocket && step.may_enter_column) continue;
      problems.push_back("passes through the rack at pocket " + std::to_string(number) +
                         (number == step.pocket ? " outside its approach" : ""));
    }
    // An empty spindle, or a tool of no length, is the nose's check alone.
    const bool carries = step.held != 0 && held_length > 0.0;
    const TipRoom room = carries ? tip_room(config, from, step) : TipRoom{};
    if (carries && held_length > room.length + 1e-9) {
      problems.push_back("carries T" + std::to_string(step.held) + " (length " +
                         format_length(config, held_length) + ") with its tip " +
                         format_length(config, held_length - room.length) +
                         " below the top of the holder at pocket " + std::to_string(room.pocket) +
                         ": " + tip_remedy());
    }
  }
  return problems;
}

namespace {

/// Calls `visit(index, from, known, move)` for each move of `steps`, from
/// where the one before left the spindle.
template <class Visit>
void walk_moves(const std::vector<Step>& steps, const Point& at, unsigned known, Visit visit) {
  Point position = at;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const Step& step = steps[i];
    if (!is_motion(step.kind)) continue;
    visit(i, position, known, step);
    position = moved_to(position, step);
    known |= step.axes;
  }
}

}  // namespace

std::vector<Violation> check_steps(const Config& config, const std::vector<Step>& steps,
                                   const std::optional<SoftLimits>& limits,
                                   const StepsFrom& from) {
  std::vector<Violation> violations;
  walk_moves(steps, from.at, from.known,
             [&](std::size_t i, const Point& position, unsigned known, const Step& step) {
               const double held_length = from.lengths.of(step.held, from.measured).length;
               for (auto& what : check_move(config, position, known, step, limits, held_length)) {
                 violations.push_back({i, std::move(what)});
               }
             });
  return violations;
}

StepRoom least_tip_room(const Config& config, const std::vector<Step>& steps, const Point& at) {
  StepRoom least{{std::numeric_limits<double>::infinity(), 0}, 0};
  walk_moves(steps, at, axis_xyz,
             [&](std::size_t i, const Point& position, unsigned known, const Step& step) {
               if (step.held == 0 || known != axis_xyz) return;
               const TipRoom room = tip_room(config, position, step);
               if (room.length < least.room.length) least = {room, i};
             });
  return least;
}

}  // namespace fatc
