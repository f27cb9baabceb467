#include "core/machine/changer.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <memory>

#include "core/dry_run/simulator.hpp"
#include "core/plan/routes.hpp"
#include "sim_lines.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using Lines = std::vector<std::string>;

/// A changer wired to a Simulator; an unexpected event fails the test.
struct Rig {
  explicit Rig(int spindle = 0, std::set<int> out_of_machine = {})
      : Rig(test::valid_config(), spindle, std::move(out_of_machine)) {}
  Rig(Config with, int spindle, std::set<int> out_of_machine = {},
      std::map<int, double> lengths = {})
      : config(std::move(with)) {
    ToolState tools = ToolState::fresh(config);
    tools.lengths = std::move(lengths);
    tools.spindle = spindle;
    test::take_out(tools, spindle);
    for (int tool : out_of_machine) test::take_out(tools, tool);
    changer = std::make_unique<Changer>(config, sim, tools);
    changer->ready();
  }
  ~Rig() { EXPECT_TRUE(sim.unexpected_events.empty()) << sim.unexpected_events.front(); }

  /// The records since `from`, compactly: "rapid safe Z", "chuck open", "dwell 0.50", ...
  Lines lines(std::size_t from = 0) const { return test::record_lines(sim, from); }

  /// One event the way the executor, the clock or the operator would give it.
  bool advance_once() {
    if (changer->status().awaiting == Awaiting::operator_choice) {
      changer->operator_continue();
      return true;
    }
    return sim.run(*changer, 1) == 1;
  }

  Config config;
  Simulator sim;
  std::unique_ptr<Changer> changer;
};

Lines concat(std::initializer_list<Lines> parts) {
  Lines all;
  for (const auto& part : parts) all.insert(all.end(), part.begin(), part.end());
  return all;
}

// The sequences of docs/sequences.md, spelled out once, for pocket `t` of the test config.
Lines to_safe() { return {"rapid safe Z", "rapid safe XY"}; }

Lines return_to_pocket(int t) {
  const std::string p = std::to_string(t);
  return concat(
      {to_safe(),
       {"rapid over the side of pocket " + p, "rapid side of pocket " + p, "feed pocket " + p,
        "chuck open", "dwell 0.50", "rapid above-chuck of pocket " + p, "chuck close",
        "rapid above-clearance of pocket " + p},
       to_safe()});
}

/// Retrieval after a return, which already ended at safe.
Lines retrieve_from_safe(int t) {
  const std::string p = std::to_string(t);
  return concat({{"rapid over pocket " + p, "rapid above-clearance of pocket " + p,
                  "rapid above-chuck of pocket " + p, "chuck open", "dwell 0.20", "chuck close",
                  "dwell 0.20", "chuck open", "dwell 0.50", "feed pocket " + p, "dwell 0.50",
                  "chuck close", "dwell 0.50", "feed side of pocket " + p},
                 to_safe()});
}

Lines retrieve(int t) { return concat({to_safe(), retrieve_from_safe(t)}); }

Lines flush() { return {"chuck open", "dwell 0.20", "chuck close", "dwell 0.20"}; }
Lines at_loading() { return {"rapid loading Z", "rapid loading XY"}; }

// ---------------------------------------------------------------- M6

TEST(Change, shouldAnswerAtOnceWithoutMotionWhenTheToolIsAlreadyInTheSpindle) {
  Rig rig(3);
  rig.changer->tool_change(3);
  EXPECT_EQ(rig.lines(), (Lines{"done T3"}));
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
}

TEST(Change, shouldAnswerAtOnceForT0WithAnEmptySpindle) {
  Rig rig(0);
  rig.changer->tool_change(0);
  EXPECT_EQ(rig.lines(), (Lines{"done T0"}));
}

TEST(Change, shouldRetrieveIntoAnEmptySpindle) {
  Rig rig(0);
  rig.changer->tool_change(4);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({retrieve(4), {"done T4"}}));
  EXPECT_EQ(rig.changer->tools().spindle, 4);
  EXPECT_FALSE(rig.changer->tools().holds(4));
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
}

TEST(Change, shouldReturnThenRetrieveFromAToB) {
  Rig rig(2);
  rig.changer->tool_change(5);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({return_to_pocket(2), retrieve_from_safe(5), {"done T5"}}));
  EXPECT_EQ(rig.changer->tools().spindle, 5);
  EXPECT_TRUE(rig.changer->tools().holds(2));
  EXPECT_FALSE(rig.sim.chuck_open);
}

TEST(Change, shouldOnlyReturnForT0) {
  Rig rig(6);
  rig.changer->tool_change(0);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({return_to_pocket(6), {"done T0"}}));
  EXPECT_EQ(rig.changer->tools().spindle, 0);
}

TEST(Change, shouldSaveWhatIsUnderWayBeforeItMovesAndWhereTheToolsAreAfterEachChange) {
  Rig rig(2);
  rig.changer->tool_change(5);
  rig.sim.run(*rig.changer);
  // Each save, in order: what runs, what it does, the spindle, and whether
  // the pockets of the two tools hold them; then the record before it.
  Lines saves;
  std::size_t first_move = 0;
  for (std::size_t i = 0; i < rig.sim.records.size(); ++i) {
    const Record& r = rig.sim.records[i];
    if (r.kind == Record::Kind::step && first_move == 0) first_move = i;
    if (r.kind != Record::Kind::save) continue;
    const ToolState& t = r.saved;
    std::string line = t.in_progress ? t.in_progress->sequence + ": " + t.in_progress->step : "-";
    line += " | spindle " + std::to_string(t.spindle) + " | pocket 2 " +
            (t.holds(2) ? "full" : "empty") + ", pocket 5 " +
            (t.holds(5) ? "full" : "empty");
    saves.push_back(line);
    if (saves.size() == 2) {
      EXPECT_EQ(first_move, 0u) << "the return was recorded after the machine moved";
    }
  }
  EXPECT_EQ(
      saves,
      (Lines{"M6 T5: starting | spindle 2 | pocket 2 empty, pocket 5 full",
             "M6 T5: returning tool 2 to pocket 2 | spindle 2 | pocket 2 empty, pocket 5 full",
             "M6 T5: returning tool 2 to pocket 2 | spindle 0 | pocket 2 full, pocket 5 full",
             "M6 T5: fetching tool 5 from pocket 5 | spindle 0 | pocket 2 full, pocket 5 full",
             "M6 T5: fetching tool 5 from pocket 5 | spindle 5 | pocket 2 full, pocket 5 empty",
             "- | spindle 5 | pocket 2 full, pocket 5 empty"}));
}

