// A change in the air: any sequence flown above the rack at the operator's
// feed, nothing taken, handed or measured, the keep-out still holding.
#include "core/dry_run/air_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>

#include "core/config/rack_volume.hpp"
#include "core/dry_run/dry_run.hpp"
#include "core/dry_run/simulator.hpp"
#include "sim_rig.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::valid_config;

const AirSettings kAir{30.0, 1000.0};

/// The lowest the nose may be over the rack part around `at`, in an air run
/// `air.height` high; none where `at` is over no part.
std::optional<double> floor_over(const Config& config, const Point& at, const AirSettings& air) {
  for (const RackPart& part : rack_volume(config)) {
    const Box& b = part.box;
    if (at.x > b.low.x && at.x < b.high.x && at.y > b.low.y && at.y < b.high.y) {
      return b.high.z + air.height;
    }
  }
  return std::nullopt;
}

/// Every move of `route`, from `start`, stays at or above the air floor while
/// over the rack, runs at the air feed, and nothing but moves is in it.
void expect_in_the_air(const Config& config, const std::vector<Step>& route, const Point& start,
                       const AirSettings& air) {
  ASSERT_FALSE(route.empty());
  Point at = start;
  for (std::size_t i = 0; i < route.size(); ++i) {
    const Step& move = route[i];
    EXPECT_EQ(move.kind, StepKind::feed) << i << ": " << move.label;
    EXPECT_DOUBLE_EQ(move.feed, air.feed) << i << ": " << move.label;
    EXPECT_TRUE(move.before.empty());
    const Point from = at;
    at = moved_to(at, move);
    // Both ends: a straight move between two points above the floor stays above it.
    for (const Point& p : {from, at}) {
      if (const auto floor = floor_over(config, p, air)) {
        EXPECT_GE(p.z, *floor - 1e-9) << i << ": " << move.label << " at X" << p.x << " Y" << p.y;
      }
    }
  }
}

struct Sequence {
  const char* name;
  int spindle;
  std::function<void(Changer&)> request;
};

std::vector<Sequence> sequences() {
  return {{"M6 T3 from T1", 1, [](Changer& c) { c.tool_change(3); }},
          {"M6 T5 from empty", 0, [](Changer& c) { c.tool_change(5); }},
          {"unload T2", 2, [](Changer& c) { c.unload(2); }},
          {"verify 4", 0, [](Changer& c) { c.verify(4); }}};
}

Config with(const char* patch) { return *parse_config(test::sample_config_with(patch)).config; }

TEST(AirRun, shouldKeepEveryMoveOverTheRackAboveItsTopPlusTheHeight) {
  for (const Config& config : {valid_config(), with(R"({"path": "direct"})"),
                               with(R"({"pocket_default": {"approach": "top"}})")}) {
    for (const Sequence& s : sequences()) {
      ToolState tools = with_in_spindle(config, s.spindle);
      if (std::string(s.name) == "verify 4") tools.pockets[4] = {};
      const AirPlan plan =
          plan_air_run(config, tools, config.safe, axis_xyz, s.request, s.name, kAir);
      ASSERT_TRUE(plan.request) << s.name << ": " << plan.refused;
      SCOPED_TRACE(s.name);
      expect_in_the_air(config, plan.request->route, config.safe, kAir);
    }
  }
}

TEST(AirRun, shouldLeaveOutTheProbeTheChuckAndTheToolCommands) {
  const Config config = with(R"({"probe_after_change": "always"})");
  const ToolState tools = with_in_spindle(config, 1);
  const Simulator real = plan_from(config, tools, config.safe, axis_xyz,
                                   [](Changer& c) { c.tool_change(3); });
  bool probes = false;
  for (const Step& step : real.steps()) probes = probes || step.kind == StepKind::probe;
  ASSERT_TRUE(probes) << "the real change measures";
  const AirPlan plan = plan_air_run(config, tools, config.safe, axis_xyz,
                                    [](Changer& c) { c.tool_change(3); }, "M6 T3", kAir);
  ASSERT_TRUE(plan.request) << plan.refused;
  for (const Step& step : plan.request->route) EXPECT_EQ(step.kind, StepKind::feed);
  EXPECT_EQ(plan.request->name, "air run of M6 T3, 30 mm above the rack at F1000");
}

