#include "geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "keepout.hpp"

namespace fatc {
namespace {

std::string format(const char* pattern, double value) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

}  // namespace

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

std::vector<std::string> check_move(const Config& config, const Point& from, unsigned known,
                                    const Step& step, const std::optional<SoftLimits>& limits) {
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
        problems.push_back(std::string(names[axis]) + format("=%.3f", values[axis]) +
                           " is outside the soft limits " + format("%.3f", axes[axis].min) +
                           " .. " + format("%.3f", axes[axis].max));
      }
    }
  }
  // The keep-out needs the start of the move: only once every axis is known.
  if (known == axis_xyz) {
    for (const auto& [number, pocket] : config.pockets) {
      // Touching a face, as at above_clearance, is no entry.
      const Box column = pocket_column(config, pocket.at, config.pocket_above_clearance_offset_z);
      if (!entry_along(from, target, column)) continue;
      if (number == step.pocket && step.approach) continue;
      problems.push_back("passes through the rack at pocket " + std::to_string(number) +
                         (number == step.pocket ? " outside its approach" : ""));
    }
  }
  return problems;
}

std::vector<Violation> check_steps(const Config& config, const std::vector<Step>& steps,
                                   const std::optional<SoftLimits>& limits) {
  std::vector<Violation> violations;
  Point position;
  unsigned known = 0;  // axes whose position is known; the start position is not
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const Step& step = steps[i];
    if (!is_motion(step.kind)) continue;
    for (auto& what : check_move(config, position, known, step, limits)) {
      violations.push_back({i, std::move(what)});
    }
    if (step.axes & axis_x) position.x = step.target.x;
    if (step.axes & axis_y) position.y = step.target.y;
    if (step.axes & axis_z) position.z = step.target.z;
    known |= step.axes;
  }
  return violations;
}

}  // namespace fatc