TEST(Change, shouldOpenTheChuckOnlyAtAPocketOrAboveItsChuck) {
  Rig rig(1);
  rig.changer->tool_change(6);
  rig.sim.run(*rig.changer);
  std::string where;
  for (const auto& record : rig.sim.records) {
    if (record.kind == Record::Kind::step && is_motion(record.step.kind)) where = record.step.label;
    if (record.kind == Record::Kind::chuck && record.chuck_open) {
      EXPECT_TRUE(where.rfind("pocket ", 0) == 0 || where.rfind("above-chuck of pocket", 0) == 0)
          << "chuck opened at " << where;
    }
  }
}

TEST(Change, shouldMoveSlowlyOnlyIntoAndOutOfThePocket) {
  Rig rig(1);
  rig.changer->tool_change(6);
  rig.sim.run(*rig.changer);
  for (const auto& step : rig.sim.motion_steps()) {
    const bool slow =
        step.label.rfind("pocket ", 0) == 0 || step.label.rfind("side of pocket", 0) == 0;
    if (step.kind == StepKind::feed) {
      EXPECT_TRUE(slow) << step.label;
      EXPECT_EQ(step.feed, rig.config.pocket_feed);
    }
  }
}

struct Refusal {
  const char* name;
  int spindle;
  std::set<int> out;
  int tool;
  const char* why;
  const char* extra_config = "";
};
std::ostream& operator<<(std::ostream& out, const Refusal& r) { return out << r.name; }

class RefusedChange : public ::testing::TestWithParam<Refusal> {};

TEST_P(RefusedChange, shouldFailTheExecutorWithAMessageAndMoveNothing) {
  Rig rig(test::valid_config(GetParam().extra_config), GetParam().spindle, GetParam().out);
  rig.changer->tool_change(GetParam().tool);
  ASSERT_EQ(rig.sim.steps().size(), 1u);
  EXPECT_EQ(rig.sim.steps()[0].kind, StepKind::fail);
  EXPECT_NE(rig.sim.steps()[0].label.find(GetParam().why), std::string::npos)
      << rig.sim.steps()[0].label;
  ASSERT_EQ(rig.sim.messages(MessageKind::error).size(), 1u);
  EXPECT_NE(rig.sim.messages(MessageKind::error)[0].find(GetParam().why), std::string::npos);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rig.changer->tools().spindle, GetParam().spindle);
}

// clang-format off
INSTANTIATE_TEST_SUITE_P(Each, RefusedChange, ::testing::Values(
  Refusal{"no_pocket", 0, {}, 9, "tool 9 is in no pocket of the rack (and manual_tools is off)",
          R"("manual_tools": false)"},
  Refusal{"negative", 0, {}, -1, "T-1 is not a tool number"},
  Refusal{"unloaded", 0, {4}, 4, "tool 4 belongs in pocket 4 but is not in it; load it first"},
  Refusal{"spindle_tool_without_pocket", 9, {}, 2, "tool 9 in the spindle has no pocket to go to",
          R"("manual_tools": false)"}
));
// clang-format on

TEST(Change, shouldRefuseWhenTheMachineIsNotReady) {
  Rig rig(0);
  rig.changer->not_ready();
  rig.changer->tool_change(2);
  ASSERT_EQ(rig.sim.steps().size(), 1u);
  EXPECT_EQ(rig.sim.steps()[0].kind, StepKind::fail);
  EXPECT_NE(rig.sim.steps()[0].label.find("not on and homed"), std::string::npos);
}

TEST(Change, shouldRefuseASecondRequestWhileBusyAndFinishTheFirst) {
  Rig rig(0);
  rig.changer->tool_change(2);
  rig.advance_once();
  rig.changer->tool_change(3);
  rig.changer->load(3);
  EXPECT_EQ(rig.sim.messages(MessageKind::error).size(), 2u);
  EXPECT_NE(rig.sim.messages(MessageKind::error)[0].find("busy"), std::string::npos);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.changer->tools().spindle, 2);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
}

TEST(Change, shouldWaitForTheSpindleToStopBeforeMovingWhenToldNotToMoveMeanwhile) {
  Rig rig(test::valid_config(R"("move_while_spindle_stops": false)"), 0);
  rig.changer->spindle_stopped(false);
  rig.changer->tool_change(2);
  EXPECT_EQ(rig.changer->status().awaiting, Awaiting::spindle);
  EXPECT_TRUE(rig.sim.motion_steps().empty());
  rig.changer->spindle_stopped(true);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.changer->tools().spindle, 2);
}

TEST(Change, shouldRiseAndCrossAtSafeZWhileTheSpindleRunsDownThenGoOnFromThere) {
  Rig rig(2);
  rig.changer->spindle_stopped(false);
  rig.changer->tool_change(5);
  rig.sim.run(*rig.changer);
  // Then it waits for the spindle, at most spindle_stop_timeout_seconds.
  EXPECT_EQ(rig.lines(), (Lines{"rapid safe Z", "rapid safe XY", "rapid over the side of pocket 2",
                                "dwell 10.00"}));
  EXPECT_EQ(rig.changer->status().awaiting, Awaiting::spindle);
  EXPECT_FALSE(rig.sim.chuck_open);
  const std::size_t stood = rig.sim.records.size();
  rig.changer->spindle_stopped(true);
  rig.sim.run(*rig.changer);
  // The return walks on from over the side: what it would have walked first is done.
  Lines rest = return_to_pocket(2);
  rest.erase(rest.begin(), rest.begin() + 3);
  EXPECT_EQ(rig.lines(stood), concat({rest, retrieve_from_safe(5), {"done T5"}}));
  EXPECT_EQ(rig.changer->tools().spindle, 5);
}

TEST(Change, shouldCrossOverThePocketToFetchFromWhileTheSpindleRunsDownOnTheDirectPath) {
  Rig rig(test::valid_config(R"("path": "direct")"), 0);
  rig.changer->spindle_stopped(false);
  rig.changer->tool_change(4);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), (Lines{"rapid safe Z", "rapid over pocket 4", "dwell 10.00"}));
  const std::size_t stood = rig.sim.records.size();
  rig.changer->spindle_stopped(true);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(stood).at(0), "rapid above-chuck of pocket 4") << "not over the pocket again";
  EXPECT_EQ(rig.changer->tools().spindle, 4);
}

TEST(Change, shouldOnlyRiseWhileTheSpindleRunsDownUnderARackCover) {
  Rig rig(test::valid_config(R"("rack_cover": {})"), 2);
  rig.changer->spindle_stopped(false);
  rig.changer->tool_change(5);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), (Lines{"rapid safe Z", "dwell 10.00"}))
      << "the cover's shape is not known: not across";
}

TEST(Change, shouldStandStillWhileTheSpindleRunsDownBeforeAHandoverAtLoading) {
  Rig rig(0);
  rig.changer->spindle_stopped(false);
  rig.changer->tool_change(20);
  rig.sim.run(*rig.changer);
  EXPECT_TRUE(rig.sim.motion_steps().empty()) << "the operator's hand meets the spindle there";
  EXPECT_EQ(rig.changer->status().awaiting, Awaiting::spindle);
}

