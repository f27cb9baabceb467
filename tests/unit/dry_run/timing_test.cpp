// The motion and time model of src/core/dry_run/timing.hpp: each move as an
// exact stop with a trapezoidal profile, the bound at the machine's limits,
// and the estimate --plan and --lint print (LinuxCNC's planner, the dwells, the
// changer's costs per step and per change). Each figure worked out by hand.
#include "core/dry_run/timing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>

#include "core/dry_run/simulator.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

/// A move as the changer publishes it, into a plan of the test's own.
void publish_move(Simulator& plan, StepKind kind, unsigned axes, Point target, double feed) {
  Step step;
  step.kind = kind;
  step.axes = axes;
  step.target = target;
  step.feed = feed;
  plan.publish(step);
}

void publish_done(Simulator& plan) {
  Step step;
  step.kind = StepKind::done;
  plan.publish(step);
}

/// Every axis at `velocity` and `acceleration`, no linear limits of their own.
MotionLimits limits_of(double velocity, double acceleration) {
  MotionLimits limits;
  limits.velocity = {velocity, velocity, velocity};
  limits.acceleration = {acceleration, acceleration, acceleration};
  limits.linear_velocity = std::numeric_limits<double>::infinity();
  limits.linear_acceleration = std::numeric_limits<double>::infinity();
  return limits;
}

/// config/sim/fixed_atc_sim.ini: every axis and [TRAJ] at 200 mm/s and 2000 mm/s².
MotionLimits simulated_mill() {
  MotionLimits limits = limits_of(200, 2000);
  limits.linear_velocity = 200;
  limits.linear_acceleration = 2000;
  return limits;
}

// ---- one move ----

TEST(MoveSeconds, shouldTakeATrapezoidWhenTheMoveReachesFullSpeed) {
  // 100 at 10/s with 10/s²: 1 s up, 8 s at speed, 1 s down.
  EXPECT_NEAR(move_seconds({0, 0, 0}, {100, 0, 0}, 0.0, limits_of(10, 10)), 11.0, 1e-9);
  EXPECT_NEAR(trapezoid_seconds(100, 10, 10), 11.0, 1e-9);
}

TEST(MoveSeconds, shouldTakeATriangleWhenTheMoveIsTooShortForFullSpeed) {
  // 4 with 1/s²: 2 s up to 2/s, 2 s down, never at 10/s.
  EXPECT_NEAR(move_seconds({0, 0, 0}, {0, 0, 4}, 0.0, limits_of(10, 1)), 4.0, 1e-9);
}

TEST(MoveSeconds, shouldHoldAFeedBelowTheMachinesSpeed) {
  // 100 at F600 (10/s) on a 100/s machine with 10/s²: 10 s + 1 s.
  EXPECT_NEAR(move_seconds({0, 0, 0}, {0, 100, 0}, 600.0, limits_of(100, 10)), 11.0, 1e-9);
}

TEST(MoveSeconds, shouldLetTheSlowestAxisAndTheLinearLimitsDecide) {
  MotionLimits limits = limits_of(100, 1000);
  limits.velocity.z = 10;  // a slow Z: along X and Z at once, Z's share decides
  // 30 along X, 40 along Z: Z has 0.8 of the move, so at most 12.5/s along it.
  const double diagonal = move_seconds({0, 0, 0}, {30, 0, 40}, 0.0, limits);
  EXPECT_NEAR(diagonal, 50.0 / 12.5 + 12.5 / (1000 / 0.8), 1e-9);
  limits.linear_velocity = 5;
  EXPECT_NEAR(move_seconds({0, 0, 0}, {30, 0, 40}, 0.0, limits), 50.0 / 5 + 5 / 1250.0, 1e-9);
  EXPECT_EQ(move_seconds({1, 2, 3}, {1, 2, 3}, 0.0, limits), 0.0);
}

TEST(MoveSeconds, shouldTakeNoTimeWithoutALimitToMoveAt) {
  EXPECT_EQ(trapezoid_seconds(10, 0, 10), 0.0);
  EXPECT_EQ(trapezoid_seconds(10, 10, 0), 0.0);
  EXPECT_EQ(trapezoid_seconds(10, std::nan(""), 10), 0.0);
}