TEST(AirRun, shouldStayAboveTheTouchOffSensorWhereTheLoadWouldMeasure) {
  // The real load probes down from loading Z, backs off the sensor and
  // retracts from it: in the air nothing goes below where the probe started.
  const Config config = valid_config();
  ToolState tools = with_in_spindle(config, 0);
  tools.pockets[2] = {};
  const auto load = [](Changer& c) { c.load(30, 2); };
  const Simulator real = plan_from(config, tools, config.safe, axis_xyz, load);
  bool backs_off = false;
  for (const Step& step : real.steps()) backs_off = backs_off || step.label == "back off the sensor";
  ASSERT_TRUE(backs_off) << "the real load measures on the sensor";
  const AirPlan plan = plan_air_run(config, tools, config.safe, axis_xyz, load, "load", kAir);
  ASSERT_TRUE(plan.request) << plan.refused;
  Point at = config.safe;
  for (const Step& move : plan.request->route) {
    at = moved_to(at, move);
    const bool over_sensor =
        std::abs(at.x - config.probe_limit.x) < 1e-9 && std::abs(at.y - config.probe_limit.y) < 1e-9;
    if (over_sensor) {
      EXPECT_GE(at.z, config.loading.z - 1e-9) << move.label;
    }
  }
  expect_in_the_air(config, plan.request->route, config.safe, kAir);
}

TEST(AirRun, shouldFlyWithoutTouchingTheChuckOrTheBelief) {
  const Config config = valid_config();
  const ToolState tools = with_in_spindle(config, 1);
  test::SimRig rig(config, tools);
  const AirPlan plan = plan_air_run(config, tools, config.safe, axis_xyz,
                                    [](Changer& c) { c.tool_change(3); }, "M6 T3", kAir);
  ASSERT_TRUE(plan.request) << plan.refused;
  rig.changer->request(*plan.request);
  EXPECT_EQ(rig.changer->status().phase, Phase::air_run);
  EXPECT_TRUE(rig.changer->status().over_mdi);
  const test::Lines lines = rig.run();
  ASSERT_FALSE(lines.empty());
  for (const std::string& line : lines) {
    EXPECT_TRUE(line.rfind("feed ", 0) == 0 || line == "done T1") << line;
  }
  EXPECT_EQ(lines.back(), "done T1") << "LinuxCNC's tool stays the one the spindle holds";
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rig.changer->tools(), tools) << "an air run records nothing";
  EXPECT_EQ(rig.last_message(), "air run of M6 T3, 30 mm above the rack at F1000 done: " +
                                    std::to_string(plan.request->route.size()) +
                                    " moves, nothing taken or recorded");
}

TEST(AirRun, shouldStopWithoutAFaultWhenLinuxCncAborts) {
  const Config config = valid_config();
  const ToolState tools = with_in_spindle(config, 1);
  test::SimRig rig(config, tools);
  const AirPlan plan = plan_air_run(config, tools, config.safe, axis_xyz,
                                    [](Changer& c) { c.tool_change(3); }, "M6 T3", kAir);
  ASSERT_TRUE(plan.request);
  rig.changer->request(*plan.request);
  rig.changer->abort("the program was stopped");
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rig.changer->tools(), tools);
  EXPECT_EQ(rig.last_message(),
            "air run of M6 T3, 30 mm above the rack at F1000 stopped (the program was stopped); "
            "nothing was recorded. The spindle may be in the rack: jog it out the way it came in "
            "before the next change");
}

