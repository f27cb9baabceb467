// Touching the rack (docs/sequences.md#teach-by-touch): the probe in the
// spindle teaches pockets by touch, the rack datum is taught and checked,
// and M6 is refused while the rack moved or a check is due.
#include <gtest/gtest.h>

#include <cmath>

#include "core/config/config.hpp"
#include "core/dry_run/simulator.hpp"
#include "core/machine/changer.hpp"
#include "sim_rig.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

constexpr int kProbe = 9;
constexpr double kProbeLength = 80.0;
constexpr double kRadius = 1.5;
constexpr double kAboveTop = 10.0;

/// Bores of 30 mm, the datum pocket 1's, a probe T9 (80 mm) in the spindle.
std::string touch_config(const char* more = "") {
  std::string patch = std::string(R"({"tools": {"9": {"kind": "probe"}}, "rack_touch": {
    "feature": "bore", "stylus_radius": 1.5, "bore_diameter": 30.0, "top": {"x": 0, "y": -20},
    "pocket_above_top": 10.0, "depth": 5.0, "datum": {"pocket": 1})") + more + "}}";
  return test::sample_config_with(patch.c_str());
}

Config parsed(const std::string& text) {
  const ConfigResult result = parse_config(text);
  if (!result.config) ADD_FAILURE() << result.errors.front();
  return result.config.value_or(Config{});
}

/// The probe in the spindle, pockets 1 and 3 emptied (their bores are touched).
ToolState probe_in_spindle(const Config& config) {
  ToolState tools = ToolState::fresh(config);
  tools.pockets[1] = {};
  tools.pockets[3] = {};
  tools.spindle = kProbe;
  tools.lengths[kProbe] = kProbeLength;
  return tools;
}

double on(const Point& p, unsigned axis) {
  return axis == axis_x ? p.x : axis == axis_y ? p.y : p.z;
}

/// The simulated rack: every pocket `shift` away from where config.json puts it.
struct TouchRig : test::SimRig {
  explicit TouchRig(const Config& c) : SimRig(c, probe_in_spindle(c)) {
    sim.touches = [this](const Step& probe) { return trip(probe); };
  }
  Point shift;
  bool rack_there = true;

  /// Where the nose trips on `probe`, starting where the simulated spindle stands.
  std::optional<double> trip(const Step& probe) const {
    if (!rack_there) return std::nullopt;
    const Point& from = sim.rack.at;
    // The pocket whose bore the probe is over: the nearest.
    const Pocket* nearest = nullptr;
    double best = 1e9;
    for (const auto& [number, pocket] : config.pockets) {
      const double d = std::hypot(pocket.at.x + shift.x - from.x, pocket.at.y + shift.y - from.y);
      if (d < best) best = d, nearest = &pocket;
    }
    const Point truth{nearest->at.x + shift.x, nearest->at.y + shift.y, nearest->at.z + shift.z};
    if (probe.axes == axis_z) return truth.z - kAboveTop + kProbeLength;
    const unsigned axis = probe.axes;
    const unsigned other = axis == axis_x ? axis_y : axis_x;
    const double direction = on(probe.target, axis) > on(from, axis) ? 1.0 : -1.0;
    const double room = 15.0 - kRadius;
    const double aside = on(from, other) - on(truth, other);
    return on(truth, axis) + direction * std::sqrt(room * room - aside * aside);
  }
};

TEST(TeachByTouch, shouldFindThePocketShowItBesideTheConfigAndWriteItOnlyOnContinue) {
  TouchRig rig(parsed(touch_config()));
  rig.shift = {0.41, -0.27, 0.13};
  rig.changer->request(TouchRequest{TouchRequest::Goal::pockets, {3}});
  rig.run();
  const Status shown = rig.changer->status();
  ASSERT_EQ(shown.phase, Phase::touching);
  ASSERT_TRUE(shown.awaits_operator()) << shown.activity;
  EXPECT_NE(shown.activity.find("pocket 3"), std::string::npos) << shown.activity;
  EXPECT_NE(shown.activity.find("Continue to write"), std::string::npos) << shown.activity;
  EXPECT_TRUE(rig.sim.written.empty()) << "nothing written before the operator accepts";

  rig.changer->operator_continue();
  const test::Lines rest = rig.run();
  ASSERT_EQ(rig.sim.written.size(), 1u);
  const Found& found = rig.sim.written.front();
  EXPECT_EQ(found.pocket, 3);
  const Point& configured = rig.config.pockets.at(3).at;
  EXPECT_NEAR(found.at.x, configured.x + 0.41, 1e-6);
  EXPECT_NEAR(found.at.y, configured.y - 0.27, 1e-6);
  EXPECT_NEAR(found.at.z, configured.z + 0.13, 1e-6);
  EXPECT_FALSE(rig.sim.written_datum);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rest.back(), "done T9");
  EXPECT_EQ(rig.changer->tools(), rig.tools) << "touching records nothing in the tool state";
}

