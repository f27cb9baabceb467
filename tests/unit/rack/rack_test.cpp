// The rack as the machinist sees it: pockets hold any tool, per-pocket
// approach and side offset, where a load puts its tool, measure all.
#include <gtest/gtest.h>

#include <memory>

#include "core/machine/changer.hpp"
#include "core/config/config.hpp"
#include "core/rack/geometry.hpp"
#include "core/machine/base/admission.hpp"
#include "core/dry_run/sequence_check.hpp"
#include "core/dry_run/simulator.hpp"
#include "core/rack/tool_state.hpp"
#include "sim_lines.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::Lines;

/// Pocket 1 holds T12, pocket 2 T7, pocket 3 starts empty, pocket 4 holds T3
/// from above, pocket 5 its own tool with the side facing -X.
const std::string kRack = test::sample_config_with_pockets(
    R"({"1": {"x": 50.0, "tool": 12}, "2": {"x": 100.0, "tool": 7},
              "3": {"x": 150.0, "tool": 0}, "4": {"x": 200.0, "tool": 3, "approach": "top"},
              "5": {"x": 300.0, "side_offset": {"x": -40.0, "y": 0.0}}})");

Config rack_config() {
  const auto parsed = parse_config(kRack);
  EXPECT_TRUE(parsed.errors.empty()) << parsed.errors.front();
  return *parsed.config;
}

struct RackRig {
  explicit RackRig(ToolState start) : config(rack_config()) {
    changer = std::make_unique<Changer>(config, sim, std::move(start));
    changer->ready();
  }
  RackRig() : RackRig(ToolState::fresh(rack_config())) {}
  ~RackRig() { EXPECT_TRUE(sim.unexpected_events.empty()) << sim.unexpected_events.front(); }
  Lines run(std::size_t& from) {
    sim.run(*changer);
    const Lines done = test::record_lines(sim, from);
    from = sim.records.size();
    return done;
  }
  /// The targets of the motion steps since `from`, as pocket labels say them.
  Lines motion(std::size_t from) const {
    Lines out;
    for (std::size_t i = from; i < sim.records.size(); ++i) {
      const Record& r = sim.records[i];
      if (r.kind == Record::Kind::step && is_motion(r.step.kind)) out.push_back(r.step.label);
    }
    return out;
  }
  std::string last_error() const {
    const auto errors = sim.messages(MessageKind::error);
    return errors.empty() ? "" : errors.back();
  }
  Config config;
  Simulator sim;
  std::unique_ptr<Changer> changer;
};

// ---------------------------------------------------------------- config

TEST(RackConfig, shouldReadEachPocketsToolApproachAndSideOffset) {
  const Config c = rack_config();
  EXPECT_EQ(c.pockets.at(1).first_tool, 12);
  EXPECT_EQ(c.pockets.at(3).first_tool, 0);
  EXPECT_EQ(c.pockets.at(5).first_tool, 5) << "without `tool` pocket N starts with tool N";
  EXPECT_EQ(c.pockets.at(4).approach, Approach::top);
  EXPECT_EQ(c.pockets.at(1).approach, Approach::side);
  EXPECT_EQ(c.pockets.at(5).side_offset.x, -40.0);
  EXPECT_EQ(c.pockets.at(1).side_offset.y, 40.0) << "pocket_side_offset is the default";
  EXPECT_EQ(c.first_pocket_of(7), 2);
  EXPECT_FALSE(c.first_pocket_of(2).has_value());
}

TEST(RackConfig, shouldTakeApproachAndSideOffsetFromPocketDefault) {
  std::string text = kRack;
  text.replace(text.find(R"("pocket_default": {"y": 20.0, "z": -80.0})"),
               std::string(R"("pocket_default": {"y": 20.0, "z": -80.0})").size(),
               R"("pocket_default": {"y": 20.0, "z": -80.0, "approach": "top"})");
  const auto parsed = parse_config(text);
  ASSERT_TRUE(parsed.config) << parsed.errors.front();
  EXPECT_EQ(parsed.config->pockets.at(1).approach, Approach::top);
}

