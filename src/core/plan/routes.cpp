#include "routes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "../rack/geometry.hpp"

namespace fatc::plan {

namespace {

std::string of_pocket(const char* what, int pocket) {
  return std::string(what) + " of pocket " + std::to_string(pocket);
}

bool direct(const Config& c) { return c.path == Path::direct; }
bool from_above(const Config& c, int pocket) {
  return c.pockets.at(pocket).approach == Approach::top;
}

// The moves to the waypoints of one pocket's approach, each named as --plan
// prints it (not fatc::Pocket, the config's entry).
struct PocketMoves {
  const Config& c;
  int number;
  PocketWaypoints at = pocket_waypoints(c, number);

  /// Straight up from the pocket or its side, still within its approach.
  Step safe_z() const { return move_step(StepKind::rapid, axis_z, c.safe, "safe Z", number, true); }
  Step over_side() const {
    return move_step(StepKind::rapid, axis_xy, at.side, of_pocket("over the side", number), number);
  }
  Step down_to_side() const {
    return move_step(StepKind::rapid, axis_z, at.side, of_pocket("side", number), number, true);
  }
  Step over_pocket() const {
    return move_step(StepKind::rapid, axis_xy, at.pocket, "over pocket " + std::to_string(number),
                number);
  }
  Step above_chuck() const {
    return move_step(StepKind::rapid, axis_z, at.above_chuck, of_pocket("above-chuck", number), number,
                true);
  }
  Step above_clearance() const {
    return move_step(StepKind::rapid, axis_z, at.above_clearance, of_pocket("above-clearance", number),
                number, true);
  }
  /// On the direct path the side approach crosses to the pocket's column at
  /// rapid; only inside the column (the holder engaged) is it slow.
  Step column_edge() const {
    return move_step(StepKind::rapid, axis_xy, at.column_edge, of_pocket("column edge", number), number,
                true);
  }
  Step out_to_side() const {
    return move_step(StepKind::rapid, axis_xy, at.side, of_pocket("side", number), number, true);
  }
  Step slowly(unsigned axes, const Point& target, std::string label) const {
    return move_step(StepKind::feed, axes, target, std::move(label), number, true, c.pocket_feed);
  }
  Step slowly_into() const {
    return slowly(axis_xy, at.pocket, "pocket " + std::to_string(number));
  }
  Step slowly_down() const { return slowly(axis_z, at.pocket, "pocket " + std::to_string(number)); }
  Step slowly_to_side() const { return slowly(axis_xy, at.side, of_pocket("side", number)); }
  Step slowly_to_column_edge() const {
    return slowly(axis_xy, at.column_edge, of_pocket("column edge", number));
  }
  Step slowly_up_to_clearance() const {
    return slowly(axis_z, at.above_clearance, of_pocket("above-clearance", number));
  }
  Step slowly_up_to_above_chuck() const {
    return slowly(axis_z, at.above_chuck, of_pocket("above-chuck", number));
  }
  /// A collet nut: `offset` above the engage Z (the pocket's z), or a zone's Z.
  Step at_height(StepKind kind, double z, const char* what) const {
    Point there = at.pocket;
    there.z = z;
    return move_step(kind, axis_z, there, of_pocket(what, number), number, true,
                     kind == StepKind::feed ? c.chuck.engage_feed : 0.0);
  }
  Step spin_off(StepKind kind) const {
    return at_height(kind, at.pocket.z + c.chuck.spin_off_offset_z, "spin-off");
  }
  Step engaged() const { return at_height(StepKind::feed, at.pocket.z, "engage Z"); }
};

}  // namespace

Step safe_z(const Config& c) { return move_step(StepKind::rapid, axis_z, c.safe, "safe Z"); }
Step safe_xy(const Config& c) { return move_step(StepKind::rapid, axis_xy, c.safe, "safe XY"); }
Step loading_z(const Config& c) { return move_step(StepKind::rapid, axis_z, c.loading, "loading Z"); }
Step loading_xy(const Config& c) {
  return move_step(StepKind::rapid, axis_xy, c.loading, "loading XY");
}
Step sensor_xy(const Config& c) {
  return move_step(StepKind::rapid, axis_xy, c.probe_limit, "over the touch-off sensor");
}
std::optional<double> probe_approach_z(const Config& c, int tool, double length,
                                       std::optional<double> start_z) {
  if (c.seek_feed_of(tool) >= c.probe_seek_feed || length <= 0.0 || !start_z) return std::nullopt;
  const double z = length + c.probe_length_compensation_offset + c.window();
  if (z <= c.probe_limit.z || z >= *start_z - c.probe_backoff) return std::nullopt;
  return z;
}
Step probe_approach(const Config& c, double z) {
  Point above = c.probe_limit;
  above.z = z;
  return move_step(StepKind::probe, axis_z, above, "touch-off sensor (approach)", 0, false,
              c.probe_seek_feed);
}
Step probe_seek(const Config& c, int tool) {
  return move_step(StepKind::probe, axis_z, c.probe_limit, "touch-off sensor (seek)", 0, false,
              c.seek_feed_of(tool));
}
Step probe_back_off(const Config& c, int tool, double first_touch_z) {
  Point above = c.probe_limit;
  above.z = first_touch_z + c.probe_backoff;
  return move_step(StepKind::feed, axis_z, above, "back off the sensor", 0, false, c.seek_feed_of(tool));
}
Step probe_latch(const Config& c, int tool) {
  return move_step(StepKind::probe, axis_z, c.probe_limit, "touch-off sensor (latch)", 0, false,
              c.latch_feed_of(tool));
}
Step retract_from_sensor(const Config& c, double latched_z) {
  Point up = c.probe_limit;
  up.z = latched_z + c.probe_retract_offset_z;
  return move_step(StepKind::rapid, axis_z, up, "retract from the sensor");
}
Step spindle_tool(int tool) {
  Step step;
  step.kind = StepKind::set_spindle_tool;
  step.tool = tool;
  step.label = "tool in spindle";
  return step;
}
Step tool_length(int tool, double length) {
  Step step;
  step.kind = StepKind::set_tool_length;
  step.tool = tool;
  step.value = length;
  step.label = "tool table";
  return step;
}

Route return_to_approach(const Config& c, int pocket) {
  const PocketMoves p{c, pocket};
  Route route{safe_z(c)};
  if (!direct(c)) route.push_back(safe_xy(c));
  if (!from_above(c, pocket)) {
    route.push_back(p.over_side());
    route.push_back(p.down_to_side());
  } else {
    route.push_back(p.over_pocket());
    route.push_back(direct(c) ? p.above_chuck() : p.above_clearance());
  }
  return route;
}

Route return_into_pocket(const Config& c, int pocket) {
  const PocketMoves p{c, pocket};
  if (from_above(c, pocket)) return {p.slowly_down()};
  if (direct(c)) return {p.column_edge(), p.slowly_into()};
  return {p.slowly_into()};
}

Route return_up_from_tool(const Config& c, int pocket) {
  return {PocketMoves{c, pocket}.above_chuck()};
}

Route return_away(const Config& c, int pocket, bool fetch_follows) {
  const PocketMoves p{c, pocket};
  Route route;
  if (!direct(c)) route.push_back(p.above_clearance());
  route.push_back(p.safe_z());
  if (!(direct(c) && fetch_follows)) route.push_back(safe_xy(c));
  return route;
}

Route fetch_to_above_chuck(const Config& c, int pocket) {
  const PocketMoves p{c, pocket};
  Route route{safe_z(c)};
  if (!direct(c)) route.push_back(safe_xy(c));
  route.push_back(p.over_pocket());
  if (!direct(c)) route.push_back(p.above_clearance());
  route.push_back(p.above_chuck());
  return route;
}

Route fetch_down_to_tool(const Config& c, int pocket) {
  return {PocketMoves{c, pocket}.slowly_down()};
}

Route fetch_out_and_away(const Config& c, int pocket) {
  const PocketMoves p{c, pocket};
  Route route;
  if (!from_above(c, pocket)) {
    if (direct(c)) {
      route = {p.slowly_to_column_edge(), p.out_to_side()};
    } else {
      route = {p.slowly_to_side()};
    }
  } else {
    route = {direct(c) ? p.slowly_up_to_above_chuck() : p.slowly_up_to_clearance()};
  }
  route.push_back(p.safe_z());
  route.push_back(safe_xy(c));
  return route;
}

Route nut_to_spin_off(const Config& c, int pocket) {
  const PocketMoves p{c, pocket};
  Route route{safe_z(c)};
  if (!direct(c)) route.push_back(safe_xy(c));
  route.push_back(p.over_pocket());
  route.push_back(p.spin_off(StepKind::rapid));
  return route;
}

Route nut_away(const Config& c, int pocket) { return return_away(c, pocket, false); }

Route nut_back_to_spin_off(const Config& c, int pocket) {
  return {PocketMoves{c, pocket}.spin_off(StepKind::rapid)};
}

Route nut_screw_off(const Config& c, int pocket) {
  const PocketMoves p{c, pocket};
  return {p.engaged(),
          p.at_height(StepKind::feed, p.at.pocket.z + c.chuck.rise_after_unload_offset_z,
                      "rise after unload")};
}

Route nut_screw_on(const Config& c, int pocket) {
  const PocketMoves p{c, pocket};
  Route route;
  for (int plunge = 0; plunge < c.chuck.tighten_plunges; ++plunge) {
    route.push_back(p.engaged());
    route.push_back(p.spin_off(StepKind::feed));
  }
  return route;
}

Route nut_to_zone_1(const Config& c, int pocket) {
  return {PocketMoves{c, pocket}.at_height(StepKind::rapid, c.chuck.recognition->zone_1_z,
                                           "recognition zone 1")};
}

Route nut_to_zone_2(const Config& c, int pocket) {
  return {PocketMoves{c, pocket}.at_height(StepKind::rapid, c.chuck.recognition->zone_2_z,
                                           "recognition zone 2")};
}

namespace {
/// A move that stays at safe Z: across, or up (or down) to safe Z.
bool at_safe_z(const Config& c, const Step& step) {
  return is_motion(step.kind) && (!(step.axes & axis_z) || step.target.z == c.safe.z);
}
}  // namespace

Route while_spindle_stops(const Config& c, const Route& first) {
  Route route;
  if (!c.move_while_spindle_stops) return route;
  for (const Step& step : first) {
    if (!at_safe_z(c, step) || (c.rack_cover && (step.axes & axis_xy))) break;
    route.push_back(step);
  }
  // Across at a Z nobody knows is safe: only once up at safe Z.
  if (route.empty() || route.front().axes != axis_z) return {};
  return route;
}

Route while_spindle_stops_before(const Config& c, const FirstLeg& first) {
  if (c.screws_nuts()) return while_spindle_stops(c, nut_to_spin_off(c, first.pocket));
  return while_spindle_stops(c, first.returns ? return_to_approach(c, first.pocket)
                                              : fetch_to_above_chuck(c, first.pocket));
}

Route from_where_it_stands(const Config& c, Route route, const Point& at, unsigned known_axes) {
  if (!(known_axes & axis_z) || at.z != c.safe.z) return route;
  Point along = at;
  std::size_t start = 0;
  for (std::size_t i = 0; i + 1 < route.size() && at_safe_z(c, route[i]); ++i) {
    const Step& step = route[i];
    if ((step.axes & ~known_axes) != 0) break;
    if (step.axes & axis_x) along.x = step.target.x;
    if (step.axes & axis_y) along.y = step.target.y;
    if (step.axes & axis_z) along.z = step.target.z;
    if (along.x == at.x && along.y == at.y && along.z == at.z) start = i + 1;
  }
  route.erase(route.begin(), route.begin() + static_cast<std::ptrdiff_t>(start));
  return route;
}

namespace {
bool rapid_on(const Step& step, unsigned axes) {
  return step.kind == StepKind::rapid && step.axes == axes;
}

/// How far the vertical line through `at` lies outside the nearest pocket's
/// keep-out column, in XY (a column is a square).
double outside_columns(const Config& c, const Point& at) {
  const double m = c.keepout_margin();
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& [number, pocket] : c.pockets) {
    nearest = std::min(nearest, std::hypot(std::max(std::abs(at.x - pocket.at.x) - m, 0.0),
                                           std::max(std::abs(at.y - pocket.at.y) - m, 0.0)));
  }
  return nearest;
}
}  // namespace