TEST(Change, shouldFaultWhenTheSpindleDoesNotStopInTimeWithNothingEntered) {
  Rig rig(1);
  rig.changer->spindle_stopped(false);
  rig.changer->tool_change(2);
  rig.sim.run(*rig.changer);
  ASSERT_EQ(rig.changer->status().awaiting, Awaiting::spindle);
  rig.changer->timer_elapsed();
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
  for (const Step& step : rig.sim.motion_steps()) {
    EXPECT_TRUE(!(step.axes & axis_z) || step.target.z == rig.config.safe.z) << describe(step);
  }
  EXPECT_FALSE(rig.sim.chuck_open);
  EXPECT_EQ(rig.sim.steps().back().kind, StepKind::fail);
  EXPECT_FALSE(rig.changer->tools().uncertain) << "nothing entered, the spindle still holds tool 1";
  EXPECT_NE(rig.sim.messages(MessageKind::error).back().find("did not stop"), std::string::npos);
}

// ---------------------------------------------------------------- load and probe

constexpr double kSensorZ = -70.0;

TEST(Load, shouldLoadProbeAndPutAwayWithAnEmptySpindle) {
  Rig rig(0, {4});
  rig.sim.sensor_z = kSensorZ;
  rig.changer->load(4);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({at_loading(), flush(), {"wait operator"}}));
  EXPECT_EQ(rig.changer->status().phase, Phase::loading);
  EXPECT_EQ(rig.changer->status().awaiting, Awaiting::operator_choice);
  const std::size_t inserted = rig.sim.records.size();
  rig.changer->operator_continue();
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(inserted), (Lines{"set-tool T4", "wait operator"}));
  const std::size_t jogged = rig.sim.records.size();
  rig.changer->operator_continue();
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(jogged), concat({{"probe touch-off sensor (seek)", "feed back off the sensor",
                                        "probe touch-off sensor (latch)", "set-length tool table",
                                        "rapid retract from the sensor"},
                                       return_to_pocket(4),
                                       {"set-tool T0", "done T0"}}));
  EXPECT_DOUBLE_EQ(rig.changer->tools().lengths.at(4),
                   kSensorZ - rig.config.probe_length_compensation_offset);
  EXPECT_EQ(rig.changer->tools().spindle, 0);
  EXPECT_TRUE(rig.changer->tools().holds(4));
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rig.sim.messages(MessageKind::info).back(), "tool 4 measured 25.0000 mm, in pocket 4");
}

TEST(Load, shouldWriteTheLengthItMeasuredIntoTheToolTableStep) {
  Rig rig(0, {4});
  rig.sim.sensor_z = kSensorZ;
  rig.changer->load(4);
  for (int i = 0; i < 3; ++i) {
    rig.sim.run(*rig.changer);
    if (rig.changer->status().awaiting == Awaiting::operator_choice)
      rig.changer->operator_continue();
  }
  for (const auto& step : rig.sim.steps()) {
    if (step.kind != StepKind::set_tool_length) continue;
    EXPECT_EQ(step.tool, 4);
    EXPECT_DOUBLE_EQ(step.value, 25.0);  // -70 - (-95)
  }
}

TEST(Load, shouldReturnTheToolInTheSpindleFirst) {
  Rig rig(2, {4});
  rig.sim.sensor_z = kSensorZ;
  rig.changer->load(4);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({return_to_pocket(2), at_loading(), flush(), {"wait operator"}}));
}

TEST(Load, shouldGoStraightToProbingWhenTheToolIsAlreadyInTheSpindle) {
  Rig rig(4);
  rig.sim.sensor_z = kSensorZ;
  rig.changer->load(4);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({at_loading(), {"wait operator"}}));
  EXPECT_NE(rig.changer->status().activity.find("Jog"), std::string::npos);
}

TEST(Load, shouldLeaveTheSpindleEmptyWhenCancelledBeforeInsertion) {
  Rig rig(0, {4});
  rig.changer->load(4);
  rig.sim.run(*rig.changer);
  const std::size_t before = rig.sim.records.size();
  rig.changer->operator_cancel();
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(before), (Lines{"set-tool T0", "done T0"}));
  EXPECT_EQ(rig.changer->tools().spindle, 0);
  EXPECT_TRUE(rig.changer->tools().lengths.empty());
  EXPECT_NE(rig.sim.messages(MessageKind::info).back().find("the spindle is empty"),
            std::string::npos);
}

TEST(Load, shouldKeepTheToolInTheSpindleUnmeasuredWhenCancelledBeforeProbing) {
  Rig rig(0, {4});
  rig.changer->load(4);
  rig.sim.run(*rig.changer);
  rig.changer->operator_continue();
  rig.sim.run(*rig.changer);
  const std::size_t before = rig.sim.records.size();
  rig.changer->operator_cancel();
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(before), (Lines{"set-tool T4", "done T4"}));
  EXPECT_EQ(rig.changer->tools().spindle, 4);
  EXPECT_TRUE(rig.changer->tools().lengths.empty());
  EXPECT_NE(rig.sim.messages(MessageKind::info).back().find("tool 4 is in the spindle"),
            std::string::npos);
}

TEST(Load, shouldRetractAndWriteNothingWhenTheSensorIsNeverTouched) {
  Rig rig(4);
  rig.changer->load(4);  // sim.sensor_z unset: the probe misses
  rig.sim.run(*rig.changer);
  const std::size_t before = rig.sim.records.size();
  rig.changer->operator_continue();
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(before),
            (Lines{"probe touch-off sensor (seek)", "rapid loading Z", "set-tool T4", "done T4"}));
  EXPECT_TRUE(rig.changer->tools().lengths.empty());
  EXPECT_NE(rig.sim.messages(MessageKind::error).back().find("did not touch the sensor"),
            std::string::npos);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
}

TEST(Load, shouldWriteNothingWhenTheLatchStageMisses) {
  Rig rig(4);
  rig.changer->load(4);
  rig.sim.run(*rig.changer);
  rig.changer->operator_continue();
  rig.changer->probe_result(true, kSensorZ);  // the seek touches ...
  rig.changer->in_position();                 // ... the back-off ends ...
  rig.changer->probe_result(false, -90.0);    // ... and the latch misses
  rig.sim.run(*rig.changer);
  EXPECT_TRUE(rig.changer->tools().lengths.empty());
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
}

struct LoadRefusal {
  const char* name;
  int spindle;
  std::set<int> out;
  int tool;
  const char* why;
};
std::ostream& operator<<(std::ostream& out, const LoadRefusal& r) { return out << r.name; }
class RefusedLoad : public ::testing::TestWithParam<LoadRefusal> {};

