#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/rack/touch.hpp"
#include "test_config.hpp"

// The rack found by touch (docs/sequences.md, teach by touch): each feature
// is touched by a simulated probe whose trips come from a known true pocket,
// and what FeatureTouch finds is held against that truth.

namespace fatc {
namespace {

constexpr double kProbeLength = 80.0;
constexpr double kRadius = 1.5;
constexpr double kDiameter = 30.0;
constexpr double kAboveTop = 10.0;  ///< pocket Z above the top face
/// How far the rack really is from where config.json puts pocket 3.
const Point kShift{0.41, -0.27, 0.13};

const char* const kBore = R"({"rack_touch": {
  "feature": "bore", "stylus_radius": 1.5, "bore_diameter": 30.0, "top": {"x": 0, "y": -20},
  "pocket_above_top": 10.0, "depth": 5.0, "datum": {"pocket": 1}}})";

Config config_of(const char* patch) {
  const ConfigResult parsed = parse_config(test::sample_config_with(patch));
  if (!parsed.config) ADD_FAILURE() << parsed.errors.front();
  return parsed.config.value_or(Config{});
}

Point plus(const Point& a, const Point& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
double on(const Point& p, unsigned axis) {
  return axis == axis_x ? p.x : axis == axis_y ? p.y : p.z;
}

/// A rack whose pocket really is at `truth`: a top face kAboveTop below it,
/// a bore (or fork, the same circle) of `diameter` around it, or two faces.
struct TrueRack {
  Point truth;
  double diameter = kDiameter;
  PlanarOffset x_face, y_face;  ///< faces: where they really are, from `truth`
  bool faces = false;

  /// Where the nose trips on `touch`: its stylus ball meets the feature.
  double trip(const Touch& touch) const {
    if (touch.axis == axis_z) return truth.z - kAboveTop + kProbeLength;
    if (faces) {
      const double face = touch.axis == axis_x ? truth.x + x_face.x : truth.y + y_face.y;
      return face - touch.direction * kRadius;
    }
    // The ball's centre on a circle of the bore's radius less its own: off
    // the middle across, a touch meets a chord.
    const double room = diameter / 2.0 - kRadius;
    const unsigned other = touch.axis == axis_x ? axis_y : axis_x;
    const double aside = on(touch.start, other) - on(truth, other);
    return on(truth, touch.axis) + touch.direction * std::sqrt(room * room - aside * aside);
  }
};

TrueRack true_rack(const Point& truth) {
  TrueRack rack;
  rack.truth = truth;
  return rack;
}

/// Walks every touch of `feature` against `rack`; each trip must lie on the
/// touch's way between its start and its limit.
std::vector<Touch> touch_all(FeatureTouch& feature, const TrueRack& rack) {
  std::vector<Touch> made;
  while (const auto touch = feature.next()) {
    const double at = rack.trip(*touch);
    const double from = on(touch->start, touch->axis);
    EXPECT_GT((at - from) * touch->direction, 0.0) << touch->label << " trips behind its start";
    EXPECT_GT((touch->limit - at) * touch->direction, 0.0) << touch->label << " beyond its limit";
    feature.touched(at);
    made.push_back(*touch);
    if (made.size() > 10) break;
  }
  return made;
}

void expect_found(const FeatureTouch& feature, const Point& truth) {
  const auto found = feature.found();
  ASSERT_TRUE(found) << feature.problem();
  EXPECT_NEAR(found->at.x, truth.x, 1e-6);
  EXPECT_NEAR(found->at.y, truth.y, 1e-6);
  EXPECT_NEAR(found->at.z, truth.z, 1e-6);
}

TEST(RackTouch, shouldFindABoredPocketWhereItReallyIs) {
  const Config c = config_of(kBore);
  const Point rough = c.pockets.at(3).at;
  const TrueRack rack = true_rack(plus(rough, kShift));
  FeatureTouch feature = FeatureTouch::of_pocket(c, 3, rough, kProbeLength);
  touch_all(feature, rack);
  expect_found(feature, rack.truth);
  EXPECT_EQ(feature.found()->pocket, 3);
  EXPECT_EQ(feature.found()->before.x, 150.0);
}

TEST(RackTouch, shouldTouchTheTopFirstThenAcrossXThenAcrossYThroughTheXFound) {
  const Config c = config_of(kBore);
  const Point rough = c.pockets.at(3).at;
  const TrueRack rack = true_rack(plus(rough, kShift));
  FeatureTouch feature = FeatureTouch::of_pocket(c, 3, rough, kProbeLength);
  const std::vector<Touch> made = touch_all(feature, rack);
  ASSERT_EQ(made.size(), 5u);
  const std::vector<std::string> labels = {"pocket 3, top face", "pocket 3, wall +X",
                                           "pocket 3, wall -X", "pocket 3, wall +Y",
                                           "pocket 3, wall -Y"};
  for (std::size_t i = 0; i < made.size(); ++i) EXPECT_EQ(made[i].label, labels[i]);
  EXPECT_EQ(made[0].start.x, rough.x);
  EXPECT_EQ(made[0].start.y, rough.y - 20.0) << "the top face where rack_touch.top says";
  EXPECT_EQ(made[1].start.x, rough.x) << "X from the rough position";
  EXPECT_NEAR(made[3].start.x, rack.truth.x, 1e-9) << "Y from the X centre measured";
  EXPECT_NEAR(made[4].start.x, rack.truth.x, 1e-9);
  // The walls are touched with the ball's centre `depth` below the top face found.
  const double top = rack.truth.z - kAboveTop;
  EXPECT_NEAR(made[1].start.z, top - 5.0 - kRadius + kProbeLength, 1e-9);
  EXPECT_EQ(made[1].expected, rough.x + kDiameter / 2.0 - kRadius);
  EXPECT_EQ(made[1].limit, made[1].expected + 5.0) << "search, 5 mm by default";
  EXPECT_EQ(made[2].direction, -1);
}

TEST(RackTouch, shouldRefuseABoreThatMeasuresOffItsDiameter) {
  const Config c = config_of(kBore);
  const Point rough = c.pockets.at(3).at;
  TrueRack rack = true_rack(plus(rough, kShift));
  rack.diameter = 29.2;
  FeatureTouch feature = FeatureTouch::of_pocket(c, 3, rough, kProbeLength);
  touch_all(feature, rack);
  EXPECT_FALSE(feature.found());
  EXPECT_EQ(feature.problem().rfind(
                "pocket 3: the bore measured 29.194 across X, rack_touch.bore_diameter says 30.000 "
                "(tolerance 0.500)",
                0),
            0u)
      << feature.problem();
}

TEST(RackTouch, shouldSayWhatIsMissingBeforeEveryTouchIsMade) {
  const Config c = config_of(kBore);
  FeatureTouch feature = FeatureTouch::of_pocket(c, 3, c.pockets.at(3).at, kProbeLength);
  feature.touched(-0.0);
  EXPECT_FALSE(feature.found());
  EXPECT_EQ(feature.problem(), "pocket 3: 4 touches still to make");
}

TEST(RackTouch, shouldFindAForkByItsJawsAndItsBackWall) {
  // Pockets open toward -X: the jaws are touched across Y, the back wall at +X.
  const Config c = config_of(R"({"pocket_side_offset": {"x": -40.0, "y": 0.0},
    "pockets": {"1": {"y": 20}, "2": {"x": 50, "y": 100}, "3": {"x": 50, "y": 150},
                "4": null, "5": null, "6": null},
    "rack_touch": {"feature": "fork", "stylus_radius": 1.5, "bore_diameter": 30.0,
    "top": {"x": 20, "y": 0}, "pocket_above_top": 10.0, "depth": 5.0}})");
  const Point rough = c.pockets.at(3).at;
  const TrueRack rack = true_rack(plus(rough, kShift));
  FeatureTouch feature = FeatureTouch::of_pocket(c, 3, rough, kProbeLength);
  const std::vector<Touch> made = touch_all(feature, rack);
  ASSERT_EQ(made.size(), 4u);
  EXPECT_EQ(made[1].axis, axis_y);
  EXPECT_EQ(made[2].axis, axis_y);
  EXPECT_EQ(made[3].label, "pocket 3, back wall");
  EXPECT_EQ(made[3].axis, axis_x);
  EXPECT_EQ(made[3].direction, 1) << "away from the opening";
  EXPECT_NEAR(made[3].start.y, rack.truth.y, 1e-9) << "from the middle between the jaws";
  expect_found(feature, rack.truth);
}