struct BadRack {
  const char* name;
  const char* from;
  const char* to;
  const char* expected;
};
std::ostream& operator<<(std::ostream& out, const BadRack& b) { return out << b.name; }
class BadRackConfig : public ::testing::TestWithParam<BadRack> {};

TEST_P(BadRackConfig, shouldNameThePocketKeyInOneLine) {
  std::string text = kRack;
  const auto at = text.find(GetParam().from);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, std::string(GetParam().from).size(), GetParam().to);
  const auto parsed = parse_config(text);
  ASSERT_FALSE(parsed.config);
  EXPECT_EQ(parsed.errors.front(), GetParam().expected);
}

// clang-format off
INSTANTIATE_TEST_SUITE_P(Each, BadRackConfig, ::testing::Values(
  BadRack{"tool_twice", R"("x": 100.0, "tool": 7)", R"("x": 100.0, "tool": 12)",
          "pockets.2.tool: tool 12 already starts in pocket 1"},
  BadRack{"tool_negative", R"("tool": 7)", R"("tool": -7)",
          "pockets.2.tool: expected a tool number (1 to 999999999) or 0 (starts empty), got -7"},
  BadRack{"tool_text", R"("tool": 7)", R"("tool": "T7")",
          "pockets.2.tool: expected a tool number (1 to 999999999) or 0 (starts empty), got \"T7\""},
  BadRack{"approach", R"("approach": "top")", R"("approach": "below")",
          "pockets.4.approach: expected \"side\" or \"top\", got \"below\""},
  BadRack{"side_offset_inside_keepout", R"({"x": -40.0, "y": 0.0})", R"({"x": -10.0, "y": 0.0})",
          "pockets.5.side_offset: must lead out of the pocket's keep-out (rack_keepout_margin 20), got 10 long"},
  BadRack{"side_offset_key", R"({"x": -40.0, "y": 0.0})", R"({"x": -40.0, "z": 0.0})",
          "pockets.5.side_offset.z: unknown key, did you mean \"x\"?"},
  BadRack{"tool_in_default", R"("pocket_default": {"y": 20.0,)", R"("pocket_default": {"tool": 3, "y": 20.0,)",
          "pocket_default.tool: unknown key"}
));
// clang-format on

// ---------------------------------------------------------------- the map

TEST(RackState, shouldStartWithEachPocketsFirstTool) {
  const ToolState fresh = ToolState::fresh(rack_config());
  EXPECT_EQ(fresh.tool_of(1), 12);
  EXPECT_EQ(fresh.tool_of(3), 0);
  EXPECT_EQ(fresh.pocket_holding(3), 4);
  EXPECT_EQ(fresh.free_pockets(), (std::vector<int>{3}));
  EXPECT_EQ(fresh.rack_tools(), (std::vector<int>{12, 7, 3, 5}));
}

TEST(RackState, shouldRoundTripVersionTwo) {
  ToolState state = ToolState::fresh(rack_config());
  state.spindle = 7;
  state.pockets[2].holds = false;
  const auto read = tool_state_from_json(to_json(state));
  ASSERT_TRUE(read.state) << read.error;
  EXPECT_EQ(*read.state, state);
  EXPECT_EQ(read.version, 2);
}

TEST(RackState, shouldReadVersionOneAsPocketNHoldingToolN) {
  const auto read = tool_state_from_json(
      R"({"version": 1, "spindle": 2, "uncertain": false, "in_pocket": [1, 4], "lengths": {}})");
  ASSERT_TRUE(read.state) << read.error;
  ToolState state = *read.state;
  ASSERT_EQ(fit_to_config(state, test::valid_config(), read.version), "");
  EXPECT_TRUE(state.holds(1));
  EXPECT_EQ(state.tool_of(2), 2) << "tool 2 in the spindle still belongs in pocket 2";
  EXPECT_FALSE(state.holds(2));
  EXPECT_EQ(state.tool_of(3), 3);
  EXPECT_FALSE(state.holds(3)) << "version 1 had tool 3 out of its pocket";
}