TEST_P(RefusedLoad, shouldSayWhyAndMoveNothing) {
  Rig rig(GetParam().spindle, GetParam().out);
  rig.changer->load(GetParam().tool);
  EXPECT_TRUE(rig.sim.steps().empty());
  ASSERT_EQ(rig.sim.messages(MessageKind::error).size(), 1u);
  EXPECT_EQ(rig.sim.messages(MessageKind::error)[0],
            "load of tool " + std::to_string(GetParam().tool) + " refused: " + GetParam().why);
}

// clang-format off
INSTANTIATE_TEST_SUITE_P(Each, RefusedLoad, ::testing::Values(
  LoadRefusal{"no_pocket", 0, {}, 9, "no pocket for tool 9: every pocket holds a tool; unload one first"},
  LoadRefusal{"zero", 0, {}, 0, "load needs a tool number above 0, got 0"},
  LoadRefusal{"already_in_rack", 0, {}, 3, "tool 3 is already in pocket 3; unload it first"},
  LoadRefusal{"spindle_tool_homeless", 9, {3}, 3, "tool 9 in the spindle has no pocket to go to; unload it, or load tool 9 again to measure it into a pocket"}
));
// clang-format on

TEST(Load, shouldRefuseWhileTheSpindleTurns) {
  Rig rig(0, {4});
  rig.changer->spindle_stopped(false);
  rig.changer->load(4);
  EXPECT_TRUE(rig.sim.steps().empty());
  EXPECT_EQ(rig.sim.messages(MessageKind::error).at(0),
            "load of tool 4 refused: the spindle is turning; stop it first");
}

// ---------------------------------------------------------------- unload

TEST(Unload, shouldFetchTheToolAndLetTheOperatorTakeIt) {
  Rig rig(0);
  rig.changer->unload(3);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({retrieve(3), at_loading(), {"set-tool T3", "wait operator"}}));
  const std::size_t before = rig.sim.records.size();
  rig.changer->operator_continue();
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(before), concat({flush(), {"set-tool T0", "done T0"}}));
  EXPECT_EQ(rig.changer->tools().spindle, 0);
  EXPECT_FALSE(rig.changer->tools().holds(3));
}

TEST(Unload, shouldReturnTheToolInTheSpindleFirst) {
  Rig rig(1);
  rig.changer->unload(3);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({return_to_pocket(1),
                                 retrieve_from_safe(3),
                                 at_loading(),
                                 {"set-tool T3", "wait operator"}}));
}

TEST(Unload, shouldGoStraightToLoadingWhenTheToolIsInTheSpindle) {
  Rig rig(3);
  rig.changer->unload(3);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({at_loading(), {"set-tool T3", "wait operator"}}));
}

TEST(Unload, shouldKeepTheToolInTheSpindleWhenCancelled) {
  Rig rig(3);
  rig.changer->unload(3);
  rig.sim.run(*rig.changer);
  rig.changer->operator_cancel();
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.changer->tools().spindle, 3);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rig.lines().back(), "done T3");
}

TEST(Unload, shouldRefuseAToolThatIsNotInTheRack) {
  Rig rig(0, {3});
  rig.changer->unload(3);
  EXPECT_TRUE(rig.sim.steps().empty());
  EXPECT_EQ(rig.sim.messages(MessageKind::error).at(0),
            "unload of tool 3 refused: tool 3 is not in the rack");
}

// ---------------------------------------------------------------- faults

struct Flow {
  const char* name;
  int spindle;
  std::set<int> out;
  std::function<void(Changer&)> start;
  const char* extra_config = "";
};
std::ostream& operator<<(std::ostream& out, const Flow& f) { return out << f.name; }

class EveryState : public ::testing::TestWithParam<Flow> {};

/// Aborts after 0, 1, 2, ... events, so that every state of the flow is hit.
TEST_P(EveryState, shouldFaultSafelyOnAbort) {
  int states = 0;
  for (int cut = 0;; ++cut) {
    Rig rig(test::valid_config(GetParam().extra_config), GetParam().spindle, GetParam().out);
    rig.sim.sensor_z = kSensorZ;
    GetParam().start(*rig.changer);
    bool more = true;
    for (int i = 0; i < cut && more; ++i) more = rig.advance_once();
    if (!more || rig.changer->status().phase == Phase::idle) break;
    ++states;
    const int spindle_before = rig.changer->tools().spindle;
    rig.changer->abort("program aborted");
    EXPECT_EQ(rig.changer->status().phase, Phase::fault) << "cut " << cut;
    EXPECT_FALSE(rig.sim.chuck_open) << "cut " << cut;
    EXPECT_TRUE(rig.changer->tools().uncertain) << "cut " << cut;
    EXPECT_EQ(rig.changer->tools().spindle, spindle_before);
    EXPECT_FALSE(rig.sim.timer_armed);
    EXPECT_EQ(rig.sim.steps().back().kind, StepKind::fail);
    const auto errors = rig.sim.messages(MessageKind::error);
    EXPECT_NE(errors.back().find("program aborted"), std::string::npos) << errors.back();
    EXPECT_NE(errors.back().find("not certain"), std::string::npos) << errors.back();

    rig.changer->tool_change(1);
    EXPECT_EQ(rig.sim.steps().back().kind, StepKind::fail) << "M6 is refused while faulted";
    rig.changer->clear_fault(2);
    EXPECT_EQ(rig.changer->status().phase, Phase::idle);
    EXPECT_EQ(rig.changer->tools().spindle, 2);
    EXPECT_FALSE(rig.changer->tools().uncertain);
  }
  EXPECT_GT(states, 5);
}

// clang-format off
INSTANTIATE_TEST_SUITE_P(Each, EveryState, ::testing::Values(
  Flow{"change_a_to_b", 1, {}, [](Changer& c) { c.tool_change(4); }},
  Flow{"load_with_tool_in_spindle", 1, {5}, [](Changer& c) { c.load(5); }},
  Flow{"unload_with_tool_in_spindle", 1, {}, [](Changer& c) { c.unload(5); }},
  Flow{"change_and_check", 1, {}, [](Changer& c) { c.tool_change(4); }, R"("probe_after_change": "check")"},
  Flow{"manual_to_manual_and_measure", 9, {}, [](Changer& c) { c.tool_change(8); },
       R"("probe_after_change": "measure")"}
));
// clang-format on

TEST(Fault, shouldFaultWhenTheMachineGoesOffDuringASequence) {
  Rig rig(1);
  rig.changer->tool_change(2);
  rig.advance_once();
  rig.changer->not_ready();
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
  EXPECT_TRUE(rig.changer->tools().uncertain);
  rig.changer->clear_fault(1);
  EXPECT_EQ(rig.changer->status().phase, Phase::not_ready)
      << "cleared, but the machine is still off";
  rig.changer->ready();
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
}