TEST(RackTouch, shouldFindAPocketByTwoOutsideFaces) {
  const Config c = config_of(R"({"rack_touch": {"feature": "faces", "stylus_radius": 1.5,
    "top": {"x": 0, "y": -20}, "pocket_above_top": 10.0, "depth": 5.0,
    "x_face": {"x": -22.0, "y": -10.0}, "y_face": {"x": 5.0, "y": -25.0}}})");
  const Point rough = c.pockets.at(3).at;
  TrueRack rack = true_rack(plus(rough, kShift));
  rack.faces = true;
  rack.x_face = {-22.0, -10.0};
  rack.y_face = {5.0, -25.0};
  FeatureTouch feature = FeatureTouch::of_pocket(c, 3, rough, kProbeLength);
  const std::vector<Touch> made = touch_all(feature, rack);
  ASSERT_EQ(made.size(), 3u);
  EXPECT_EQ(made[1].label, "pocket 3, face -X");
  EXPECT_EQ(made[1].direction, 1) << "from outside the face toward the pocket";
  EXPECT_EQ(made[1].start.x, rough.x - 22.0 - 3.0 - kRadius) << "clear + stylus radius outside";
  EXPECT_EQ(made[1].start.y, rough.y - 10.0);
  EXPECT_EQ(made[2].label, "pocket 3, face -Y");
  expect_found(feature, rack.truth);
  EXPECT_FALSE(feature.found()->across);
}