Route blended(const Config& c, const Route& route, const Point& at, unsigned known_axes) {
  if (c.blend_tolerance <= 0.0) return route;
  // A rounded corner stays within the tolerance of its two moves (G64 P): of
  // the crossing at safe Z, which lies that much above every column's top
  // (Config::blend_room), and of the way up or down, whose vertical lies that
  // much outside every column. A way up or down closer to a column, or into or
  // out of one, gets Config::blend_over_columns(), which keeps the whole
  // corner above the columns. A run takes its corners' least.
  const auto corner_beside = [&](const Point& vertical) {
    return outside_columns(c, vertical) >= c.blend_tolerance ? c.blend_tolerance
                                                             : c.blend_over_columns();
  };
  Route runs;
  Point where = at;
  unsigned known = known_axes;
  for (std::size_t i = 0; i < route.size(); ++i) {
    const auto next_is = [&](std::size_t k, unsigned axes) {
      return k < route.size() && rapid_on(route[k], axes);
    };
    const bool xy_known = (known & axis_xy) == axis_xy;
    bool at_safe = (known & axis_z) && where.z == c.safe.z;
    std::vector<Step> before;
    double tolerance = c.blend_tolerance;
    // Up to safe Z, on into a crossing.
    if (rapid_on(route[i], axis_z) && route[i].target.z == c.safe.z && next_is(i + 1, axis_xy) &&
        xy_known) {
      if (const double up = corner_beside(where); up > 0.0) {
        tolerance = up;
        before.push_back(route[i++]);
        at_safe = true;
      }
    }
    // Across at safe Z, on into another crossing or a way down.
    if (at_safe && rapid_on(route[i], axis_xy)) {
      const double next = next_is(i + 1, axis_xy)  ? c.blend_tolerance
                          : next_is(i + 1, axis_z) ? corner_beside(route[i].target)
                                                   : 0.0;
      if (next > 0.0) {
        tolerance = std::min(tolerance, next);
        before.push_back(route[i++]);
      }
    }
    Step step = route[i];
    if (!before.empty()) {
      step.before = std::move(before);
      step.blend = tolerance;
    }
    for (const Step& move : moves_of(step)) {
      if (!is_motion(move.kind)) continue;
      where = moved_to(where, move);
      known |= move.axes;
      if (move.kind == StepKind::probe) known &= ~static_cast<unsigned>(axis_z);
    }
    runs.push_back(std::move(step));
  }
  return runs;
}