TEST(TeachByTouch, shouldTouchOnlyAtTheProbesOwnFeedsAndTheLatchSlowest) {
  TouchRig rig(parsed(touch_config()));
  rig.changer->request(TouchRequest{TouchRequest::Goal::pockets, {3}});
  rig.run();
  int probes = 0;
  for (const Step& step : rig.sim.steps()) {
    if (step.kind != StepKind::probe) continue;
    ++probes;
    EXPECT_TRUE(step.feed == rig.config.seek_feed_of(kProbe) ||
                step.feed == rig.config.latch_feed_of(kProbe))
        << describe(step);
  }
  EXPECT_EQ(probes, 10) << "the top face and four walls, each a seek and a latch";
}

TEST(TeachByTouch, shouldWriteNothingWhenTheOperatorCancels) {
  TouchRig rig(parsed(touch_config()));
  rig.changer->request(TouchRequest{TouchRequest::Goal::pockets, {3}});
  rig.run();
  rig.changer->operator_cancel();
  rig.run();
  EXPECT_TRUE(rig.sim.written.empty());
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rig.last_message(), "touching cancelled by the operator: nothing written");
}

TEST(TeachByTouch, shouldBackOutAndSayHowFarItWentWhenTheProbeFindsNothing) {
  TouchRig rig(parsed(touch_config()));
  rig.rack_there = false;
  rig.changer->request(TouchRequest{TouchRequest::Goal::pockets, {3}});
  const test::Lines lines = rig.run();
  EXPECT_EQ(rig.changer->status().phase, Phase::idle) << "no fault: nothing is uncertain";
  EXPECT_TRUE(rig.sim.written.empty());
  const std::string said = rig.last_message();
  EXPECT_NE(said.find("pocket 3, top face: no touch within"), std::string::npos) << said;
  EXPECT_NE(said.find("travelled"), std::string::npos) << said;
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines.back().rfind("fail", 0), 0u) << "the executor ends the MDI run failed: "
                                               << lines.back();
}

TEST(TeachByTouch, shouldBackOutAndSayItWhenTheOperatorCancelsATouch) {
  TouchRig rig(parsed(touch_config()));
  rig.changer->request(TouchRequest{TouchRequest::Goal::pockets, {3}});
  for (int i = 0; i < 50 && rig.changer->status().awaiting != Awaiting::probe; ++i) {
    rig.sim.run(*rig.changer, 1);
  }
  ASSERT_EQ(rig.changer->status().awaiting, Awaiting::probe);
  rig.changer->operator_cancel();
  rig.run();
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_TRUE(rig.sim.written.empty());
  EXPECT_EQ(rig.last_message(),
            "pocket 3, top face: the touch was cancelled by the operator; nothing written");
}

TEST(TeachByTouch, shouldBeRefusedWithoutAProbeInTheSpindleOrWithAToolInTheBore) {
  const Config config = parsed(touch_config());
  ToolState tools = probe_in_spindle(config);
  tools.spindle = 0;
  test::SimRig empty(config, tools);
  empty.changer->request(TouchRequest{TouchRequest::Goal::pockets, {3}});
  empty.run();
  EXPECT_NE(empty.last_message().find("the spindle is empty: put the probe"), std::string::npos)
      << empty.last_message();

  TouchRig full(config);
  full.changer->request(TouchRequest{TouchRequest::Goal::pockets, {2}});
  full.run();
  EXPECT_NE(full.last_message().find("pocket 2 holds tool 2"), std::string::npos)
      << full.last_message();
  EXPECT_EQ(full.changer->status().phase, Phase::idle);
}