TEST(RackTouch, shouldFindTheDatumAroundItsTaughtPosition) {
  const Config c = config_of(R"({"rack_touch": {"feature": "bore", "stylus_radius": 1.5,
    "bore_diameter": 30.0, "top": {"x": 0, "y": -20}, "pocket_above_top": 10.0, "depth": 5.0,
    "datum": {"pocket": 1, "x": 50.2, "y": 19.9, "z": -80.1}}})");
  FeatureTouch feature = FeatureTouch::of_datum(c, kProbeLength);
  EXPECT_EQ(feature.name(), "the rack datum (pocket 1)");
  const TrueRack rack = true_rack(plus({50.2, 19.9, -80.1}, kShift));
  const std::vector<Touch> made = touch_all(feature, rack);
  EXPECT_EQ(made[1].start.x, 50.2);
  expect_found(feature, rack.truth);
  EXPECT_EQ(feature.found()->pocket, 0) << "the datum teaches no pocket";
  EXPECT_EQ(feature.found()->before.y, 19.9);
}

TEST(RackTouch, shouldProbeOnTheTouchsAxisTowardItsLimitWithTheProbe) {
  const Config c = config_of(R"({"tools": {"9": {"kind": "probe", "probe_feed": 40}},
    "rack_touch": {"feature": "bore", "stylus_radius": 1.5, "bore_diameter": 30.0,
    "top": {"x": 0, "y": -20}, "pocket_above_top": 10.0, "depth": 5.0}})");
  FeatureTouch feature = FeatureTouch::of_pocket(c, 3, c.pockets.at(3).at, kProbeLength);
  feature.touched(-10.0);
  const Touch wall = *feature.next();
  const Step seek = plan::touch_seek(c, wall, 9);
  EXPECT_EQ(seek.kind, StepKind::probe);
  EXPECT_EQ(seek.axes, static_cast<unsigned>(axis_x));
  EXPECT_EQ(seek.target.x, wall.limit);
  EXPECT_EQ(seek.target.y, wall.start.y);
  EXPECT_EQ(seek.feed, c.seek_feed_of(9));
  EXPECT_EQ(seek.pocket, 3);
  EXPECT_TRUE(seek.may_enter_column);
  EXPECT_EQ(seek.held, 9);
  const Step back = plan::touch_back_off(c, wall, 163.0, 9);
  EXPECT_EQ(back.kind, StepKind::feed);
  EXPECT_EQ(back.axes, static_cast<unsigned>(axis_x));
  EXPECT_EQ(back.target.x, 163.0 - c.probe_backoff) << "back against the touch's direction";
  const Step latch = plan::touch_latch(c, wall, 9);
  EXPECT_EQ(latch.feed, c.latch_feed_of(9));
  EXPECT_EQ(latch.target.x, wall.limit);
  EXPECT_EQ(describe(seek).substr(0, 24), "probe      X=168.500 F40");
}

TEST(RackTouch, shouldGoToEachTouchFromSafeZAndLeaveTheFeatureUpToIt) {
  const Config c = config_of(kBore);
  FeatureTouch feature = FeatureTouch::of_pocket(c, 3, c.pockets.at(3).at, kProbeLength);
  feature.touched(-40.0);  // the walls touched below above-clearance
  const Touch wall = *feature.next();
  const std::vector<Step> route = plan::to_touch(c, wall, 3, 9);
  ASSERT_EQ(route.size(), 4u);
  EXPECT_EQ(route[0].target.z, c.safe.z);
  EXPECT_EQ(route[1].axes, static_cast<unsigned>(axis_xy));
  EXPECT_EQ(route[2].target.z, c.pockets.at(3).at.z + c.pocket_above_clearance_offset_z);
  EXPECT_EQ(route[3].kind, StepKind::feed);
  EXPECT_EQ(route[3].target.z, wall.start.z);
  for (const Step& step : route) {
    EXPECT_EQ(step.pocket, 3);
    EXPECT_TRUE(step.may_enter_column);
    EXPECT_EQ(step.held, 9);
  }
  const std::vector<Step> out = plan::leave_feature(c, 3, 9);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].target.z, c.safe.z);
}