TEST(AirRun, shouldBeRefusedInOneLineForAHeightOrFeedOfNothing) {
  const Config config = valid_config();
  const ToolState tools = with_in_spindle(config, 1);
  const auto change = [](Changer& c) { c.tool_change(3); };
  EXPECT_EQ(plan_air_run(config, tools, config.safe, axis_xyz, change, "M6 T3", {0.0, 1000.0})
                .refused,
            "air run of M6 T3, 0 mm above the rack at F1000 refused: air height 0: expected a "
            "height above the rack in mm, more than 0");
  EXPECT_EQ(plan_air_run(config, tools, config.safe, axis_xyz, change, "M6 T3", {30.0, -5.0})
                .refused,
            "air run of M6 T3, 30 mm above the rack at F-5 refused: air feed -5: expected a feed "
            "in mm/min, more than 0 (0: the config's verify feed, F500)");
}

TEST(AirRun, shouldBeRefusedWithTheReasonTheSequenceItselfWouldBe) {
  const Config config = valid_config();
  const ToolState tools = with_in_spindle(config, 1);
  const AirPlan plan = plan_air_run(config, tools, config.safe, axis_xyz,
                                    [](Changer& c) { c.unload(9); }, "unload of tool 9", kAir);
  EXPECT_FALSE(plan.request);
  EXPECT_EQ(plan.refused,
            "air run of unload of tool 9, 30 mm above the rack at F1000 refused: tool 9 is not in "
            "the rack");
}

TEST(AirRun, shouldBeRefusedWhereTheToolInTheSpindleWouldReachIntoTheRack) {
  // The spindle really holds T1, 200 mm long, all the way: the keep-out
  // counts it, though the sequence flown would have put it away.
  const Config config = valid_config();
  const ToolState tools = with_in_spindle(config, 1);
  test::SimRig rig(config, tools);
  DryRun dry_run;
  ToolLengths lengths;
  lengths.table[1] = 200.0;
  lengths.longest = 250.0;
  rig.changer->keepout_lengths(lengths);
  rig.changer->rehearse_with(&dry_run);
  const AirPlan plan = plan_air_run(config, tools, config.safe, axis_xyz,
                                    [](Changer& c) { c.tool_change(3); }, "M6 T3", kAir);
  ASSERT_TRUE(plan.request);
  rig.changer->request(*plan.request);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_TRUE(rig.run().empty()) << "nothing moved";
  EXPECT_NE(rig.last_message().find("refused"), std::string::npos) << rig.last_message();
}

TEST(AirRun, shouldBeRefusedWhereTheSpindlesToolWouldHangBelowTheRacksTop) {
  // Over its own empty pocket a return may put T1's tip into the holder; in
  // the air T1 stays in the spindle over every pocket, full ones too.
  const Config config = valid_config();
  test::SimRig rig(config, with_in_spindle(config, 1));
  ToolLengths lengths;
  lengths.table[1] = 40.0;
  lengths.longest = 100.0;
  rig.changer->keepout_lengths(lengths);
  AirAsk ask;
  ask.tool = 3;
  ask.air = {30.0, 1000.0};
  EXPECT_EQ(plan_air_run(*rig.changer, ask, config.safe).refused,
            "air run of M6 T3 with T1, 30 mm above the rack at F1000 refused: T1 in the spindle "
            "(40 mm) would hang 10 mm below the rack's top: fly at least 40 mm above it, or empty "
            "the spindle");
  ask.air.height = 40.0;
  EXPECT_TRUE(plan_air_run(*rig.changer, ask, config.safe).request);
  ask.from = 0;  // flown as if empty: the real T1 still counts
  ask.air.height = 30.0;
  EXPECT_FALSE(plan_air_run(*rig.changer, ask, config.safe).request);
}

TEST(AirRun, shouldPlanAsIfTheNamedToolWereInTheSpindle) {
  const Config config = valid_config();
  const ToolState empty = with_in_spindle(config, 0);
  const ToolState holding = as_if_holding(config, empty, 2);
  EXPECT_EQ(holding.spindle, 2);
  EXPECT_FALSE(holding.holds(2));
  const ToolState back = as_if_holding(config, holding, 0);
  EXPECT_EQ(back, empty);
}

}  // namespace
}  // namespace fatc