TEST(Fault, shouldAcceptNotReadyAtStartUp) {
  Simulator sim;
  const Config config = test::valid_config();
  Changer changer(config, sim, ToolState::fresh(config));
  changer.not_ready();
  EXPECT_TRUE(sim.unexpected_events.empty());
  EXPECT_EQ(changer.status().phase, Phase::not_ready);
}

TEST(Fault, shouldIgnoreAnAbortWhileIdle) {
  Rig rig(1);
  rig.changer->abort("program aborted");
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_FALSE(rig.changer->tools().uncertain);
}

TEST(Fault, shouldStartInFaultWhenTheSavedStateIsUncertain) {
  Simulator sim;
  ToolState tools = ToolState::fresh(test::valid_config());
  tools.uncertain = true;
  const Config config = test::valid_config();
  Changer changer(config, sim, tools);
  EXPECT_EQ(changer.status().phase, Phase::not_ready);
  changer.ready();
  EXPECT_EQ(changer.status().phase, Phase::fault);
}

TEST(Fault, shouldGoToNotReadyWhenTheMachineGoesOffWhileIdle) {
  Rig rig(1);
  rig.changer->not_ready();
  EXPECT_EQ(rig.changer->status().phase, Phase::not_ready);
  EXPECT_FALSE(rig.changer->tools().uncertain);
}

TEST(Fault, shouldReportAStrayEventAsABug) {
  Simulator sim;
  const Config config = test::valid_config();
  Changer changer(config, sim, ToolState::fresh(config));
  changer.ready();
  changer.in_position();  // nothing was published
  ASSERT_EQ(sim.unexpected_events.size(), 1u);
  EXPECT_NE(sim.unexpected_events[0].find("InPosition"), std::string::npos);
}

TEST(Operator, shouldIgnoreContinueWhenNothingWaits) {
  Rig rig(1);
  rig.changer->operator_continue();
  rig.changer->operator_cancel();
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rig.sim.messages(MessageKind::info).size(), 2u);
}

TEST(Diagram, shouldNameEveryFlowAndStateOfTheTables) {
  const std::string dot = Changer::dot();
  for (const char* name :
       {"ChangeFlow", "LoadFlow", "UnloadFlow", "ReturnLeg<Before>", "RetrieveLeg", "FlushLeg",
        "ProbingLeg", "IntoPocket", "GrippingTool", "AwaitingTool", "Faulted", "MachineNotReady",
        "HandOutLeg", "HandInLeg", "MeasureLeg", "AwaitingRemoval", "Stopped"}) {
    EXPECT_NE(dot.find(name), std::string::npos) << name;
  }
  EXPECT_EQ(dot.rfind("digraph", 0), 0u);
}

}  // namespace
}  // namespace fatc

namespace fatc {
namespace {

TEST(Load, shouldSayTheSensorWasAlreadyTrippedAndWriteNothing) {
  Simulator sim;
  const Config config = test::valid_config();
  ToolState tools = ToolState::fresh(config);
  tools.spindle = 4;
  test::take_out(tools, 4);
  Changer changer(config, sim, tools);
  changer.ready();
  changer.load(4);
  sim.run(changer);
  changer.operator_continue();
  sim.pending.reset();
  changer.probe_result(false, -10.0, true);
  sim.run(changer);
  EXPECT_TRUE(changer.tools().lengths.empty());
  EXPECT_NE(sim.messages(MessageKind::error).back().find("already tripped"), std::string::npos);
  EXPECT_EQ(changer.status().phase, Phase::idle);
  EXPECT_TRUE(sim.unexpected_events.empty());
}

}  // namespace
}  // namespace fatc

namespace fatc {
namespace {

// ---------------------------------------------------------------- probe after change

Lines measure_at_sensor(bool writes) {
  Lines lines{"rapid loading Z", "rapid over the touch-off sensor", "probe touch-off sensor (seek)",
              "feed back off the sensor", "probe touch-off sensor (latch)"};
  if (writes) lines.push_back("set-length tool table");
  lines.push_back("rapid retract from the sensor");
  lines.push_back("rapid safe Z");
  return lines;
}

TEST(MeasureRule, shouldMeasureAndWriteTheRetrievedTool) {
  Rig rig(test::valid_config(R"("probe_after_change": "measure")"), 0);
  rig.sim.sensor_z = kSensorZ;
  rig.changer->tool_change(4);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({retrieve(4), measure_at_sensor(true), {"done T4"}}));
  EXPECT_DOUBLE_EQ(rig.changer->tools().lengths.at(4), 25.0);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
}

TEST(MeasureRule, shouldPassACheckWithinToleranceAndWriteNothing) {
  Rig rig(test::valid_config(R"("probe_after_change": "check", "probe_check_tolerance": 0.05)"), 0,
          {}, {{4, 25.04}});
  rig.sim.sensor_z = kSensorZ;
  rig.changer->tool_change(4);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({retrieve(4), measure_at_sensor(false), {"done T4"}}));
  EXPECT_DOUBLE_EQ(rig.changer->tools().lengths.at(4), 25.04);
  EXPECT_EQ(rig.sim.messages(MessageKind::info).back(),
            "tool 4 measures 25.0000 mm, stored 25.0400 mm");
}

TEST(MeasureRule, shouldFaultWhenTheCheckedLengthDiffers) {
  Rig rig(test::valid_config(R"("probe_after_change": "check")"), 0, {}, {{4, 30.0}});
  rig.sim.sensor_z = kSensorZ;
  rig.changer->tool_change(4);
  rig.sim.run(*rig.changer);
  const Simulator& sim = rig.sim;
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
  EXPECT_EQ(sim.steps().back().kind, StepKind::fail);
  EXPECT_NE(sim.steps().back().label.find("tool 4 measures 25.0000 mm but its stored length is "
                                          "30.0000 mm, 5.0000 mm shorter (probe_check_tolerance "
                                          "0.1000 mm): tool broken or pulled out?"),
            std::string::npos)
      << sim.steps().back().label;
  EXPECT_DOUBLE_EQ(rig.changer->tools().lengths.at(4), 30.0) << "a check never writes";
  EXPECT_EQ(rig.changer->tools().spindle, 4);
  EXPECT_FALSE(sim.chuck_open);
}

TEST(MeasureRule, shouldMeasureAToolNeverMeasuredWhenChecking) {
  Rig rig(test::valid_config(R"("probe_after_change": "check")"), 0);
  rig.sim.sensor_z = kSensorZ;
  rig.changer->tool_change(4);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({retrieve(4), measure_at_sensor(true), {"done T4"}}));
  EXPECT_DOUBLE_EQ(rig.changer->tools().lengths.at(4), 25.0);
}

