// The tool the spindle carries through the changer's own moves: its tip may
// not enter a holder, checked with the length LinuxCNC's tool table gives
// (a negative or missing one counts as the longest the config allows), and a
// request whose sequence would do it is refused before anything moves.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "core/config/config.hpp"
#include "core/machine/changer.hpp"
#include "core/dry_run/dry_run.hpp"
#include "core/dry_run/sequence_check.hpp"
#include "core/dry_run/simulator.hpp"
#include "core/rack/geometry.hpp"
#include "core/rack/keepout.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {


Config top_rack() {
  const auto parsed = parse_config(test::kTopRack);
  EXPECT_TRUE(parsed.errors.empty()) << parsed.errors.front();
  return *parsed.config;
}

Step rapid_to(const Point& at, int held) {
  Step step;
  step.kind = StepKind::rapid;
  step.axes = axis_xyz;
  step.target = at;
  step.held = held;
  step.label = "test";
  return step;
}

bool has_motion(const Simulator& sim) {
  for (const Step& step : sim.steps()) {
    if (is_motion(step.kind)) return true;
  }
  return false;
}

std::string errors(const Simulator& sim) {
  std::string all;
  for (const auto& text : sim.messages(MessageKind::error)) all += text + "\n";
  return all;
}

// ---------------------------------------------------------------- lengths

TEST(KeepoutLength, shouldTakeTheTablesLengthOnlyWhereItIsOneBelowTheNose) {
  ToolLengths lengths;
  lengths.table = {{1, 30.0}, {2, -12.0}, {3, 0.0}};
  lengths.longest = 45.0;
  const std::map<int, double> measured = {{2, 33.0}};
  EXPECT_EQ(lengths.of(1, measured).source, LengthSource::table);
  EXPECT_DOUBLE_EQ(lengths.of(1, measured).length, 30.0);
  EXPECT_EQ(lengths.of(2, measured).source, LengthSource::measured) << "never lowered to -12";
  EXPECT_DOUBLE_EQ(lengths.of(2, measured).length, 33.0);
  EXPECT_EQ(lengths.of(3, measured).source, LengthSource::longest);
  EXPECT_DOUBLE_EQ(lengths.of(3, measured).length, 45.0);
  EXPECT_EQ(lengths.of(9, measured).source, LengthSource::longest) << "not in the table";
  EXPECT_DOUBLE_EQ(lengths.of(0, measured).length, 0.0) << "an empty spindle";
  // A table relative to a master tool gives a longer tool a small positive Z.
  lengths.table[4] = 5.0;
  EXPECT_DOUBLE_EQ(lengths.of(4, {{4, 85.0}}).length, 85.0) << "the measurement, longer";
  EXPECT_EQ(lengths.of(4, {{4, 85.0}}).source, LengthSource::measured);
  EXPECT_DOUBLE_EQ(lengths.of(1, {{1, 29.9}}).length, 30.0) << "the table's, longer";
  // The table's six decimals of the changer's own measurement: the same length.
  lengths.table[5] = 24.9983;
  EXPECT_EQ(lengths.of(5, {{5, 24.998300000003056}}).source, LengthSource::table);
  EXPECT_EQ(keepout_length_words(top_rack(), lengths, 5, {{5, 24.998300000003056}}), "");
}

TEST(KeepoutLength, shouldSayWhatItCountsWhereTheTablesZIsNoLength) {
  const Config config = top_rack();
  ToolLengths lengths;
  lengths.table = {{1, 30.0}, {2, -12.0}};
  lengths.longest = 40.0;
  EXPECT_EQ(keepout_length_words(config, lengths, 1, {}), "");
  EXPECT_EQ(keepout_length_words(config, lengths, 2, {}),
            "T2: LinuxCNC's tool table gives Z-12.0000 mm, no length below the spindle nose; the "
            "rack keep-out counts it as 40.0000 mm (the longest tool the config allows)");
  EXPECT_NE(keepout_length_words(config, lengths, 7, {{7, 51.5}}).find(
                "gives no length; the rack keep-out counts it as 51.5000 mm (its length as the "
                "changer measured it)"),
            std::string::npos);
}

