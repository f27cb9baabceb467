#pragma once

// The rack found by touch (issue 45): a 3D probe in the spindle touches a
// pocket's features (rack_touch in config.json) and the pocket's position is
// computed from where it touched; the rack datum, touched again, says whether
// the rack moved. Pure: the flows (core/machine/flows/touch*) walk the
// touches one at a time, since where the next one starts depends on what the
// earlier ones found. docs/sequences.md#teach-by-touch.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "../config/config.hpp"
#include "../motion/step.hpp"

namespace fatc {

/// One touch of a feature: the probe goes from `start` along `axis` in
/// `direction` until it touches, at the latest at `limit`.
struct Touch {
  std::string label;  ///< "pocket 3, top face", "pocket 3, wall +X"
  unsigned axis = axis_z;  ///< axis_x, axis_y or axis_z
  int direction = -1;      ///< +1 or -1 along `axis`
  Point start;             ///< the nose where the touch starts (machine coordinates)
  double expected = 0.0;   ///< the nose's coordinate on `axis` where it should touch
  double limit = 0.0;      ///< where it gives up: `search` past `expected`
  int pocket = 0;          ///< the pocket whose feature it touches (the datum's too)
  /// Made from inside the feature (a bore's or a fork's walls): from one
  /// such touch the next is reached straight across (plan::to_next_touch).
  bool within = false;
};

/// A feature found by touch: a pocket's (the position it gives the pocket) or the datum's.
struct Found {
  std::string name;        ///< "pocket 3", "the rack datum (pocket 1)"
  int pocket = 0;          ///< the pocket taught, 0 for the datum
  Point before;            ///< what config.json says now (the datum: its taught value)
  Point at;                ///< what the touches say
  std::optional<double> across;  ///< a bore's measured diameter, where one was measured
};

/// Finds one feature by touch, one touch at a time.
class FeatureTouch {
 public:
  /// Pocket `pocket`'s feature (rack_touch), searched around `rough` (the
  /// pocket's configured position unless the operator gave another), with a
  /// probe `probe_length` long (its tool-table length) in the spindle.
  static FeatureTouch of_pocket(const Config& c, int pocket, const Point& rough,
                                double probe_length);
  /// The rack datum's feature (rack_touch.datum), around its taught position.
  static FeatureTouch of_datum(const Config& c, double probe_length);

  const std::string& name() const;
  /// The touch to make next, nullopt once every touch is made.
  std::optional<Touch> next() const;
  /// The nose's coordinate on the touch's axis where the (slow, latched) touch tripped.
  void touched(double at);
  /// Once every touch is made: where the feature is, or nullopt and problem()
  /// says why ("pocket 3: the bore measured 29.210 across X, rack_touch.bore_diameter says 30.000").
  std::optional<Found> found() const;
  std::string problem() const;

 private:
  struct State;
  std::shared_ptr<State> state_;
};

namespace plan {
/// From where the spindle stands to the touch's start, the probe `held` in
/// the spindle: up to the feature's clearance, across, down (the pocket's
/// keep-out column entered only for its own pocket).
std::vector<Step> to_touch(const Config& c, const Touch& touch, int pocket, int held);
/// From where `made` latched to the start of `next`: straight across at
/// `pocket_feed` where both are made from inside the same feature (the ball
/// stays within the bore: both ends are), else to_touch.
std::vector<Step> to_next_touch(const Config& c, const Touch& made, const Touch& next, int held);
/// The fast seek: a probe step toward `touch.limit` at the probe's seek feed.
Step touch_seek(const Config& c, const Touch& touch, int probe);
/// Back off `probe_backoff` from where the seek tripped, against `direction`.
Step touch_back_off(const Config& c, const Touch& touch, double tripped, int probe);
/// The slow latch toward `touch.limit` at the probe's latch feed.
Step touch_latch(const Config& c, const Touch& touch, int probe);
/// A touch that found nothing: back along its axis to where it started.
Step back_to_touch_start(const Config& c, const Touch& touch, int probe);
/// Up and out of the feature to its clearance once its touches are made.
std::vector<Step> leave_feature(const Config& c, int pocket, int held);
}  // namespace plan

/// A touch path as if every touch touched where it was expected: what
/// `--plan --touch` prints and what the keep-out check walks.
struct ExpectedTouches {
  std::vector<Step> steps;   ///< to each touch, seek, back off, latch; out of each feature
  std::vector<Found> found;  ///< each feature where the config has it already
};
/// `features` one after the other, the probe `probe` in the spindle.
ExpectedTouches expected_touches(const Config& c, std::vector<FeatureTouch> features, int probe);

/// "pocket 3   X 150.000 → 150.412 (+0.412)   Y ...   Z ...": one line per
/// found feature, old and new side by side with the difference.
std::vector<std::string> found_lines(const Config& c, const std::vector<Found>& found);

/// The datum touched again against its taught position.
struct Drift {
  Point off;           ///< measured minus taught
  double worst = 0.0;  ///< the largest |off| of the three axes
  char axis = 'X';     ///< where it is
  bool within = true;  ///< worst <= rack_touch.drift_tolerance
  /// "the rack datum is 0.62 mm off in X (tolerance 0.10): re-teach or check
  /// the rack", or "the rack datum is within 0.02 mm of where it was taught
  /// (tolerance 0.10)".
  std::string words;
};
Drift drift_of(const Config& c, const Point& taught, const Point& measured);

}  // namespace fatc
