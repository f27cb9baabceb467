// blend_tolerance: a run of rapids at safe Z goes out as one step whose
// corners the executor rounds (G64 P). Blending changes when the machine
// stops, never where it goes.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "core/config/config.hpp"
#include "core/plan/routes.hpp"
#include "core/dry_run/sequence_check.hpp"
#include "core/dry_run/simulator.hpp"
#include "core/dry_run/timing.hpp"
#include "sim_lines.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::valid_config;

/// What --plan prints of a change, each move without what blending adds.
test::Lines plain_lines(const Simulator& sim) {
  test::Lines lines = test::record_lines(sim);
  for (std::string& line : lines) {
    const auto rounded = line.find(", on into the next within");
    if (rounded != std::string::npos) line.erase(rounded);
  }
  return lines;
}

Config top_rack(const std::string& extra) {
  std::string text = test::kValidConfig;
  const std::string side = R"("pocket_default": {"y": 20.0, "z": -80.0})";
  text.replace(text.find(side), side.size(),
               R"("pocket_default": {"y": 20.0, "z": -80.0, "approach": "top"})");
  text.insert(text.rfind('}'), "," + extra);
  return parse_config(text).config.value();
}

TEST(Blend, shouldLeaveEveryRouteAsItIsWithoutATolerance) {
  const Config c = valid_config(R"("path": "direct")");
  const plan::Route route = plan::return_to_approach(c, 2);
  const plan::Route same = plan::blended(c, route, c.safe, axis_xyz);
  ASSERT_EQ(same.size(), route.size());
  for (const Step& step : same) EXPECT_TRUE(step.before.empty()) << describe(step);
}

TEST(Blend, shouldJoinUpToSafeZAndAcrossIntoTheRapidThatFollows) {
  const Config c = valid_config(R"("path": "direct", "blend_tolerance": 10)");
  // Up to safe Z, over the side of pocket 2, down to the side: one step.
  const plan::Route route = plan::return_to_approach(c, 2);
  ASSERT_GE(route.size(), 3u);
  const plan::Route runs = plan::blended(c, route, Point{0, 0, -60}, axis_xyz);
  ASSERT_EQ(runs.size(), route.size() - 2);
  const Step& run = runs.front();
  EXPECT_EQ(via_of(run), Via::up_and_across);
  EXPECT_EQ(run.blend, 10.0);
  EXPECT_EQ(run.label, route[2].label);
  const auto moves = moves_of(run);
  ASSERT_EQ(moves.size(), 3u);
  EXPECT_EQ(moves[0].label, "safe Z");
  EXPECT_EQ(moves[0].blend, 10.0);
  EXPECT_EQ(moves[1].blend, 10.0);
  EXPECT_EQ(moves[2].blend, 0.0) << "the run's last move ends standing";
  EXPECT_TRUE(moves[2].before.empty());
}

TEST(Blend, shouldRoundACornerOverOrBesideAColumnWithinAThirdOfTheRoom) {
  // Safe Z lies 15 above the above-clearance: a corner whose way up or down
  // is in a column or beside one is rounded within 15 / 3.5, so LinuxCNC's
  // arc, which leaves the way down 2.41 P below the corner, and its parabolic
  // blend, 2.83 P, stay above the column.
  const Config c = valid_config(R"("path": "direct", "blend_tolerance": 10)");
  ASSERT_EQ(c.blend_room(), 15.0);
  const double over_columns = 15.0 / 3.5;
  ASSERT_EQ(c.blend_over_columns(), over_columns);
  const plan::Route fetch = plan::from_where_it_stands(c, plan::fetch_to_above_chuck(c, 2),
                                                       c.safe, axis_xyz);
  const plan::Route fetch_runs = plan::blended(c, fetch, c.safe, axis_xyz);
  ASSERT_EQ(via_of(fetch_runs.front()), Via::across);
  EXPECT_EQ(fetch_runs.front().before.front().label, "over pocket 2");
  EXPECT_EQ(fetch_runs.front().blend, over_columns) << "down over pocket 2 into its column";
  const Config top = top_rack(R"("path": "direct", "blend_tolerance": 10)");
  const plan::Route down = plan::blended(top, plan::return_to_approach(top, 2), c.safe, axis_xyz);
  ASSERT_EQ(down.size(), 1u);
  EXPECT_EQ(via_of(down[0]), Via::up_and_across);
  EXPECT_EQ(down[0].before.back().label, "over pocket 2");
  EXPECT_EQ(down[0].blend, over_columns) << "up at safe XY within 10, down into the column: the least";
  const plan::Route up = plan::blended(c, plan::return_to_approach(c, 2), Point{0, 0, -60},
                                       axis_xyz);
  EXPECT_EQ(up.front().blend, 10.0) << "up at X0 Y0, across, down beside the rack: all clear";
  // Beside a side 1 mm outside its pocket's column: within 15 / 3.5 instead
  // of 12; with safe Z 50 above the above-clearance, 50 / 3.5 is more than 12.
  auto j = nlohmann::json::parse(test::kValidConfig);
  j["path"] = "direct";
  j["blend_tolerance"] = 12;
  j["rack_keepout_margin"] = 39;
  const Config narrow = parse_config(j.dump()).config.value();
  const plan::Route side = plan::blended(narrow, plan::return_to_approach(narrow, 2),
                                         narrow.safe, axis_xyz);
  EXPECT_EQ(via_of(side.front()), Via::up_and_across);
  EXPECT_EQ(side.front().before.back().label, "over the side of pocket 2");
  EXPECT_EQ(side.front().blend, over_columns);
  j["safe"]["z"] = 30.0;
  const Config roomy = parse_config(j.dump()).config.value();
  ASSERT_EQ(roomy.blend_room(), 50.0);
  EXPECT_EQ(plan::blended(roomy, plan::return_to_approach(roomy, 2), roomy.safe, axis_xyz)
                .front()
                .blend,
            12.0);
  // Where Z is not known to be safe Z, nothing goes across on the way.
  const plan::Route across{plan::safe_xy(c), plan::safe_z(c)};
  EXPECT_TRUE(plan::blended(c, across, c.safe, axis_xy).front().before.empty());
  // Into a pocket from its side: the slow move starts from standing.
  for (const Step& step : plan::blended(c, plan::return_into_pocket(c, 2), c.safe, axis_xyz)) {
    EXPECT_TRUE(step.before.empty()) << describe(step);
  }
  // No room over the columns: a corner there stands (G64 P0 would round it
  // as far as LinuxCNC likes).
  auto flush = nlohmann::json::parse(test::kValidConfig);
  flush["path"] = "direct";
  flush["blend_tolerance"] = 0;
  flush["safe"]["z"] = -20.0;
  Config level = parse_config(flush.dump()).config.value();
  ASSERT_EQ(level.blend_room(), 0.0);
  level.blend_tolerance = 10;
  for (const Step& step : plan::blended(level, fetch, level.safe, axis_xyz)) {
    if (!step.before.empty()) {
      EXPECT_GT(step.blend, 0.0) << describe(step);
    }
  }
}