TEST(LoadingNote, shouldSayWhenLoadingIsNotOverTheTouchOffSensor) {
  Config config = top_rack();
  config.loading.x = config.probe_limit.x + 0.5;
  config.loading.y = config.probe_limit.y;
  EXPECT_FALSE(loading_note(config)) << "within 1 mm: over it";
  config.loading = {20.0, 150.0, -10.0};
  config.probe_limit = {300.0, 300.0, -90.0};
  const auto note = loading_note(config);
  ASSERT_TRUE(note);
  EXPECT_EQ(note->rfind("note: loading X20.000 Y150.000 is not over the touch-off sensor "
                        "(probe_limit X300.000 Y300.000), 317.6476 mm off: a load measures "
                        "straight down from loading",
                        0),
            0u)
      << *note;
}

// ---------------------------------------------------------------- one move

TEST(TipRoom, shouldBeTheNosesLowestHeightOverAColumnLessItsHoldersTop) {
  const Config config = top_rack();
  // Across pockets 1 and 2 at safe Z: the holders' tops are at -60.
  const TipRoom across = tip_room(config, {20.0, 20.0, -15.0}, rapid_to({125.0, 20.0, -15.0}, 1));
  EXPECT_DOUBLE_EQ(across.length, 45.0);
  EXPECT_EQ(across.pocket, 1);
  // Down into pocket 2's column from above: its lowest point counts.
  const TipRoom down = tip_room(config, {100.0, 20.0, -15.0}, rapid_to({100.0, 20.0, -30.0}, 1));
  EXPECT_DOUBLE_EQ(down.length, 30.0);
  // Straight up never carries anything into anything; beside the rack nothing is crossed.
  EXPECT_TRUE(std::isinf(
      tip_room(config, {100.0, 20.0, -30.0}, rapid_to({100.0, 20.0, -15.0}, 1)).length));
  EXPECT_TRUE(std::isinf(
      tip_room(config, {20.0, 150.0, -15.0}, rapid_to({300.0, 150.0, -15.0}, 1)).length));
}

TEST(TipRoom, shouldLeaveOutThePocketServedOnItsApproachAndStraightDownIntoIt) {
  const Config config = top_rack();
  Step into = rapid_to({100.0, 20.0, -80.0}, 1);
  into.pocket = 2;
  EXPECT_TRUE(std::isinf(tip_room(config, {100.0, 20.0, -20.0}, into).length)) << "straight down";
  into.pocket = 3;
  EXPECT_DOUBLE_EQ(tip_room(config, {100.0, 20.0, -20.0}, into).length, -20.0)
      << "another pocket's column is no way in";
}

TEST(CheckMove, shouldRefuseATipIntoAHolderNamingToolPocketAndWhatToChange) {
  const Config config = top_rack();
  // Out of pocket 1's column and over pocket 2's: its own holder is the first hit.
  const Step back = rapid_to({125.0, 20.0, -15.0}, 1);
  const auto problems = check_move(config, {50.0, 20.0, -15.0}, axis_xyz, back, std::nullopt, 80.0);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems.front(),
            "carries T1 (length 80.0000 mm) with its tip 35.0000 mm below the top of the holder "
            "at pocket 1: raise safe Z or pocket_above_clearance_offset_z, use the side approach, "
            "or place safe away from over the rack");
  EXPECT_TRUE(check_move(config, {50.0, 20.0, -15.0}, axis_xyz, back, std::nullopt, 45.0).empty())
      << "a tip that just clears the tops";
  EXPECT_TRUE(check_move(config, {50.0, 20.0, -15.0}, axis_xyz, rapid_to({125.0, 20.0, -15.0}, 0),
                         std::nullopt, 80.0)
                  .empty())
      << "an empty spindle carries nothing";
}

// ---------------------------------------------------------------- every sequence

TEST(CarriedSequences, shouldFindTheLongestToolThePocketsSequencesCarry) {
  const Config config = top_rack();
  const SequencesChecked checked = check_sequences(config, std::nullopt);
  EXPECT_TRUE(checked.violations.empty()) << describe(checked.violations.front());
  ASSERT_EQ(checked.room.count(1), 1u);
  EXPECT_DOUBLE_EQ(checked.room.at(1).length, 45.0) << describe(checked.room.at(1));
  EXPECT_DOUBLE_EQ(longest_carried(config, checked), 40.0)
      << "no longer than what crosses the holders at above-clearance";
}

TEST(CarriedSequences, shouldNameEveryStepATableToolTooLongForItsPocketWouldHit) {
  const Config config = top_rack();
  ToolLengths lengths;
  lengths.table = {{1, 80.0}, {2, 30.0}, {3, -12.0}};
  const SequencesChecked checked = check_sequences(config, std::nullopt, lengths);
  ASSERT_FALSE(checked.violations.empty());
  for (const auto& violation : checked.violations) {
    EXPECT_NE(violation.sequence.find("T1"), std::string::npos) << describe(violation);
    EXPECT_NE(violation.what.find("carries T1 (length 80.0000 mm)"), std::string::npos)
        << describe(violation);
  }
}