// ---- as LinuxCNC plans it ----

TEST(PlannerLimits, shouldKeepTheVelocitiesAndTheAxesAccelerationsOfAnExactStop) {
  MotionLimits limits = simulated_mill();
  limits.velocity.z = 30;
  limits.acceleration.z = 200;
  const MotionLimits planned = planner_limits(limits);
  EXPECT_EQ(planned.velocity.z, 30);
  EXPECT_EQ(planned.linear_velocity, 200);
  EXPECT_EQ(planned.acceleration.x, 2000);
  EXPECT_EQ(planned.acceleration.z, 200);
  EXPECT_TRUE(std::isinf(planned.linear_acceleration));
}

TEST(PlannerLimits, shouldTimeARapidOfTheSimulatedMillAsLinuxCncRanIt) {
  // 20 mm along Z with 2000 mm/s²: never at 200 mm/s (that needs 20 mm of
  // ramps and no cruise); a triangle of 2 √(20 / 2000) = 0.2 s.
  const MotionLimits planned = planner_limits(simulated_mill());
  EXPECT_NEAR(move_seconds({0, 0, -80}, {0, 0, -60}, 0.0, planned), 0.2, 1e-9);
  // 230 mm along X: 1.15 s at 200 mm/s and 0.1 s of ramps.
  EXPECT_NEAR(move_seconds({100, 20, -5}, {330, 20, -5}, 0.0, planned), 1.25, 1e-9);
  // 80 along X with 60 along Y: [TRAJ] holds it to 200 mm/s, X's 2000 / 0.8
  // to 2500 mm/s² (not [TRAJ]'s 2000): 0.5 s + 0.08 s.
  EXPECT_NEAR(move_seconds({200, 20, -5}, {120, 80, -5}, 0.0, planned), 0.58, 1e-9);
}

// ---- the bound ----

TEST(Bound, shouldAddEveryMoveAsAnExactStopAndTheDwells) {
  Simulator plan;
  publish_move(plan, StepKind::rapid, axis_z, {0, 0, 4}, 0);  // 4 with 1/s²: 4 s
  plan.start_timer(0.5);
  publish_move(plan, StepKind::feed, axis_xy, {100, 0, 0},
               600);  // 100 at 10/s: 10 s + 10 s of ramps at 1/s²
  EXPECT_NEAR(limits_seconds(plan, {0, 0, 0}, limits_of(100, 1)), 4.0 + 0.5 + 20.0, 1e-9);
}

TEST(Bound, shouldTakeARunOfRapidsAsOneMoveForWhatBlendingIsWorthAtMost) {
  Simulator plan;
  publish_move(plan, StepKind::rapid, axis_z, {0, 0, 50}, 0);    // 50 up
  publish_move(plan, StepKind::rapid, axis_xy, {50, 0, 0}, 0);   // 50 over: one run of 100
  publish_move(plan, StepKind::feed, axis_xy, {60, 0, 0}, 600);  // 10 at 10/s, on its own
  publish_move(plan, StepKind::rapid, axis_z, {0, 0, 0}, 0);     // 50 down
  plan.start_timer(0.5);                                         // a dwell ends the run
  publish_move(plan, StepKind::rapid, axis_xy, {0, 0, 0}, 0);    // 60 back
  const MotionLimits limits = limits_of(10, 100);
  // At 10/s with 100/s²: a move of d stopped at both ends takes d/10 + 0.1 s.
  // The first run: Z travels 50 and X 50, at once at best.
  EXPECT_NEAR(blended_seconds(plan, {0, 0, 0}, limits), 5.1 + 1.1 + 5.1 + 0.5 + 6.1, 1e-9);
  MotionLimits slow_z = limits;
  slow_z.velocity.z = 1;  // the run's Z travel decides now: 50 at 1/s, + 0.01 s
  EXPECT_NEAR(blended_seconds(plan, {0, 0, 0}, slow_z), 50.01 + 1.1 + 50.01 + 0.5 + 6.1, 1e-9);
  EXPECT_LT(blended_seconds(plan, {0, 0, 0}, slow_z), limits_seconds(plan, {0, 0, 0}, slow_z));
  EXPECT_NEAR(limits_seconds(plan, {0, 0, 0}, limits), 5.1 + 5.1 + 1.1 + 5.1 + 0.5 + 6.1, 1e-9);
}