TEST(RackState, shouldGiveAPocketNewToTheConfigItsFirstTool) {
  ToolState state = ToolState::fresh(rack_config());
  state.pockets.erase(5);
  ASSERT_EQ(fit_to_config(state, rack_config(), 2), "");
  EXPECT_TRUE(state.holds(5));
  EXPECT_EQ(state.tool_of(5), 5);
}

TEST(RackState, shouldRefuseAToolInAPocketTheConfigLost) {
  ToolState state = ToolState::fresh(rack_config());
  state.pockets[9] = {9, true};
  EXPECT_EQ(fit_to_config(state, rack_config(), 2),
            "pockets.9: tool 9 is recorded in pocket 9, which config.json does not have");
}

// ---------------------------------------------------------------- M6 through the map

TEST(RackChange, shouldFetchFromThePocketHoldingTheToolAndReturnItThere) {
  RackRig rig;
  std::size_t from = 0;
  rig.changer->tool_change(12);
  rig.run(from);
  EXPECT_EQ(rig.changer->tools().spindle, 12);
  EXPECT_EQ(rig.motion(0)[2], "over pocket 1");
  const std::size_t second = rig.sim.records.size();
  rig.changer->tool_change(7);
  rig.run(from);
  const Lines moves = rig.motion(second);
  EXPECT_EQ(moves[2], "over the side of pocket 1") << "T12 goes back to pocket 1";
  EXPECT_NE(std::find(moves.begin(), moves.end(), "over pocket 2"), moves.end());
  EXPECT_TRUE(rig.changer->tools().holds(1));
  EXPECT_EQ(rig.changer->tools().tool_of(1), 12);
  EXPECT_EQ(rig.changer->tools().spindle, 7);
  EXPECT_FALSE(rig.changer->tools().holds(2));
}

TEST(RackChange, shouldGoStraightDownAndUpAtATopPocket) {
  RackRig rig;
  std::size_t from = 0;
  rig.changer->tool_change(3);
  EXPECT_EQ(rig.run(from),
            (Lines{"rapid safe Z", "rapid safe XY", "rapid over pocket 4",
                   "rapid above-clearance of pocket 4", "rapid above-chuck of pocket 4",
                   "chuck open", "dwell 0.20", "chuck close", "dwell 0.20", "chuck open",
                   "dwell 0.50", "feed pocket 4", "dwell 0.50", "chuck close", "dwell 0.50",
                   "feed above-clearance of pocket 4", "rapid safe Z", "rapid safe XY", "done T3"}))
      << "fetched out the top: the slow move is straight up";
  rig.changer->tool_change(0);
  EXPECT_EQ(rig.run(from), (Lines{"rapid safe Z", "rapid safe XY", "rapid over pocket 4",
                                  "rapid above-clearance of pocket 4", "feed pocket 4",
                                  "chuck open", "dwell 0.50", "rapid above-chuck of pocket 4",
                                  "chuck close", "rapid above-clearance of pocket 4",
                                  "rapid safe Z", "rapid safe XY", "done T0"}))
      << "returned from the top: no side waypoint, the slow move straight down";
}

TEST(RackChange, shouldUseThePocketsOwnSideOffset) {
  RackRig rig;
  rig.changer->tool_change(5);
  std::size_t from = 0;
  rig.run(from);
  const std::size_t start = rig.sim.records.size();
  rig.changer->tool_change(0);
  rig.run(from);
  for (std::size_t i = start; i < rig.sim.records.size(); ++i) {
    const Step& step = rig.sim.records[i].step;
    if (rig.sim.records[i].kind == Record::Kind::step && step.label == "side of pocket 5") {
      EXPECT_DOUBLE_EQ(step.target.x, 260.0);
      EXPECT_DOUBLE_EQ(step.target.y, 20.0);
      return;
    }
  }
  ADD_FAILURE() << "no move to the side of pocket 5";
}