// ---------------------------------------------------------------- the running changer

struct TopRig {
  explicit TopRig(double t1_length, bool rehearsed = true) : config(top_rack()) {
    changer = std::make_unique<Changer>(config, sim, ToolState::fresh(config));
    ToolLengths lengths;
    lengths.table = {{1, t1_length}, {2, 30.0}};
    lengths.longest = 40.0;
    changer->keepout_lengths(lengths);
    if (rehearsed) changer->rehearse_with(&dry_run);
    changer->ready();
  }
  Config config;
  Simulator sim;
  DryRun dry_run;
  std::unique_ptr<Changer> changer;
};

TEST(CarriedByTheChanger, shouldRefuseAChangeBeforeItMovesWhereTheToolWouldHitAHolder) {
  TopRig rig(80.0);
  rig.changer->tool_change(1);
  rig.sim.run(*rig.changer);
  EXPECT_FALSE(has_motion(rig.sim)) << "nothing moved";
  const std::string said = errors(rig.sim);
  EXPECT_NE(said.find("M6 T1 refused: its step "), std::string::npos) << said;
  EXPECT_NE(said.find("carries T1 (length 80.0000 mm)"), std::string::npos) << said;
  EXPECT_NE(said.find("(rapid to safe XY): carries T1"), std::string::npos) << said;
  EXPECT_NE(said.find("holder at pocket 1"), std::string::npos) << said;
  EXPECT_NE(said.find("nothing moved"), std::string::npos) << said;
  ASSERT_FALSE(rig.sim.steps().empty());
  EXPECT_EQ(rig.sim.steps().back().kind, StepKind::fail) << "the program ends, with the words";
  EXPECT_EQ(rig.changer->tools().spindle, 0);
  EXPECT_TRUE(rig.changer->tools().holds(1)) << "nothing in the rack touched";
  EXPECT_NE(rig.changer->status().phase, Phase::fault) << "refused, not faulted";
}

TEST(CarriedByTheChanger, shouldChangeToAToolThatClearsTheHolders) {
  TopRig rig(30.0);
  rig.changer->tool_change(1);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.changer->tools().spindle, 1) << errors(rig.sim);
  EXPECT_EQ(errors(rig.sim), "");
}

TEST(CarriedByTheChanger, shouldCountAToolOfNoLengthAsTheLongestTheConfigAllows) {
  TopRig rig(-12.0);  // a table written relative to a master tool
  rig.changer->tool_change(1);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.changer->tools().spindle, 1) << "40 mm clears the holders: " << errors(rig.sim);
}

TEST(CarriedByTheChanger, shouldRefuseLoadUnloadAndMeasureTheSameWay) {
  {
    TopRig rig(80.0);
    rig.changer->unload(1);
    rig.sim.run(*rig.changer);
    EXPECT_FALSE(has_motion(rig.sim));
    EXPECT_NE(errors(rig.sim).find("unload of tool 1 refused: its step"), std::string::npos)
        << errors(rig.sim);
  }
  {
    TopRig rig(80.0);
    rig.changer->measure_all({1});
    rig.sim.run(*rig.changer);
    EXPECT_FALSE(has_motion(rig.sim));
    EXPECT_NE(errors(rig.sim).find("refused: its step"), std::string::npos) << errors(rig.sim);
  }
}

TEST(CarriedByTheChanger, shouldRehearseTheWayStraightUpOutOfAPocketAfterAFault) {
  // A sequence cut off in pocket 2 left the spindle in its column: the next
  // change leaves straight up, which enters nothing.
  TopRig rig(30.0);
  rig.changer->machine_at(Point{100.0, 20.0, -70.0});
  rig.changer->tool_change(1);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.changer->tools().spindle, 1) << errors(rig.sim);
}

TEST(CarriedByTheChanger, shouldStopAtTheMoveWhenNothingRehearsedIt) {
  // The second layer: the move itself is checked as it is published.
  TopRig rig(80.0, false);
  rig.changer->tool_change(1);
  rig.sim.run(*rig.changer);
  const std::string said = errors(rig.sim);
  EXPECT_NE(said.find("unsafe step not sent"), std::string::npos) << said;
  EXPECT_NE(said.find("carries T1 (length 80.0000 mm)"), std::string::npos) << said;
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
}

}  // namespace
}  // namespace fatc