TEST(MeasureRule, shouldFaultWhenTheToolCannotBeMeasured) {
  Rig rig(test::valid_config(R"("probe_after_change": "measure")"), 0);
  rig.changer->tool_change(4);  // sim.sensor_z unset: the probe misses
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
  EXPECT_NE(rig.sim.steps().back().label.find("tool 4 could not be measured after the change"),
            std::string::npos);
  EXPECT_TRUE(rig.changer->tools().lengths.empty());
}

TEST(MeasureRule, shouldNotLetCancelStopAProbeInsideAProgram) {
  Rig rig(test::valid_config(R"("probe_after_change": "measure")"), 0);
  rig.changer->tool_change(4);
  while (rig.changer->status().awaiting != Awaiting::probe) ASSERT_TRUE(rig.advance_once());
  rig.changer->operator_cancel();
  EXPECT_EQ(rig.changer->status().awaiting, Awaiting::probe);
  EXPECT_EQ(rig.sim.messages(MessageKind::info).back(),
            "Cancel: nothing is waiting for the operator");
}

// ---------------------------------------------------------------- each tool's own rule (tools)

/// The valid config where tool 4 has `tools.4` as given.
Config with_tool4(const std::string& tool4, const std::string& extra = "") {
  return test::valid_config(R"("tools": {"4": )" + tool4 + "}" + (extra.empty() ? "" : "," + extra));
}

bool measured(const Lines& lines) {
  return std::find(lines.begin(), lines.end(), "probe touch-off sensor (seek)") != lines.end();
}

TEST(MeasureRule, shouldMeasureANewToolOnceAndThenTrustItsLength) {
  Rig rig(with_tool4(R"({"measure": "new"})"), 0);
  rig.sim.sensor_z = kSensorZ;
  rig.changer->tool_change(4);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({retrieve(4), measure_at_sensor(true), {"done T4"}}));
  std::size_t from = rig.sim.records.size();
  rig.changer->tool_change(5);  // probe_after_change "off": not measured
  rig.sim.run(*rig.changer);
  EXPECT_FALSE(measured(rig.lines(from)));
  from = rig.sim.records.size();
  rig.changer->tool_change(4);
  rig.sim.run(*rig.changer);
  EXPECT_FALSE(measured(rig.lines(from))) << "measured once, when new";
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
}

TEST(MeasureRule, shouldMeasureAnAlwaysToolAtEveryChangeWhateverTheDefault) {
  Rig rig(with_tool4(R"({"measure": "always"})"), 0, {}, {{4, 25.0}});
  rig.sim.sensor_z = kSensorZ;
  for (int round = 0; round < 2; ++round) {
    const std::size_t from = rig.sim.records.size();
    rig.changer->tool_change(4);
    rig.sim.run(*rig.changer);
    EXPECT_TRUE(measured(rig.lines(from))) << "change " << round + 1;
    rig.changer->tool_change(0);
    rig.sim.run(*rig.changer);
  }
}

TEST(MeasureRule, shouldNeverTakeANeverToolToTheSensorAtAChange) {
  Rig rig(with_tool4(R"({"measure": "never"})", R"("probe_after_change": "always")"), 0);
  rig.sim.sensor_z = kSensorZ;
  rig.changer->tool_change(4);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({retrieve(4), {"done T4"}}));
  EXPECT_TRUE(rig.changer->tools().lengths.empty());
}

TEST(MeasureRule, shouldPutANeverToolAwayAtALoadWithoutMeasuringIt) {
  Rig rig(with_tool4(R"({"measure": "never"})"), 0, {4});
  rig.sim.sensor_z = kSensorZ;
  rig.changer->load(4);
  rig.sim.run(*rig.changer);
  const std::size_t inserted = rig.sim.records.size();
  rig.changer->operator_continue();
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(inserted),
            concat({{"set-tool T4"}, return_to_pocket(4), {"set-tool T0", "done T0"}}));
  EXPECT_TRUE(rig.changer->tools().holds(4));
  EXPECT_TRUE(rig.changer->tools().lengths.empty());
  EXPECT_EQ(rig.sim.messages(MessageKind::info).back(),
            "tool 4 not measured (\"never\": LinuxCNC's tool table length), in pocket 4");
}

TEST(MeasureRule, shouldPutANeverToolAlreadyInTheSpindleStraightAway) {
  Rig rig(with_tool4(R"({"measure": "never"})"), 4);
  rig.changer->load(4);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({return_to_pocket(4), {"set-tool T0", "done T0"}}));
  EXPECT_TRUE(rig.changer->tools().holds(4));
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
}

TEST(MeasureRule, shouldSayWhyMeasureAllHasNothingToMeasure) {
  Rig rig(with_tool4(R"({"measure": "never"})"), 0, {5});
  rig.changer->measure_all({4, 5});
  EXPECT_EQ(rig.sim.messages(MessageKind::error).back(),
            "measure all (2 tools) refused: no tool to measure (not in the rack: T5; measured "
            "never (\"never\"): T4)");
}

TEST(MeasureRule, shouldLeaveANeverToolOutOfMeasureAll) {
  Rig rig(with_tool4(R"({"measure": "never"})"), 0);
  rig.sim.sensor_z = kSensorZ;
  rig.changer->measure_all({4, 5});
  rig.sim.run(*rig.changer);
  const Lines lines = rig.lines();
  EXPECT_EQ(std::count(lines.begin(), lines.end(), "probe touch-off sensor (seek)"), 1);
  EXPECT_EQ(rig.changer->tools().lengths.count(4), 0u);
  EXPECT_EQ(rig.changer->tools().lengths.count(5), 1u);
  const auto said = rig.sim.messages(MessageKind::info);
  EXPECT_NE(std::find(said.begin(), said.end(),
                      "measure all skips what is never measured (\"never\": LinuxCNC's tool table "
                      "length): T4"),
            said.end());
}

TEST(MeasureRule, shouldCheckEachToolAgainstItsOwnTolerance) {
  // 0.3 mm off: within tools.4's 0.5, beyond probe_check_tolerance's 0.1.
  Rig within(with_tool4(R"({"measure": "check", "check_tolerance": 0.5})"), 0, {}, {{4, 25.3}});
  within.sim.sensor_z = kSensorZ;
  within.changer->tool_change(4);
  within.sim.run(*within.changer);
  EXPECT_EQ(within.changer->status().phase, Phase::idle);
  // 2 mm shorter than stored: broken.
  Rig broken(with_tool4(R"({"measure": "check", "check_tolerance": 0.05})"), 0, {}, {{4, 27.0}});
  broken.sim.sensor_z = kSensorZ;
  broken.changer->tool_change(4);
  broken.sim.run(*broken.changer);
  EXPECT_EQ(broken.changer->status().phase, Phase::fault);
  EXPECT_NE(broken.sim.steps().back().label.find(
                "tool 4 measures 25.0000 mm but its stored length is 27.0000 mm, 2.0000 mm "
                "shorter (tools.4.check_tolerance 0.0500 mm): tool broken or pulled out?"),
            std::string::npos)
      << broken.sim.steps().back().label;
  EXPECT_DOUBLE_EQ(broken.changer->tools().lengths.at(4), 27.0) << "a check never writes";
}

