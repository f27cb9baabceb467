#include "core/rack/geometry.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "core/dry_run/simulator.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

Step rapid(unsigned axes, Point target, int pocket = 0, bool may_enter_column = false) {
  Step step;
  step.kind = StepKind::rapid;
  step.axes = axes;
  step.target = target;
  step.pocket = pocket;
  step.may_enter_column = may_enter_column;
  return step;
}

TEST(Waypoints, shouldOffsetSideAndHeightsFromThePocket) {
  const auto w = pocket_waypoints(test::valid_config(), 3);
  EXPECT_EQ(w.pocket.x, 150.0);
  EXPECT_EQ(w.pocket.y, 20.0);
  EXPECT_EQ(w.side.y, 60.0);
  EXPECT_EQ(w.side.z, -80.0);
  EXPECT_EQ(w.above_chuck.z, -60.0);
  EXPECT_EQ(w.above_clearance.z, -20.0);
}

TEST(KeepOut, shouldAcceptEveryPlannedSequenceOfTheValidConfig) {
  const Config config = test::valid_config();
  for (const auto& [tool, pocket] : config.pockets) {
    EXPECT_TRUE(check_steps(config, plan_change(config, 0, tool, config.probe_limit.z).steps(), std::nullopt).empty());
    EXPECT_TRUE(check_steps(config, plan_change(config, tool, 0, config.probe_limit.z).steps(), std::nullopt).empty());
  }
}

TEST(KeepOut, shouldFlagAMoveAcrossAnotherPocket) {
  const Config config = test::valid_config();
  const std::vector<Step> steps = {rapid(axis_xyz, {50, 60, -50}),
                                   rapid(axis_xy, {150, 60, -50}),   // beside the rack: fine
                                   rapid(axis_xy, {150, 0, -50})};   // through pocket 3's column
  const auto violations = check_steps(config, steps, std::nullopt);
  ASSERT_EQ(violations.size(), 1u);
  EXPECT_EQ(violations[0].step, 2u);
  EXPECT_EQ(violations[0].what, "passes through the rack at pocket 3");
}

TEST(KeepOut, shouldAllowOnlyTheApproachIntoTheServedPocket) {
  const Config config = test::valid_config();
  std::vector<Step> steps = {rapid(axis_xyz, {100, 60, -80}), rapid(axis_xy, {100, 20, -80}, 2, true)};
  EXPECT_TRUE(check_steps(config, steps, std::nullopt).empty());
  steps[1].may_enter_column = false;
  const auto violations = check_steps(config, steps, std::nullopt);
  ASSERT_EQ(violations.size(), 1u);
  EXPECT_EQ(violations[0].what, "passes through the rack at pocket 2 outside its approach");
}

TEST(KeepOut, shouldFlagASafeZTooLowToCrossTheRack) {
  Config config = test::valid_config();
  config.safe.z = -40.0;  // below the above-clearance height of -20
  const auto violations = check_steps(config, plan_change(config, 0, 1, config.probe_limit.z).steps(), std::nullopt);
  EXPECT_FALSE(violations.empty());
}

TEST(KeepOut, shouldAllowTouchingTheTopOfAColumn) {
  const Config config = test::valid_config();
  const std::vector<Step> steps = {rapid(axis_xyz, {0, 20, -20}), rapid(axis_xy, {350, 20, -20})};
  EXPECT_TRUE(check_steps(config, steps, std::nullopt).empty());
}

TEST(SoftLimits, shouldFlagATargetOutsideTheLimits) {
  const Config config = test::valid_config();
  const SoftLimits limits{{0, 400}, {0, 300}, {-85, 0}};
  const auto violations = check_steps(config, {rapid(axis_z, {0, 0, -90})}, limits);
  ASSERT_EQ(violations.size(), 1u);
  EXPECT_EQ(violations[0].what, "Z=-90.000 is outside the soft limits -85.000 .. 0.000");
}

TEST(SoftLimits, shouldNameHugeLimitsInFull) {
  // LinuxCNC takes limits up to 1e99: a message cut by a buffer would name limits the INI has not.
  const Config config = test::valid_config();
  const SoftLimits limits{{0, 400}, {0, 300}, {-1e99, -1e98}};
  const auto violations = check_steps(config, {rapid(axis_z, {0, 0, -90})}, limits);
  ASSERT_EQ(violations.size(), 1u);
  char min[160], max[160];
  std::snprintf(min, sizeof min, "%.3f", -1e99);
  std::snprintf(max, sizeof max, "%.3f", -1e98);
  EXPECT_EQ(violations[0].what,
            std::string("Z=-90.000 is outside the soft limits ") + min + " .. " + max);
}

TEST(SoftLimits, shouldAcceptEveryPlannedStepWithinGenerousLimits) {
  const Config config = test::valid_config();
  const SoftLimits limits{{-10, 400}, {-10, 300}, {-120, 0}};
  EXPECT_TRUE(check_steps(config, plan_change(config, 2, 5, config.probe_limit.z).steps(), limits).empty());
  EXPECT_TRUE(check_steps(config, plan_load(config, 4, 0, -70).steps(), limits).empty());
}

}  // namespace
}  // namespace fatc
