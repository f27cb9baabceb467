#include "touch.hpp"

#include <algorithm>
#include <cmath>

#include "../formatted.hpp"
#include "geometry.hpp"

namespace fatc {
namespace {

int sign(double value) { return value < 0.0 ? -1 : 1; }

/// A coordinate as the config's unit shows one: 3 decimals in mm, 4 in inch.
std::string figure(Units units, double value) {
  return formatted(units == Units::inch ? "%.4f" : "%.3f", value);
}

}  // namespace

// The touches are made in a fixed order, each from what the earlier ones
// found: the top face first (it sets the height of the rest), then the walls
// or faces. Each touch is the nose's coordinate where it tripped.
struct FeatureTouch::State {
  RackTouch rack;
  Units units = Units::mm;
  std::string name;
  int pocket = 0;
  bool datum = false;
  Point rough;
  Point before;
  double probe_length = 0.0;
  /// A fork: the axis it opens along (toward the pocket's side) and which way.
  unsigned open_axis = axis_x;
  int open_sign = 1;
  std::vector<double> trips;

  double radius() const { return rack.stylus_radius; }
  /// The top face's Z: the nose where it touched less the probe's length.
  double top() const { return trips.at(0) - probe_length; }
  /// The nose's Z with the stylus ball's centre `depth` below the top face:
  /// the probe's tip (nose − length) is the ball's bottom.
  double wall_z() const { return top() - rack.depth + probe_length - radius(); }
  /// A touch on `axis` toward `direction` from `start`, expected at `expected`.
  Touch touch(std::string what, unsigned axis, int direction, const Point& start,
              double expected) const {
    Touch t;
    t.label = name + ", " + what;
    t.axis = axis;
    t.direction = direction;
    t.start = start;
    t.expected = expected;
    t.limit = expected + direction * rack.search;
    t.pocket = pocket;
    return t;
  }
  std::string wall(unsigned axis, int direction) const {
    return std::string("wall ") + (direction > 0 ? "+" : "-") + axis_letter(axis);
  }
  /// From inside a bore (or fork) at `centre`, the wall across `axis` toward `direction`.
  Touch bore_wall(unsigned axis, int direction, const Point& centre) const {
    const double reach = *rack.bore_diameter / 2.0 - radius();
    Touch t = touch(wall(axis, direction), axis, direction, centre,
                    coordinate(rough, axis) + direction * reach);
    t.within = true;
    return t;
  }
  /// From outside a face at `offset` from the pocket, toward the pocket along `axis`.
  Touch face(unsigned axis, const PlanarOffset& offset) const {
    const int side = sign(axis == axis_x ? offset.x : offset.y);
    Point start{rough.x + offset.x, rough.y + offset.y, wall_z()};
    const double face_at = coordinate(start, axis);
    coordinate(start, axis) = face_at + side * (rack.clear + radius());
    return touch(std::string("face ") + (side > 0 ? "+" : "-") + axis_letter(axis), axis, -side,
                 start, face_at + side * radius());
  }
  std::optional<Touch> next() const;
  /// Where the feature is from the pair of touches from `plus` (+, then −),
  /// and how wide it measured: the stylus radius and its runout cancel.
  double middle(std::size_t plus) const { return (trips.at(plus) + trips.at(plus + 1)) / 2.0; }
  double across(std::size_t plus) const {
    return trips.at(plus) - trips.at(plus + 1) + 2.0 * radius();
  }
  /// The top face and the pairs: a bore's four walls, a fork's jaws and back, two faces.
  std::size_t count() const {
    return rack.feature == TouchFeature::bore ? 5u : rack.feature == TouchFeature::fork ? 4u : 3u;
  }
};

std::optional<Touch> FeatureTouch::State::next() const {
  const std::size_t made = trips.size();
  if (made >= count()) return std::nullopt;
  if (made == 0) {
    const double expected = rough.z - rack.pocket_above_top + probe_length;
    return touch("top face", axis_z, -1,
                 {rough.x + rack.top.x, rough.y + rack.top.y, expected + rack.clear}, expected);
  }
  const Point centre{rough.x, rough.y, wall_z()};
  switch (rack.feature) {
    case TouchFeature::bore: {
      if (made <= 2) return bore_wall(axis_x, made == 1 ? 1 : -1, centre);
      // Across Y through the X centre found: a rough X off the middle would
      // measure a chord, not the diameter.
      Point from = centre;
      from.x = middle(1);
      return bore_wall(axis_y, made == 3 ? 1 : -1, from);
    }
    case TouchFeature::fork: {
      const unsigned jaws = open_axis == axis_x ? axis_y : axis_x;
      if (made <= 2) return bore_wall(jaws, made == 1 ? 1 : -1, centre);
      Point from = centre;
      coordinate(from, jaws) = middle(1);
      Touch back = bore_wall(open_axis, -open_sign, from);
      back.label = name + ", back wall";
      return back;
    }
    case TouchFeature::faces:
      return made == 1 ? face(axis_x, rack.x_face) : face(axis_y, rack.y_face);
  }
  return std::nullopt;
}

FeatureTouch FeatureTouch::of_pocket(const Config& c, int pocket, const Point& rough,
                                     double probe_length) {
  FeatureTouch feature;
  auto state = std::make_shared<State>();
  state->rack = c.rack_touch.value();
  state->units = c.units;
  state->name = "pocket " + std::to_string(pocket);
  state->pocket = pocket;
  state->rough = rough;
  state->before = c.pockets.at(pocket).at;
  state->probe_length = probe_length;
  const PlanarOffset side = c.pockets.at(pocket).side_offset;
  const bool along_x = std::fabs(side.x) > std::fabs(side.y);
  state->open_axis = along_x ? axis_x : axis_y;
  state->open_sign = sign(along_x ? side.x : side.y);
  feature.state_ = state;
  return feature;
}

FeatureTouch FeatureTouch::of_datum(const Config& c, double probe_length) {
  const RackTouch& rack = c.rack_touch.value();
  const int pocket = rack.datum_pocket;
  const Point taught = rack.datum.value_or(c.pockets.at(pocket).at);
  FeatureTouch feature = of_pocket(c, pocket, taught, probe_length);
  feature.state_->name = "the rack datum (pocket " + std::to_string(pocket) + ")";
  feature.state_->before = taught;
  feature.state_->datum = true;
  return feature;
}

const std::string& FeatureTouch::name() const { return state_->name; }

std::optional<Touch> FeatureTouch::next() const { return state_->next(); }

void FeatureTouch::touched(double at) { state_->trips.push_back(at); }

std::string FeatureTouch::problem() const {
  const State& s = *state_;
  if (s.trips.size() < s.count()) {
    return s.name + ": " + std::to_string(s.count() - s.trips.size()) + " touches still to make";
  }
  if (s.rack.feature == TouchFeature::faces) return "";
  const double want = *s.rack.bore_diameter;
  const auto off = [&](double measured, unsigned axis) -> std::string {
    if (std::fabs(measured - want) <= s.rack.bore_tolerance) return "";
    return s.name + ": the bore measured " + figure(s.units, measured) + " across " +
           axis_letter(axis) + ", rack_touch.bore_diameter says " + figure(s.units, want) +
           " (tolerance " + figure(s.units, s.rack.bore_tolerance) + "): a chip, or not the " +
           "feature rack_touch describes";
  };
  if (s.rack.feature == TouchFeature::fork) {
    return off(s.across(1), s.open_axis == axis_x ? axis_y : axis_x);
  }
  const std::string x = off(s.across(1), axis_x);
  return x.empty() ? off(s.across(3), axis_y) : x;
}

std::optional<Found> FeatureTouch::found() const {
  if (!problem().empty()) return std::nullopt;
  const State& s = *state_;
  Found f;
  f.name = s.name;
  f.pocket = s.datum ? 0 : s.pocket;
  f.before = s.before;
  f.at.z = s.top() + s.rack.pocket_above_top;
  const double r = s.radius();
  switch (s.rack.feature) {
    case TouchFeature::bore:
      f.at.x = s.middle(1);
      f.at.y = s.middle(3);
      f.across = (s.across(1) + s.across(3)) / 2.0;
      break;
    case TouchFeature::fork: {
      const unsigned jaws = s.open_axis == axis_x ? axis_y : axis_x;
      coordinate(f.at, jaws) = s.middle(1);
      // The back wall lies the ball's radius beyond its centre, toward the
      // back; the centre half a diameter from it, toward the opening.
      const double back = s.trips.at(3) - s.open_sign * r;
      coordinate(f.at, s.open_axis) = back + s.open_sign * *s.rack.bore_diameter / 2.0;
      f.across = s.across(1);
      break;
    }
    case TouchFeature::faces: {
      // Each face lies the ball's radius beyond its centre, the way it moved.
      const int x_side = sign(s.rack.x_face.x);
      const int y_side = sign(s.rack.y_face.y);
      f.at.x = s.trips.at(1) - x_side * r - s.rack.x_face.x;
      f.at.y = s.trips.at(2) - y_side * r - s.rack.y_face.y;
      break;
    }
  }
  return f;
}

namespace plan {
namespace {

/// A move of the touches: within `pocket`'s column, the probe `held`.
Step touch_move(StepKind kind, unsigned axes, const Point& target, std::string label, int pocket,
                int held, double feed = 0.0) {
  Step step = move_step(kind, axes, target, std::move(label), pocket, pocket != 0, feed);
  step.held = held;
  return step;
}

}  // namespace

std::vector<Step> to_touch(const Config& c, const Touch& touch, int pocket, int held) {
  // Each touch starts from safe Z: the probe hangs its length below the nose,
  // and over the rack nothing lower is clear of every holder.
  const Point& start = touch.start;
  const double above_clearance = pocket_waypoints(c, pocket).above_clearance.z;
  std::vector<Step> route{
      touch_move(StepKind::rapid, axis_z, c.safe, "safe Z", pocket, held),
      touch_move(StepKind::rapid, axis_xy, start, "over " + touch.label, pocket, held)};
  if (start.z < above_clearance) {
    Point clearance = start;
    clearance.z = above_clearance;
    route.push_back(touch_move(StepKind::rapid, axis_z, clearance,
                               "above-clearance of pocket " + std::to_string(pocket), pocket,
                               held));
    route.push_back(touch_move(StepKind::feed, axis_z, start, "start of " + touch.label, pocket,
                               held, c.pocket_feed));
  } else {
    route.push_back(
        touch_move(StepKind::rapid, axis_z, start, "start of " + touch.label, pocket, held));
  }
  return route;
}

std::vector<Step> to_next_touch(const Config& c, const Touch& made, const Touch& next, int held) {
  if (!made.within || !next.within || made.pocket != next.pocket) {
    return to_touch(c, next, next.pocket, held);
  }
  return {touch_move(StepKind::feed, axis_xy, next.start, "across to the start of " + next.label,
                     next.pocket, held, c.pocket_feed)};
}

namespace {
/// A probing move of `touch` toward its limit: G38.3 on the touch's axis.
Step probing(const Touch& touch, const char* stage, double feed, int probe) {
  Point target = touch.start;
  coordinate(target, touch.axis) = touch.limit;
  return touch_move(StepKind::probe, touch.axis, target, touch.label + " (" + stage + ")",
                    touch.pocket, probe, feed);
}
}  // namespace

Step touch_seek(const Config& c, const Touch& touch, int probe) {
  return probing(touch, "seek", c.seek_feed_of(probe), probe);
}

Step touch_back_off(const Config& c, const Touch& touch, double tripped, int probe) {
  Point target = touch.start;
  coordinate(target, touch.axis) = tripped - touch.direction * c.probe_backoff;
  return touch_move(StepKind::feed, touch.axis, target, "back off " + touch.label, touch.pocket,
                    probe, c.seek_feed_of(probe));
}

Step back_to_touch_start(const Config& c, const Touch& touch, int probe) {
  return touch_move(StepKind::feed, touch.axis, touch.start, "back to the start of " + touch.label,
                    touch.pocket, probe, c.seek_feed_of(probe));
}

Step touch_latch(const Config& c, const Touch& touch, int probe) {
  return probing(touch, "latch", c.latch_feed_of(probe), probe);
}

std::vector<Step> leave_feature(const Config& c, int pocket, int held) {
  return {touch_move(StepKind::rapid, axis_z, c.safe, "safe Z", pocket, held)};
}

}  // namespace plan

ExpectedTouches expected_touches(const Config& c, std::vector<FeatureTouch> features, int probe) {
  ExpectedTouches path;
  const auto add = [&](std::vector<Step> steps) {
    path.steps.insert(path.steps.end(), steps.begin(), steps.end());
  };
  for (FeatureTouch& feature : features) {
    int pocket = 0;
    std::optional<Touch> made;
    while (const auto touch = feature.next()) {
      pocket = touch->pocket;
      add(made ? plan::to_next_touch(c, *made, *touch, probe)
               : plan::to_touch(c, *touch, pocket, probe));
      made = touch;
      add({plan::touch_seek(c, *touch, probe),
           plan::touch_back_off(c, *touch, touch->expected, probe),
           plan::touch_latch(c, *touch, probe)});
      feature.touched(touch->expected);
    }
    add(plan::leave_feature(c, pocket, probe));
    if (const auto found = feature.found()) path.found.push_back(*found);
  }
  return path;
}

std::vector<std::string> found_lines(const Config& c, const std::vector<Found>& found) {
  std::vector<std::string> lines;
  std::size_t width = 0;
  for (const Found& f : found) width = std::max(width, f.name.size());
  for (const Found& f : found) {
    std::string line = f.name + std::string(width - f.name.size(), ' ');
    for (const unsigned axis : {axis_x, axis_y, axis_z}) {
      const double was = coordinate(f.before, axis);
      const double now = coordinate(f.at, axis);
      line += std::string("   ") + axis_letter(axis) + " " + figure(c.units, was) + " → " +
              figure(c.units, now) + " (" + (now - was < 0.0 ? "" : "+") +
              figure(c.units, now - was) + ")";
    }
    if (f.across) line += "   across " + figure(c.units, *f.across);
    lines.push_back(line);
  }
  return lines;
}

Drift drift_of(const Config& c, const Point& taught, const Point& measured) {
  Drift drift;
  drift.off = {measured.x - taught.x, measured.y - taught.y, measured.z - taught.z};
  for (const unsigned axis : {axis_x, axis_y, axis_z}) {
    const double off = std::fabs(coordinate(drift.off, axis));
    if (off > drift.worst) {
      drift.worst = off;
      drift.axis = axis_letter(axis);
    }
  }
  const double tolerance = c.rack_touch ? c.rack_touch->drift_tolerance
                                        : unit_default::touch_drift_tolerance.in(c.units);
  drift.within = drift.worst <= tolerance;
  const bool inch = c.units == Units::inch;
  const char* pattern = inch ? "%.4f" : "%.2f";
  const std::string unit = inch ? " inch" : " mm";
  const std::string worst = formatted(pattern, drift.worst);
  const std::string allowed = "(tolerance " + formatted(pattern, tolerance) + ")";
  drift.words = drift.within ? "the rack datum is within " + worst + unit +
                                   " of where it was taught " + allowed
                             : "the rack datum is " + worst + unit + " off in " + drift.axis +
                                   " " + allowed + ": re-teach or check the rack";
  return drift;
}

}  // namespace fatc