TEST(ToolKind, shouldMeasureAProbeAtItsOwnSlowFeed) {
  Rig rig(with_tool4(R"({"kind": "probe", "measure": "always"})",
                     R"("probe_seek_feed": 3000, "probe_latch_feed": 60)"),
          0);
  rig.sim.sensor_z = kSensorZ;
  rig.changer->tool_change(4);
  rig.sim.run(*rig.changer);
  int probes = 0;
  for (const Step& step : rig.sim.steps()) {
    if (step.kind != StepKind::probe && step.label != "back off the sensor") continue;
    EXPECT_DOUBLE_EQ(step.feed, 60.0) << step.label;
    probes += step.kind == StepKind::probe;
  }
  EXPECT_EQ(probes, 2);
}

/// The probe steps and the back-off of a run: "label@feed->z".
Lines probing_of(const std::vector<Step>& steps) {
  Lines probing;
  for (const Step& step : steps) {
    if (step.kind != StepKind::probe && step.label != "back off the sensor") continue;
    char line[96];
    std::snprintf(line, sizeof line, "%s@%g->%g", step.label.c_str(), step.feed, step.target.z);
    probing.push_back(line);
  }
  return probing;
}

TEST(ToolKind, shouldGoDownFastToTheWindowAboveWhereAProbesLengthPutsTheTouch) {
  Rig rig(with_tool4(R"({"kind": "probe", "measure": "always"})",
                     R"("probe_seek_feed": 3000, "probe_latch_feed": 60)"),
          0);
  rig.changer->keepout_lengths(ToolLengths{{{4, 25.0}}, 40.0});
  rig.sim.sensor_z = kSensorZ;  // a 25 mm tool touches here
  rig.changer->tool_change(4);
  rig.sim.run(*rig.changer);
  // 25 - 95 + probe_window 10: fast to Z-60, the last 10 mm at the probe's feed.
  EXPECT_EQ(probing_of(rig.sim.steps()),
            (Lines{"touch-off sensor (approach)@3000->-60", "touch-off sensor (seek)@60->-90",
                   "back off the sensor@60->-68", "touch-off sensor (latch)@60->-90"}));
  EXPECT_DOUBLE_EQ(rig.changer->tools().lengths.at(4), 25.0);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
}

TEST(ToolKind, shouldRefuseATouchOnTheFastApproach) {
  // The table says 10 mm, the probe is 25: it meets the sensor at Z-70 at
  // probe_seek_feed, above where the approach was to end (Z-75).
  Rig rig(with_tool4(R"({"kind": "probe", "measure": "always"})",
                     R"("probe_seek_feed": 3000, "probe_latch_feed": 60)"),
          0);
  rig.changer->keepout_lengths(ToolLengths{{{4, 10.0}}, 40.0});
  rig.sim.sensor_z = kSensorZ;
  rig.changer->tool_change(4);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(probing_of(rig.sim.steps()), (Lines{"touch-off sensor (approach)@3000->-75"}));
  EXPECT_EQ(rig.changer->tools().lengths.count(4), 0u) << "nothing written";
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
  const std::string said = rig.sim.messages(MessageKind::error).front();
  EXPECT_NE(said.find("tool 4 touched the sensor at Z -70.0000 mm on the fast approach "
                      "(probe_seek_feed), which was to end at Z -75.0000 mm: it is longer than "
                      "10.0000 mm (LinuxCNC's tool table) by more than probe_window 10.0000 mm"),
            std::string::npos)
      << said;
}

TEST(ToolKind, shouldApproachFromTheLongestToolTheConfigAllowsWithoutALength) {
  Rig rig(with_tool4(R"({"kind": "probe", "measure": "always"})",
                     R"("probe_seek_feed": 3000, "probe_latch_feed": 60)"),
          0);
  rig.changer->keepout_lengths(ToolLengths{{}, 40.0});
  rig.sim.sensor_z = kSensorZ;
  rig.changer->tool_change(4);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(probing_of(rig.sim.steps()).front(), "touch-off sensor (approach)@3000->-45");
}

TEST(ToolKind, shouldNotApproachWhereTheSeekIsAsFastOrNoLengthIsKnown) {
  // A cutter seeks at probe_seek_feed already.
  Rig cutter(with_tool4(R"({"measure": "always"})"), 0);
  cutter.changer->keepout_lengths(ToolLengths{{{4, 25.0}}, 40.0});
  cutter.sim.sensor_z = kSensorZ;
  cutter.changer->tool_change(4);
  cutter.sim.run(*cutter.changer);
  EXPECT_EQ(probing_of(cutter.sim.steps()).front(), "touch-off sensor (seek)@300->-90");
  // No table, no longest tool: nothing says where it may touch.
  const Config probe = with_tool4(R"({"kind": "probe"})");
  EXPECT_FALSE(plan::probe_approach_z(probe, 4, 0.0, -10.0));
  // The spindle already jogged down to within a back-off of it: nothing to save.
  EXPECT_FALSE(plan::probe_approach_z(probe, 4, 25.0, -59.0));
  EXPECT_DOUBLE_EQ(*plan::probe_approach_z(probe, 4, 25.0, -57.0), -60.0);
  // Where the approach would end below probe_limit, the seek goes alone:
  // 3 - 95 + a window of 1 is Z-91, under probe_limit's Z-90.
  const Config narrow = with_tool4(R"({"kind": "probe"})", R"("probe_window": 1)");
  EXPECT_FALSE(plan::probe_approach_z(narrow, 4, 3.0, -10.0));
  EXPECT_DOUBLE_EQ(*plan::probe_approach_z(narrow, 4, 6.0, -10.0), -88.0);
  EXPECT_FALSE(plan::probe_approach_z(probe, 4, 25.0, std::nullopt));
}

TEST(ToolKind, shouldCapBothProbingStagesAtAToolsProbeFeed) {
  const Config config = with_tool4(R"({"probe_feed": 40})", R"("probe_latch_feed": 60)");
  EXPECT_DOUBLE_EQ(config.seek_feed_of(4), 40.0);
  EXPECT_DOUBLE_EQ(config.latch_feed_of(4), 40.0);
  EXPECT_DOUBLE_EQ(config.seek_feed_of(5), config.probe_seek_feed);
  EXPECT_DOUBLE_EQ(config.latch_feed_of(5), 60.0);
}