TEST(TeachByTouch, shouldTouchEveryEmptyPocketWhenNoneIsNamed) {
  TouchRig rig(parsed(touch_config()));
  rig.changer->request(TouchRequest{});
  rig.run();
  rig.changer->operator_continue();
  rig.run();
  ASSERT_EQ(rig.sim.written.size(), 2u);
  EXPECT_EQ(rig.sim.written[0].pocket, 1);
  EXPECT_EQ(rig.sim.written[1].pocket, 3);
}

/// A config whose datum (pocket 1) was taught where the simulated rack stands.
Config with_datum(const char* more = "") {
  Config config = parsed(touch_config(more));
  config.rack_touch->datum = config.pockets.at(1).at;
  return config;
}

TEST(RackDatum, shouldSayWithinToleranceAndCountFromZero) {
  TouchRig rig(with_datum(R"(, "check_every_changes": 5)"));
  rig.shift = {0.03, 0.0, 0.0};
  rig.changer->request(TouchRequest{TouchRequest::Goal::check_datum, {}});
  rig.run();
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_NE(rig.last_message().find("within"), std::string::npos) << rig.last_message();
  EXPECT_FALSE(rig.changer->datum_refusal());
  EXPECT_TRUE(rig.sim.written.empty()) << "a check never writes";
}

TEST(RackDatum, shouldRefuseM6WhenTheRackMovedUntilTheOperatorClearsIt) {
  TouchRig rig(with_datum());
  rig.shift = {0.62, 0.0, 0.0};
  rig.changer->request(TouchRequest{TouchRequest::Goal::check_datum, {}});
  rig.run();
  const std::string words = rig.last_message();
  EXPECT_EQ(words.rfind("the rack datum is 0.62", 0), 0u) << words;
  EXPECT_NE(words.find("off in X (tolerance 0.10"), std::string::npos) << words;
  EXPECT_EQ(rig.changer->tools().datum.drift, words) << "kept in the state file";
  EXPECT_TRUE(rig.sim.written.empty()) << "never rewrites pockets on its own";

  rig.changer->tool_change(2);
  rig.run();
  EXPECT_NE(rig.last_message().find("M6 is refused until"), std::string::npos)
      << rig.last_message();
  EXPECT_EQ(rig.changer->tools().spindle, kProbe);

  EXPECT_FALSE(rig.changer->clear_datum_drift());
  EXPECT_FALSE(rig.changer->datum_refusal());
  EXPECT_TRUE(rig.changer->clear_datum_drift()) << "nothing left to clear";
}

TEST(RackDatum, shouldFallDueAfterItsChangesAndStillLetTheProbeBeFetched) {
  const Config config = with_datum(R"(, "check_every_changes": 2)");
  ToolState tools = ToolState::fresh(config);
  test::SimRig rig(config, tools);
  rig.changer->tool_change(1);
  rig.run();
  rig.changer->tool_change(2);
  rig.run();
  EXPECT_EQ(rig.changer->tools().datum.changes, 2);
  rig.changer->tool_change(3);
  rig.run();
  EXPECT_NE(rig.last_message().find("the rack datum check is due: 2 changes since the last"),
            std::string::npos)
      << rig.last_message();
  EXPECT_EQ(rig.changer->tools().spindle, 2);
}

TEST(RackDatum, shouldBeDueAtStartWhenTheConfigSaysSo) {
  const Config config = with_datum(R"(, "check_at_start": true)");
  test::SimRig rig(config, ToolState::fresh(config));
  ASSERT_TRUE(rig.changer->datum_refusal());
  EXPECT_NE(rig.changer->datum_refusal()->find("due at start"), std::string::npos);
}

TEST(RackDatum, shouldKeepItsWatchInTheStateFile) {
  ToolState tools;
  tools.datum.changes = 7;
  tools.datum.drift = "the rack datum is 0.62 mm off in X (tolerance 0.10): re-teach or check the rack";
  const ToolStateResult read = tool_state_from_json(to_json(tools));
  ASSERT_TRUE(read.state) << read.error;
  EXPECT_EQ(read.state->datum, tools.datum);
  EXPECT_EQ(to_json(ToolState{}).find("datum"), std::string::npos)
      << "a state file without a datum stays as it was";
  EXPECT_EQ(tool_state_from_json(R"({"version": 2, "spindle": 0, "uncertain": false,
      "pockets": {}, "lengths": {}, "datum": {"changes": -1}})").error,
            "datum.changes: expected a count from 0 to 1000000000, got -1");
}

}  // namespace
}  // namespace fatc