// ---- the estimate ----

TEST(ChangeTime, shouldAddThePlannedMovesTheDwellsAndTheCostsPerStepAndPerChange) {
  Simulator plan;
  plan.sensor_z = -20.0;
  // At 10/s with 20/s², each an exact stop: a move of d ≥ 5 takes d/v + v/20.
  publish_move(plan, StepKind::rapid, axis_x, {100, 0, 0}, 0);     // 10 s + 0.5 s
  publish_move(plan, StepKind::feed, axis_xy, {100, 50, 0}, 60);   // 50 at 1/s: 50 s + 0.05 s
  plan.set_chuck_open(true);                                       // no time of its own
  plan.start_timer(0.5);                                           // a dwell
  publish_move(plan, StepKind::probe, axis_z, {0, 0, -100}, 300);  // to the sensor: 20 at 5/s:
                                                                   // 4 s + 0.25 s
  plan.tell(MessageKind::prompt, "insert tool 7");                 // the operator's: not counted
  publish_done(plan);
  MachineTiming machine{limits_of(10, 20), 0.05};  // iocontrol's cycle 50 ms
  const ChangeTime time = change_time(plan, {0, 0, 0}, machine);
  EXPECT_NEAR(time.moves, 10.5 + 50.05 + 4.25, 1e-9);
  EXPECT_NEAR(time.dwells, 0.5, 1e-9);
  EXPECT_EQ(time.steps, 4);  // three moves and done: each one handshake
  EXPECT_NEAR(time.iocontrol, kIocontrolCycles * 0.05, 1e-9);
  EXPECT_EQ(time.operator_waits, 1);
  EXPECT_NEAR(time.seconds(),
              64.8 + 0.5 + 4 * kStepSeconds + kIocontrolCycles * 0.05 + kChangeSeconds, 1e-9);
}

TEST(ChangeTime, shouldNeverEstimateAChangeBelowItsBound) {
  // The gantry of issue 22: axes at 30 mm/s and 200 mm/s², [TRAJ] 100 and 800.
  MotionLimits gantry = limits_of(30, 200);
  gantry.linear_velocity = 100;
  gantry.linear_acceleration = 800;
  for (const Path path : {Path::prototype, Path::direct}) {
    Config config = test::valid_config();
    config.path = path;
    const std::pair<int, int> changes[] = {{0, 1}, {1, 2}, {2, 6}, {6, 0}};
    for (const auto& [from, to] : changes) {
      const Simulator plan = plan_change(config, from, to, -70.0);
      for (const MotionLimits& limits : {gantry, simulated_mill()}) {
        EXPECT_GT(change_time(plan, config.safe, MachineTiming{limits}).seconds(),
                  limits_seconds(plan, config.safe, limits))
            << from << " -> " << to;
      }
    }
  }
}

TEST(ChangeTime, shouldBeTheSameFromAPlanThatKeepsNoSavedStates) {
  // The preflight plans each change without the rack's copy at every save.
  const Config config = test::valid_config();
  for (const auto& [from, to] : {std::pair{0, 3}, std::pair{2, 5}, std::pair{4, 0}}) {
    const ToolState tools = with_in_spindle(config, from);
    const Simulator full = plan_change(config, tools, to, -60.0);
    const Simulator timed = plan_change_timed(config, tools, to, -60.0);
    ASSERT_EQ(timed.records.size(), full.records.size());
    EXPECT_EQ(timed.saves, full.saves);
    for (std::size_t i = 0; i < full.records.size(); ++i) {
      EXPECT_EQ(describe(timed.records[i]), describe(full.records[i])) << i;
      if (full.records[i].kind == Record::Kind::save) {
        EXPECT_EQ(timed.records[i].saved.pockets.size(), 0u);
      }
    }
    const MachineTiming machine;
    EXPECT_DOUBLE_EQ(change_time(timed, config.safe, machine).seconds(),
                     change_time(full, config.safe, machine).seconds());
  }
}

}  // namespace
}  // namespace fatc