TEST(ToolKind, shouldSayEachToolsRuleInAFewWords) {
  const Config config = test::valid_config(
      R"("probe_after_change": "new", "tools": {"3": {"measure": "check", "check_tolerance": 0.05},
         "7": {"measure": "always"}, "12": {"measure": "never"}, "99": {"kind": "probe"}})");
  EXPECT_EQ(rule_words(config, 7), "measured");
  EXPECT_EQ(rule_words(config, 3), "checked ±0.05");
  EXPECT_EQ(rule_words(config, 12), "never measured (tool table length)");
  EXPECT_EQ(rule_words(config, 99), "probe, spindle held, measured if new");
  EXPECT_EQ(rule_words(config, 5), "measured if new");
  EXPECT_EQ(rule_said(config, 12), "tools.12.measure is \"never\"");
  EXPECT_EQ(rule_said(config, 5), "probe_after_change is \"new\"");
  EXPECT_TRUE(config.is_probe(99));
  EXPECT_FALSE(config.is_probe(7));
}

// ---------------------------------------------------------------- cancel mid-probe (load)

TEST(Load, shouldRetractAndWriteNothingWhenCancelledMidProbe) {
  Rig rig(4);
  rig.sim.sensor_z = kSensorZ;
  rig.changer->load(4);
  rig.sim.run(*rig.changer);
  rig.changer->operator_continue();  // probe now
  ASSERT_EQ(rig.changer->status().awaiting, Awaiting::probe);
  rig.sim.pending.reset();  // the adapter aborts the probe move first
  const std::size_t before = rig.sim.records.size();
  rig.changer->operator_cancel();
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(before), (Lines{"rapid loading Z", "set-tool T4", "done T4"}));
  EXPECT_TRUE(rig.changer->tools().lengths.empty());
  EXPECT_EQ(rig.changer->tools().spindle, 4);
  EXPECT_NE(rig.sim.messages(MessageKind::info)
                .back()
                .find("probe of tool 4 cancelled by the operator; nothing written"),
            std::string::npos);
}

// ---------------------------------------------------------------- manual tools

TEST(Manual, shouldReturnTheRackToolThenHoldForTheManualTool) {
  Rig rig(2);
  rig.changer->tool_change(9);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), concat({return_to_pocket(2), at_loading(), flush()}))
      << "nothing is published at the prompt: the executor keeps the program waiting";
  EXPECT_EQ(rig.changer->status().phase, Phase::changing);
  EXPECT_EQ(rig.changer->status().awaiting, Awaiting::operator_choice);
  EXPECT_NE(rig.sim.messages(MessageKind::prompt).back().find("insert tool 9"), std::string::npos);
  const std::size_t before = rig.sim.records.size();
  rig.changer->operator_continue();
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(before), (Lines{"rapid safe Z", "done T9"}));
  EXPECT_EQ(rig.changer->tools().spindle, 9);
  EXPECT_TRUE(rig.changer->tools().holds(2));
}

TEST(Manual, shouldHandTheManualToolOutBeforeRetrievingARackTool) {
  Rig rig(9);
  rig.changer->tool_change(3);
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(), at_loading());
  EXPECT_NE(rig.sim.messages(MessageKind::prompt).back().find("remove tool 9"), std::string::npos);
  const std::size_t before = rig.sim.records.size();
  rig.changer->operator_continue();
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.lines(before), concat({retrieve(3), {"done T3"}}));
  EXPECT_EQ(rig.changer->tools().spindle, 3);
}

TEST(Manual, shouldSwapOneManualToolForAnother) {
  Rig rig(9);
  rig.changer->tool_change(8);
  while (rig.changer->status().phase == Phase::changing) ASSERT_TRUE(rig.advance_once());
  EXPECT_EQ(rig.lines(),
            concat({at_loading(), at_loading(), flush(), {"rapid safe Z", "done T8"}}));
  EXPECT_EQ(rig.changer->tools().spindle, 8);
}

TEST(Manual, shouldOnlyHandOutForT0) {
  Rig rig(9);
  rig.changer->tool_change(0);
  while (rig.changer->status().phase == Phase::changing) ASSERT_TRUE(rig.advance_once());
  EXPECT_EQ(rig.lines(), concat({at_loading(), {"done T0"}}));
  EXPECT_EQ(rig.changer->tools().spindle, 0);
}

TEST(Manual, shouldMeasureTheManualToolWhenConfigured) {
  Rig rig(test::valid_config(R"("probe_after_change": "measure")"), 0);
  rig.sim.sensor_z = kSensorZ;
  rig.changer->tool_change(9);
  while (rig.changer->status().phase == Phase::changing) ASSERT_TRUE(rig.advance_once());
  EXPECT_EQ(
      rig.lines(),
      concat({at_loading(), flush(), {"rapid safe Z"}, measure_at_sensor(true), {"done T9"}}));
  EXPECT_DOUBLE_EQ(rig.changer->tools().lengths.at(9), 25.0);
}

TEST(Manual, shouldStopTheProgramWithAnEmptySpindleWhenInsertionIsCancelled) {
  Rig rig(2);
  rig.changer->tool_change(9);
  rig.sim.run(*rig.changer);
  const std::size_t before = rig.sim.records.size();
  rig.changer->operator_cancel();
  rig.sim.run(*rig.changer);
  const Lines after = rig.lines(before);
  ASSERT_EQ(after.size(), 2u);
  EXPECT_EQ(after[0], "set-tool T0") << "LinuxCNC still has tool 2 until it is told";
  EXPECT_EQ(rig.sim.steps().back().kind, StepKind::fail);
  EXPECT_EQ(rig.sim.steps().back().label, "M6 T9 cancelled by the operator; the spindle is empty");
  EXPECT_EQ(rig.sim.messages(MessageKind::error).back(),
            "M6 T9 cancelled by the operator; the spindle is empty");
  EXPECT_EQ(rig.changer->status().phase, Phase::idle) << "a cancel is no fault";
  EXPECT_FALSE(rig.changer->tools().uncertain);
  EXPECT_EQ(rig.changer->tools().spindle, 0);
}

TEST(Manual, shouldStopTheProgramKeepingTheToolWhenRemovalIsCancelled) {
  Rig rig(9);
  rig.changer->tool_change(3);
  rig.sim.run(*rig.changer);
  rig.changer->operator_cancel();
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.sim.steps().back().kind, StepKind::fail);
  EXPECT_EQ(rig.sim.steps().back().label,
            "M6 T3 cancelled by the operator; tool 9 is in the spindle");
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rig.changer->tools().spindle, 9);
}

TEST(Manual, shouldRefuseLoadAndUnloadRequestsWhileHolding) {
  Rig rig(0);
  rig.changer->tool_change(9);
  rig.sim.run(*rig.changer);
  rig.changer->load(4);
  EXPECT_NE(rig.sim.messages(MessageKind::error)
                .back()
                .find("load of tool 4 refused: the changer is busy"),
            std::string::npos);
  EXPECT_EQ(rig.changer->status().awaiting, Awaiting::operator_choice);
}

}  // namespace
}  // namespace fatc