TEST(RackTouch, shouldCrossInsideABoreFromOneWallToTheNextStart) {
  const Config c = config_of(kBore);
  FeatureTouch feature = FeatureTouch::of_pocket(c, 3, c.pockets.at(3).at, kProbeLength);
  const Touch top = *feature.next();
  EXPECT_FALSE(top.within);
  feature.touched(-40.0);
  const Touch plus_x = *feature.next();
  EXPECT_EQ(plan::to_next_touch(c, top, plus_x, 9).size(), 4u) << "down into the bore: to_touch";
  feature.touched(163.5);
  const Touch minus_x = *feature.next();
  const std::vector<Step> across = plan::to_next_touch(c, plus_x, minus_x, 9);
  ASSERT_EQ(across.size(), 1u);
  EXPECT_EQ(across[0].kind, StepKind::feed);
  EXPECT_EQ(across[0].axes, static_cast<unsigned>(axis_xy));
  EXPECT_EQ(across[0].target.x, minus_x.start.x);
  EXPECT_EQ(across[0].target.y, minus_x.start.y);
  EXPECT_EQ(across[0].feed, c.pocket_feed);
  EXPECT_EQ(across[0].label, "across to the start of pocket 3, wall -X");
  EXPECT_TRUE(across[0].may_enter_column);
  EXPECT_EQ(across[0].held, 9);
}

TEST(RackTouch, shouldLeaveAFaceUpToSafeZBeforeTheNext) {
  const Config c = config_of(R"({"rack_touch": {"feature": "faces", "stylus_radius": 1.5,
    "top": {"x": 0, "y": -20}, "pocket_above_top": 10.0, "depth": 5.0,
    "x_face": {"x": -22.0, "y": -10.0}, "y_face": {"x": 5.0, "y": -25.0}}})");
  FeatureTouch feature = FeatureTouch::of_pocket(c, 3, c.pockets.at(3).at, kProbeLength);
  feature.touched(-40.0);
  const Touch x_face = *feature.next();
  feature.touched(126.0);
  const Touch y_face = *feature.next();
  EXPECT_FALSE(x_face.within);
  EXPECT_EQ(plan::to_next_touch(c, x_face, y_face, 9).front().target.z, c.safe.z)
      << "around the rack's corner, not through it";
}

TEST(RackTouch, shouldShowOldAndNewSideBySideWithTheDifference) {
  const Config c = config_of(kBore);
  Found found{"pocket 3", 3, {150.0, 20.0, -80.0}, {150.412, 19.73, -79.87}, 30.004};
  EXPECT_EQ(found_lines(c, {found}).at(0),
            "pocket 3   X 150.000 → 150.412 (+0.412)   Y 20.000 → 19.730 (-0.270)   "
            "Z -80.000 → -79.870 (+0.130)   across 30.004");
}

TEST(RackTouch, shouldSayTheDatumIsWithinOrBeyondItsTolerance) {
  const Config c = config_of(kBore);
  const Drift near = drift_of(c, {50.0, 20.0, -80.0}, {50.02, 19.99, -80.0});
  EXPECT_TRUE(near.within);
  EXPECT_EQ(near.words,
            "the rack datum is within 0.02 mm of where it was taught (tolerance 0.10)");
  const Drift far = drift_of(c, {50.0, 20.0, -80.0}, {50.62, 20.1, -80.05});
  EXPECT_FALSE(far.within);
  EXPECT_EQ(far.axis, 'X');
  EXPECT_NEAR(far.worst, 0.62, 1e-9);
  EXPECT_EQ(far.words,
            "the rack datum is 0.62 mm off in X (tolerance 0.10): re-teach or check the rack");
}

TEST(RackTouch, shouldSayTheDriftInInches) {
  auto json = nlohmann::ordered_json::parse(test::sample_config_with(kBore));
  json["units"] = "inch";
  json["rack_touch"]["stylus_radius"] = 0.06;
  json["rack_touch"]["bore_diameter"] = 1.2;
  json["rack_touch"]["depth"] = 0.2;
  const ConfigResult parsed = parse_config(json.dump());
  ASSERT_TRUE(parsed.config) << parsed.errors.front();
  const Drift far = drift_of(*parsed.config, {2.0, 0.8, -3.0}, {2.0, 0.7756, -3.0});
  EXPECT_FALSE(far.within);
  EXPECT_EQ(far.words,
            "the rack datum is 0.0244 inch off in Y (tolerance 0.0040): re-teach or check the "
            "rack");
  EXPECT_TRUE(drift_of(*parsed.config, {2.0, 0.8, -3.0}, {2.0, 0.8, -3.003}).within);
}

}  // namespace
}  // namespace fatc