Route walked(const Config& c, Route route, const Standing& from) {
  return blended(c, from_where_it_stands(c, std::move(route), from.at, from.known_axes), from.at,
                 from.known_axes);
}

Route to_safe_z(const Config& c) { return {safe_z(c)}; }
Route to_loading(const Config& c) { return {loading_z(c), loading_xy(c)}; }
Route to_sensor(const Config& c) { return {loading_z(c), sensor_xy(c)}; }

Route verify_pocket(const Config& c, int pocket) {
  const PocketMoves p{c, pocket};
  Route route{safe_z(c), safe_xy(c)};
  if (c.screws_nuts()) {
    route.insert(route.end(), {p.over_pocket(), p.spin_off(StepKind::rapid), p.engaged(),
                               p.spin_off(StepKind::feed)});
  } else if (from_above(c, pocket)) {
    route.insert(route.end(), {p.over_pocket(), p.above_clearance(), p.slowly_down(),
                               p.slowly_up_to_clearance()});
  } else {
    route.insert(route.end(), {p.over_side(), p.down_to_side(), p.slowly_into(),
                               p.slowly_to_side()});
  }
  route.push_back(p.safe_z());
  route.push_back(safe_xy(c));
  const double feed = c.dry_run_feed();
  for (Step& step : route) {
    step.feed = step.kind == StepKind::feed ? std::min(step.feed, feed) : feed;
    step.kind = StepKind::feed;
  }
  return route;
}

}  // namespace fatc::plan