TEST(RackChange, shouldReturnAToolFromOutsideToItsFreeFirstStartPocket) {
  ToolState start = ToolState::fresh(rack_config());
  start.pockets[2] = {};  // T7 was unloaded: pocket 2 is free
  start.spindle = 7;      // and handed in by hand (a manual tool now)
  RackRig rig(start);
  rig.changer->tool_change(12);
  std::size_t from = 0;
  rig.run(from);
  EXPECT_EQ(rig.changer->tools().tool_of(2), 7);
  EXPECT_TRUE(rig.changer->tools().holds(2));
}

TEST(RackChange, shouldPlanEverySequenceThroughEveryPocketWithinTheKeepOut) {
  const SequencesChecked checked = check_sequences(rack_config(), std::nullopt);
  EXPECT_EQ(checked.sequences, 30);
  EXPECT_TRUE(checked.violations.empty()) << describe(checked.violations.front());
}

// ---------------------------------------------------------------- load and unload

TEST(RackLoad, shouldChooseTheAskedOwnFirstStartOrNearestFreePocket) {
  const Config config = rack_config();
  ToolState tools = ToolState::fresh(config);
  Simulator sim;
  Ports& ports = sim;
  Context ctx(config, ports, tools);
  EXPECT_EQ(choose_load_pocket(ctx, 20, 0).pocket, 3) << "the only free pocket";
  EXPECT_EQ(choose_load_pocket(ctx, 20, 3).pocket, 3);
  EXPECT_EQ(choose_load_pocket(ctx, 20, 2).why, "pocket 2 is tool 7's (free: pocket 3)");
  EXPECT_EQ(choose_load_pocket(ctx, 20, 9).why, "pocket 9 is not in the config (free: pocket 3)");
  ctx.tools.pockets[1] = {};  // T12 unloaded
  EXPECT_EQ(choose_load_pocket(ctx, 12, 0).pocket, 1) << "its first-start pocket, free again";
  EXPECT_EQ(choose_load_pocket(ctx, 20, 0).pocket, 1) << "nearest to loading of pockets 1 and 3";
  ctx.tools.pockets[1] = {12, true};
  ctx.tools.pockets[3] = {20, true};
  EXPECT_EQ(choose_load_pocket(ctx, 21, 0).why,
            "no pocket for tool 21: every pocket holds a tool; unload one first");
}

TEST(RackLoad, shouldPutTheToolInTheAskedPocketAndUnloadShouldFreeIt) {
  RackRig rig;
  std::size_t from = 0;
  rig.sim.sensor_z = -60.0;
  rig.changer->load(20, 3);
  for (int i = 0; i < 5 && rig.changer->status().busy(); ++i) {
    rig.run(from);
    if (rig.changer->status().awaiting == Awaiting::operator_choice) {
      rig.changer->operator_continue();
    }
  }
  EXPECT_EQ(rig.changer->tools().tool_of(3), 20);
  EXPECT_TRUE(rig.changer->tools().holds(3));
  rig.changer->unload(20);
  for (int i = 0; i < 5 && rig.changer->status().busy(); ++i) {
    rig.run(from);
    if (rig.changer->status().awaiting == Awaiting::operator_choice) {
      rig.changer->operator_continue();
    }
  }
  EXPECT_EQ(rig.changer->tools().tool_of(3), 0) << "unload frees the pocket";
  EXPECT_EQ(rig.changer->tools().spindle, 0);
}

// ---------------------------------------------------------------- measure all

