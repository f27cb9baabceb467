#include "keepout.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

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

std::optional<RackEntry> rack_entry(const std::vector<RackPart>& volume, const Point& from,
                                    const Point& to, double tool_length) {
  std::optional<double> first;
  const RackPart* entered = nullptr;
  for (const RackPart& part : volume) {
    Box raised = part.box;
    raised.high.z += std::max(tool_length, 0.0);
    const auto along = entry_along(from, to, raised);
    // A move that starts inside entered before (a spindle left in a pocket):
    // it is on its way out, or the entry was named already.
    const bool starts_inside = entry_along(from, from, raised).has_value();
    if (along && !starts_inside && (!first || *along < *first)) {
      first = along;
      entered = &part;
    }
  }
  if (!entered) return std::nullopt;
  const Point nose{from.x + (to.x - from.x) * *first, from.y + (to.y - from.y) * *first,
                   from.z + (to.z - from.z) * *first};
  return RackEntry{nearest_pocket(*entered, nose), nose};
}

int nearest_pocket(const RackPart& part, const Point& at) {
  const auto nearest = std::min_element(
      part.pockets.begin(), part.pockets.end(), [&](const auto& a, const auto& b) {
        return std::hypot(a.at.x - at.x, a.at.y - at.y) < std::hypot(b.at.x - at.x, b.at.y - at.y);
      });
  return nearest == part.pockets.end() ? 0 : nearest->number;
}

KeepoutState keepout_state(const Config& config, const KeepoutInputs& in) {
  if (!config.rack_keepout_all_motion) return KeepoutState::off;
  if (!in.machine_ready || !in.status_read) return KeepoutState::not_armed;
  if (in.changer_busy) return KeepoutState::lifted_for_changer;
  if (in.operator_lifts) return KeepoutState::lifted_by_operator;
  return KeepoutState::armed;
}

const char* keepout_words(KeepoutState state) {
  switch (state) {
    case KeepoutState::off:
      return "rack keep-out OFF (rack_keepout_all_motion is false)";
    case KeepoutState::armed:
      return "rack keep-out armed";
    case KeepoutState::lifted_for_changer:
      return "rack keep-out lifted for the changer's own moves";
    case KeepoutState::lifted_by_operator:
      return "rack keep-out LIFTED for teaching";
    case KeepoutState::not_armed:
      break;
  }
  return "rack keep-out not armed: the machine is not on and homed";
}

KeepoutLength ToolLengths::of(int tool, const std::map<int, double>& measured) const {
  if (tool == 0) return {};
  if (const auto z = table.find(tool); z != table.end() && z->second > 0.0) {
    return {z->second, LengthSource::table};
  }
  if (const auto own = measured.find(tool); own != measured.end() && own->second > 0.0) {
    return {own->second, LengthSource::measured};
  }
  return {longest, LengthSource::longest};
}

std::string keepout_length_words(const Config& config, const ToolLengths& lengths, int tool,
                                 const std::map<int, double>& measured) {
  const KeepoutLength counted = lengths.of(tool, measured);
  if (counted.source == LengthSource::table || counted.source == LengthSource::none) return {};
  const auto z = lengths.table.find(tool);
  const std::string given =
      z == lengths.table.end()
          ? "LinuxCNC's tool table gives no length"
          : "LinuxCNC's tool table gives Z" + format_length(config, z->second) +
                ", no length below the spindle nose";
  return "T" + std::to_string(tool) + ": " + given + "; the rack keep-out counts it as " +
         format_length(config, counted.length) +
         (counted.source == LengthSource::measured ? " (its length as the changer measured it)"
                                                   : " (the longest tool the config allows)");
}

std::string held_words(const Config& config, int tool, double tool_length) {
  if (tool == 0) return "with an empty spindle";
  return "with T" + std::to_string(tool) + " (length " + format_length(config, tool_length) + ")";
}

std::string keepout_refusal(const Config& config, const std::string& what, int pocket, int tool,
                            double tool_length, const Point& at) {
  char where[96];
  std::snprintf(where, sizeof where, "X%.3f Y%.3f Z%.3f", at.x, at.y, at.z);
  return what + " would have entered the rack at pocket " + std::to_string(pocket) + " " +
         held_words(config, tool, tool_length) + ": stopped near " + where +
         " and aborted; move clear above or beside the rack";
}

}  // namespace fatc