TEST(Blend, shouldGoThroughTheSameWaypointsOnEveryChange) {
  for (const Config& blended :
       {valid_config(R"("path": "direct", "blend_tolerance": 15)"),
        valid_config(R"("blend_tolerance": 15)"), top_rack(R"("path": "direct", "blend_tolerance": 15)")}) {
    Config exact = blended;
    exact.blend_tolerance = 0.0;
    for (int from = 0; from <= 6; ++from) {
      for (int to = 0; to <= 6; ++to) {
        const Simulator rounded = plan_change(blended, from, to, -70.0);
        const Simulator stopped = plan_change(exact, from, to, -70.0);
        EXPECT_EQ(plain_lines(rounded), plain_lines(stopped)) << from << "->" << to;
        EXPECT_TRUE(check_sequence("M6", blended, rounded, std::nullopt).empty())
            << from << "->" << to;
        for (const Step& move : rounded.motion_steps()) {
          if (move.blend == 0.0) continue;
          EXPECT_TRUE(move.blend == blended.blend_tolerance ||
                      move.blend == blended.blend_over_columns())
              << from << "->" << to << ": " << describe(move);
          EXPECT_TRUE(move.kind == StepKind::rapid &&
                      (move.axes == axis_xy || move.target.z == blended.safe.z))
              << from << "->" << to << ": " << describe(move);
        }
        // Fewer handshakes: one step a run.
        const MachineTiming machine{};
        const auto fewer = change_time(rounded, blended.safe, machine).steps;
        const auto each = change_time(stopped, exact.safe, machine).steps;
        EXPECT_LE(fewer, each) << from << "->" << to;
        if (from != to) {
          EXPECT_LT(fewer, each) << from << "->" << to;
        }
      }
    }
  }
}

TEST(Blend, shouldRefuseAToleranceThatWouldCutIntoTheRack) {
  // Safe Z -5 over above-clearance -80 + 60: 15.
  std::string why;
  EXPECT_EQ(valid_config().blend_room(&why), 15.0);
  EXPECT_EQ(why, "how far safe.z lies above pocket 1's above-clearance");
  const auto refused = [](double tolerance, double safe_z = -5.0, double side = 40.0,
                          double margin = 20.0) {
    auto j = nlohmann::json::parse(test::kValidConfig);
    j["blend_tolerance"] = tolerance;
    j["safe"]["z"] = safe_z;
    j["pocket_side_offset"]["y"] = side;
    j["rack_keepout_margin"] = margin;
    const auto result = parse_config(j.dump());
    return result.config ? std::string() : result.errors.front();
  };
  EXPECT_EQ(refused(15.5),
            "blend_tolerance: must not be more than 15, how far safe.z lies above pocket 1's "
            "above-clearance: a rounded corner would cut into the rack; got 15.5");
  EXPECT_EQ(refused(15), "");
}

}  // namespace
}  // namespace fatc
