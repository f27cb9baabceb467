// `path`: the prototype's sequences (through safe XY before and after each
// leg) or the direct path (over the rack at safe Z, no trip to safe XY
// between a return and a fetch). Both keep every keep-out rule.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "core/config/config.hpp"
#include "core/rack/geometry.hpp"
#include "core/program/preflight.hpp"
#include "core/plan/routes.hpp"
#include "core/dry_run/simulator.hpp"
#include "core/dry_run/timing.hpp"
#include "sim_lines.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::Lines;
using test::valid_config;

/// The moves of a plan, as "rapid safe Z".
Lines moves(const Simulator& sim) {
  Lines out;
  for (const std::string& line : test::record_lines(sim)) {
    if (line.rfind("rapid", 0) == 0 || line.rfind("feed", 0) == 0) out.push_back(line);
  }
  return out;
}

long count(const Lines& lines, const std::string& line) {
  return std::count(lines.begin(), lines.end(), line);
}

Config direct() { return valid_config(R"("path": "direct")"); }

/// The estimate of a change on a machine at 3000 mm/min and 500 mm/s² on every axis.
double seconds(const Config& config, const Simulator& sim) {
  MotionLimits limits;
  limits.velocity = {50.0, 50.0, 50.0};
  limits.acceleration = {500.0, 500.0, 500.0};
  limits.linear_velocity = 50.0;
  limits.linear_acceleration = 500.0;
  return change_time(sim, config.safe, MachineTiming{limits}).seconds();
}

TEST(PathConfig, shouldKeepThePrototypePathUnlessTold) {
  EXPECT_EQ(valid_config().path, Path::prototype);
  EXPECT_EQ(direct().path, Path::direct);
  std::string text = test::kValidConfig;
  text.insert(text.rfind('}'), R"(,"path": "fast")");
  const auto parsed = parse_config(text);
  ASSERT_FALSE(parsed.config);
  EXPECT_EQ(parsed.errors.front(), R"(path: expected "prototype" or "direct", got "fast")");
}

TEST(DirectPath, shouldGoFromOnePocketToTheNextAtSafeZ) {
  const Simulator sim = plan_change(direct(), 1, 2, -70.0);
  EXPECT_EQ(moves(sim),
            (Lines{"rapid safe Z", "rapid over the side of pocket 1", "rapid side of pocket 1",
                   "rapid column edge of pocket 1", "feed pocket 1",
                   "rapid above-chuck of pocket 1", "rapid safe Z", "rapid over pocket 2",
                   "rapid above-chuck of pocket 2", "feed pocket 2", "feed column edge of pocket 2",
                   "rapid side of pocket 2", "rapid safe Z", "rapid safe XY"}))
      << "no stop at above-clearance on the way straight up or down";
  const Lines prototype = moves(plan_change(valid_config(), 1, 2, -70.0));
  EXPECT_EQ(count(prototype, "rapid safe XY"), 3) << "before the return, after it, at the end";
}

TEST(DirectPath, shouldEndAtSafeXYWhereTheProgramOrTheOperatorComesNext) {
  const Config config = direct();
  for (const auto& [what, sim] :
       {std::pair{"M6 T0", plan_change(config, 3, 0, -70.0)},
        std::pair{"M6 to a manual tool", plan_change(config, 3, 42, -70.0)},
        std::pair{"a load", plan_load(config, 4, 3, -70.0)}}) {
    const Lines lines = moves(sim);
    const auto back = std::find(lines.begin(), lines.end(), "rapid safe XY");
    ASSERT_NE(back, lines.end()) << what;
    EXPECT_EQ(back - lines.begin(), 7) << what << ": the return ends at safe XY";
  }
  const Lines unload = moves(plan_unload(config, 2, 3));
  EXPECT_EQ(count(unload, "rapid safe XY"), 1) << "the fetch of tool 2 follows the return of 3";
}

/// The length of the slow moves (feed) of a plan.
double slow_length(const Simulator& sim) {
  double length = 0.0;
  Point at;
  for (const Step& step : sim.motion_steps()) {
    Point to = at;
    if (step.axes & axis_x) to.x = step.target.x;
    if (step.axes & axis_y) to.y = step.target.y;
    if (step.axes & axis_z) to.z = step.target.z;
    if (step.kind == StepKind::feed) length += std::hypot(to.x - at.x, to.y - at.y, to.z - at.z);
    at = to;
  }
  return length;
}

TEST(DirectPath, shouldCrossOnlyThePocketsColumnSlowly) {
  // Side offset 40, keep-out margin 20 (half of it): the return's 40 into the
  // pocket, the fetch's 20 down and 40 out, of which only the column's part slowly.
  EXPECT_DOUBLE_EQ(slow_length(plan_change(valid_config(), 1, 2, -70.0)), 40.0 + 20.0 + 40.0);
  EXPECT_DOUBLE_EQ(slow_length(plan_change(direct(), 1, 2, -70.0)), 20.0 + 20.0 + 20.0);
  const Config wider = valid_config(R"("path": "direct", "rack_keepout_margin": 30.0)");
  EXPECT_DOUBLE_EQ(slow_length(plan_change(wider, 1, 2, -70.0)), 30.0 + 20.0 + 30.0);
}