TEST(MeasureAll, shouldFetchMeasureAndPutBackEachToolWithAReport) {
  ToolState start = ToolState::fresh(rack_config());
  start.lengths[7] = 34.0;
  RackRig rig(start);
  rig.sim.sensor_z = -60.0;
  std::size_t from = 0;
  rig.changer->measure_all({12, 7, 99});
  EXPECT_EQ(rig.changer->status().phase, Phase::measuring);
  EXPECT_EQ(rig.changer->status().batch_total, 2) << "T99 is in no pocket: skipped";
  rig.run(from);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rig.changer->tools().lengths.at(12), 35.0);
  EXPECT_EQ(rig.changer->tools().lengths.at(7), 35.0);
  EXPECT_EQ(rig.changer->tools().spindle, 0);
  EXPECT_TRUE(rig.changer->tools().holds(1));
  EXPECT_TRUE(rig.changer->tools().holds(2));
  const auto infos = rig.sim.messages(MessageKind::info);
  EXPECT_EQ(infos.back(),
            "measure all done: 2 of 2 tools; T12 35.0000 mm (first measurement); T7 35.0000 mm "
            "(was 34.0000 mm, +1.0000)");
  EXPECT_NE(std::find(infos.begin(), infos.end(), "measure all skips what is not in the rack: T99"),
            infos.end());
}

TEST(MeasureAll, shouldStopAfterTheToolUnderWayIsBackWhenCancelled) {
  RackRig rig;
  rig.sim.sensor_z = -60.0;
  rig.changer->measure_all({12, 7, 3});
  // Into the first tool's fetch, then Cancel.
  for (int i = 0; i < 6; ++i) rig.sim.run(*rig.changer, 1);
  rig.changer->operator_cancel();
  std::size_t from = 0;
  rig.run(from);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rig.changer->tools().spindle, 0);
  EXPECT_TRUE(rig.changer->tools().holds(1)) << "T12 was put back before the batch stopped";
  EXPECT_EQ(rig.changer->tools().lengths.count(7), 0u) << "T7 was never fetched";
  EXPECT_EQ(rig.sim.messages(MessageKind::info).back(),
            "measure all cancelled after 1 of 3 tools; T12 35.0000 mm (first measurement)");
}

TEST(MeasureAll, shouldStopTheProbeAndTheBatchWhenCancelledDuringAProbe) {
  RackRig rig;
  rig.sim.sensor_z = -60.0;
  rig.changer->measure_all({12, 7, 3});
  for (int i = 0; i < 100 && rig.changer->status().awaiting != Awaiting::probe; ++i) {
    rig.sim.run(*rig.changer, 1);
  }
  ASSERT_EQ(rig.changer->status().awaiting, Awaiting::probe);
  ASSERT_TRUE(rig.changer->status().probe_cancellable);
  rig.changer->operator_cancel();
  std::size_t from = 0;
  rig.run(from);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rig.changer->tools().spindle, 0);
  EXPECT_TRUE(rig.changer->tools().holds(1)) << "T12 was put back before the batch stopped";
  EXPECT_EQ(rig.changer->tools().lengths.count(12), 0u) << "the cancelled probe wrote nothing";
  EXPECT_EQ(rig.changer->tools().lengths.count(7), 0u) << "T7 was never fetched";
  EXPECT_EQ(rig.sim.messages(MessageKind::info).back(),
            "measure all cancelled after 1 of 3 tools; T12 not measured: the probe was cancelled "
            "by the operator");
}

TEST(MeasureAll, shouldReturnTheSpindlesToolFirst) {
  ToolState start = ToolState::fresh(rack_config());
  start.spindle = 12;
  start.pockets[1].holds = false;
  RackRig rig(start);
  rig.sim.sensor_z = -60.0;
  rig.changer->measure_all({7});
  std::size_t from = 0;
  rig.run(from);
  EXPECT_EQ(rig.motion(0)[2], "over the side of pocket 1");
  EXPECT_TRUE(rig.changer->tools().holds(1));
  EXPECT_TRUE(rig.changer->tools().holds(2));
}

TEST(MeasureAll, shouldRefuseWhenNothingItNamesIsInTheRack) {
  RackRig rig;
  rig.changer->measure_all({99, 98});
  EXPECT_TRUE(rig.sim.steps().empty());
  EXPECT_EQ(rig.last_error(),
            "measure all (2 tools) refused: no tool to measure in the rack (not in the rack: T99, "
            "T98)");
}

}  // namespace
}  // namespace fatc
