#include "rack_volume.hpp"

#include <algorithm>
#include <cmath>

namespace fatc {
namespace {

constexpr double kNoFloor = -1e12;

/// Whether the XY footprints of two boxes lie within `gap` of each other.
bool near(const Box& a, const Box& b, double gap) {
  return a.low.x - gap <= b.high.x && b.low.x - gap <= a.high.x && a.low.y - gap <= b.high.y &&
         b.low.y - gap <= a.high.y;
}

Box joined(const Box& a, const Box& b) {
  return {{std::min(a.low.x, b.low.x), std::min(a.low.y, b.low.y), kNoFloor},
          {std::max(a.high.x, b.high.x), std::max(a.high.y, b.high.y),
           std::max(a.high.z, b.high.z)}};
}

}  // namespace

Box pocket_column(const Config& config, const Point& pocket, double top_offset) {
  const double m = config.keepout_margin();
  return {{pocket.x - m, pocket.y - m, kNoFloor}, {pocket.x + m, pocket.y + m, pocket.z + top_offset}};
}

std::optional<double> entry_along(const Point& a, const Point& b, const Box& box) {
  constexpr double kTouch = 1e-6;
  const double start[] = {a.x, a.y, a.z};
  const double delta[] = {b.x - a.x, b.y - a.y, b.z - a.z};
  const double low[] = {box.low.x + kTouch, box.low.y + kTouch, box.low.z + kTouch};
  const double high[] = {box.high.x - kTouch, box.high.y - kTouch, box.high.z - kTouch};
  double enter = 0.0;
  double leave = 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    if (delta[axis] == 0.0) {
      if (start[axis] <= low[axis] || start[axis] >= high[axis]) return std::nullopt;
      continue;
    }
    double t1 = (low[axis] - start[axis]) / delta[axis];
    double t2 = (high[axis] - start[axis]) / delta[axis];
    if (t1 > t2) std::swap(t1, t2);
    enter = std::max(enter, t1);
    leave = std::min(leave, t2);
    if (enter >= leave) return std::nullopt;
  }
  return enter;
}

std::vector<RackPart> rack_volume(const Config& config) {
  std::vector<RackPart> parts;
  for (const auto& [number, pocket] : config.pockets) {
    // Up to the holders' tops (the nose clear of the pull stud), and the margin above.
    const double top = config.pocket_above_chuck_offset_z + config.keepout_above();
    parts.push_back({{{number, pocket.at}}, pocket_column(config, pocket.at, top)});
  }
  // Join parts less than twice the side offset apart until none are: a
  // spindle has no business between two holders of a rack.
  const double gap =
      2.0 * std::hypot(config.pocket_side_offset.x, config.pocket_side_offset.y);
  for (bool joined_any = true; joined_any;) {
    joined_any = false;
    for (std::size_t i = 0; i < parts.size() && !joined_any; ++i) {
      for (std::size_t j = i + 1; j < parts.size() && !joined_any; ++j) {
        if (!near(parts[i].box, parts[j].box, gap)) continue;
        parts[i].box = joined(parts[i].box, parts[j].box);
        parts[i].pockets.insert(parts[i].pockets.end(), parts[j].pockets.begin(),
                                parts[j].pockets.end());
        parts.erase(parts.begin() + static_cast<std::ptrdiff_t>(j));
        joined_any = true;
      }
    }
  }
  for (RackPart& part : parts) {
    std::sort(part.pockets.begin(), part.pockets.end(),
              [](const auto& a, const auto& b) { return a.number < b.number; });
  }
  return parts;
}

int nearest_pocket(const RackPart& part, const Point& at) {
  const auto nearest = std::min_element(
      part.pockets.begin(), part.pockets.end(), [&](const auto& a, const auto& b) {
        return std::hypot(a.at.x - at.x, a.at.y - at.y) < std::hypot(b.at.x - at.x, b.at.y - at.y);
      });
  return nearest == part.pockets.end() ? 0 : nearest->number;
}

}  // namespace fatc