/// Every change between every two tools of the rack, and from and to an
/// empty spindle, on both paths: every move clear of the keep-out, the end at
/// safe, and the direct path never longer.
void every_change(const Config& prototype, const Config& shorter) {
  double saved = 0.0, total = 0.0;
  for (int from = 0; from <= 6; ++from) {
    for (int to = 0; to <= 6; ++to) {
      if (from == to) continue;
      double time[2];
      int i = 0;
      for (const Config* config : {&prototype, &shorter}) {
        const Simulator sim = plan_change(*config, from, to, -70.0);
        const auto violations = check_steps(*config, sim.motion_steps(), std::nullopt);
        EXPECT_TRUE(violations.empty()) << from << "->" << to << ": " << violations.front().what;
        const Step& last = sim.motion_steps().back();
        EXPECT_EQ(last.label, "safe XY") << from << "->" << to;
        time[i++] = seconds(*config, sim);
      }
      EXPECT_LE(time[1], time[0] + 1e-9) << from << "->" << to;
      if (from != 0 && to != 0) {
        EXPECT_LT(time[1], time[0]) << from << "->" << to;
      }
      saved += time[0] - time[1];
      total += time[0];
    }
  }
  std::cout << "direct path: " << saved / total * 100.0
            << " % less estimated time over every change (at 3000 mm/min and 500 mm/s²)\n";
}

TEST(DirectPath, shouldKeepClearOfTheRackOnEveryChange) { every_change(valid_config(), direct()); }

/// The valid config with every pocket approached from the top, on `path`.
Config top_pockets(const char* path) {
  const std::string side = R"("pocket_default": {"y": 20.0, "z": -80.0})";
  const std::string top = R"("pocket_default": {"y": 20.0, "z": -80.0, "approach": "top"})";
  std::string text = test::kValidConfig;
  text.replace(text.find(side), side.size(), top);
  text.insert(text.rfind('}'), std::string(R"(,"path": ")") + path + "\"");
  return parse_config(text).config.value();
}

TEST(DirectPath, shouldKeepClearOfTheRackWithTopPockets) {
  every_change(top_pockets("prototype"), top_pockets("direct"));
}

TEST(DirectPath, shouldMoveSlowlyOnlyBelowAboveChuckInATopPocket) {
  // Above-chuck 20, above-clearance 60 over the pocket: the prototype goes
  // slowly from above-clearance down and back up; the direct path only while
  // the holder can touch the pocket, below above-chuck.
  EXPECT_DOUBLE_EQ(slow_length(plan_change(top_pockets("prototype"), 1, 2, -70.0)),
                   60.0 + 20.0 + 60.0);
  EXPECT_DOUBLE_EQ(slow_length(plan_change(top_pockets("direct"), 1, 2, -70.0)),
                   20.0 + 20.0 + 20.0);
  EXPECT_EQ(moves(plan_change(top_pockets("direct"), 1, 2, -70.0)),
            (Lines{"rapid safe Z", "rapid over pocket 1", "rapid above-chuck of pocket 1",
                   "feed pocket 1", "rapid above-chuck of pocket 1", "rapid safe Z",
                   "rapid over pocket 2", "rapid above-chuck of pocket 2", "feed pocket 2",
                   "feed above-chuck of pocket 2", "rapid safe Z", "rapid safe XY"}));
}

// ---------------------------------------------------------------- from where the spindle stands

TEST(FromWhereItStands, shouldLeaveOutTheWayAtSafeZToWhereTheSpindleAlreadyIs) {
  const Config c = valid_config();
  const plan::Route route = plan::return_to_approach(c, 2);
  const Point over_side = route.at(2).target;
  const plan::Route rest = plan::from_where_it_stands(c, route, {over_side.x, over_side.y, c.safe.z}, axis_xyz);
  ASSERT_EQ(rest.size(), route.size() - 3);
  EXPECT_EQ(rest.front().label, "side of pocket 2");
}

TEST(FromWhereItStands, shouldKeepEveryWaypointWhereTheSpindleIsNotKnownToBeAtSafeZ) {
  const Config c = valid_config();
  const plan::Route route = plan::return_to_approach(c, 2);
  const Point over_side = route.at(2).target;
  EXPECT_EQ(plan::from_where_it_stands(c, route, {over_side.x, over_side.y, c.safe.z}, axis_xy).size(),
            route.size());
  EXPECT_EQ(plan::from_where_it_stands(c, route, {over_side.x, over_side.y, c.safe.z - 1}, axis_xyz).size(),
            route.size());
  EXPECT_EQ(plan::from_where_it_stands(c, route, {1, 2, c.safe.z}, axis_xyz).size(), route.size() - 1)
      << "only the rise to safe Z, which is done";
}

TEST(FromWhereItStands, shouldKeepTheLastWaypointAndEverythingBelowSafeZ) {
  const Config c = valid_config();
  const plan::Route down = plan::return_into_pocket(c, 2);
  const Point end = down.back().target;
  EXPECT_EQ(plan::from_where_it_stands(c, down, end, axis_xyz).size(), down.size());
  const plan::Route up = plan::to_safe_z(c);
  EXPECT_EQ(plan::from_where_it_stands(c, up, c.safe, axis_xyz).size(), 1u);
}

TEST(WhileSpindleStops, shouldTakeOnlyTheMovesAtSafeZAndNothingWhenSwitchedOff) {
  const Config c = valid_config();
  const plan::Route meanwhile = plan::while_spindle_stops(c, plan::return_to_approach(c, 2));
  ASSERT_EQ(meanwhile.size(), 3u);
  for (const Step& step : meanwhile) {
    EXPECT_TRUE(!(step.axes & axis_z) || step.target.z == c.safe.z) << describe(step);
  }
  EXPECT_TRUE(plan::while_spindle_stops(valid_config(R"("move_while_spindle_stops": false)"),
                                        plan::return_to_approach(c, 2))
                  .empty());
  EXPECT_TRUE(plan::while_spindle_stops(c, plan::return_into_pocket(c, 2)).empty())
      << "never across before the rise to safe Z";
}

}  // namespace
}  // namespace fatc
