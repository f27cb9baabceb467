// Step by step (issue 44): each move and each chuck action of a sequence
// waits for Continue before it goes out; Cancel there ends it as an abort.
#include <gtest/gtest.h>

#include <functional>
#include <vector>

#include "core/dry_run/simulator.hpp"
#include "core/machine/changer.hpp"
#include "sim_rig.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::Lines;
using Action = ChuckRequest::Action;

bool moves_something(const std::string& line) {
  return line.rfind("rapid ", 0) == 0 || line.rfind("feed ", 0) == 0 ||
         line.rfind("probe ", 0) == 0 || line.rfind("chuck ", 0) == 0;
}

int moving(const Lines& lines) {
  int count = 0;
  for (const auto& line : lines) count += moves_something(line) ? 1 : 0;
  return count;
}

/// What a request did, answered Continue at every wait: all its lines, the
/// --plan number of each step held, and how many moved between two Continues.
struct Walked {
  Lines lines;
  std::vector<int> held;
  std::vector<int> moved_per_continue;
};

Walked walk(test::SimRig& rig, bool step_by_step, const std::function<void(Changer&)>& request) {
  rig.changer->step_by_step(step_by_step);
  request(*rig.changer);
  Walked walked;
  Lines lines = rig.run();
  walked.moved_per_continue.push_back(moving(lines));
  walked.lines = lines;
  for (int turn = 0; turn < 400 && rig.changer->status().awaits_operator(); ++turn) {
    if (rig.sim.asked && rig.sim.asked->kind == Prompt::Kind::step) {
      walked.held.push_back(rig.sim.asked->stop);
      EXPECT_EQ(rig.changer->status().step_number >= rig.sim.asked->stop, true);
    }
    rig.sim.operator_obeys(*rig.changer);
    rig.changer->operator_continue();
    lines = rig.run();
    walked.moved_per_continue.push_back(moving(lines));
    walked.lines.insert(walked.lines.end(), lines.begin(), lines.end());
  }
  return walked;
}

/// The numbers of the moves and chuck actions, counting every record but the
/// saves and the messages, as --plan numbers an M6 (an operator flow's prompt
/// is a message and an executor's wait both: counted once).
std::vector<int> plan_numbers(const Simulator& sim, std::size_t from) {
  std::vector<int> numbers;
  int number = 0;
  for (std::size_t i = from; i < sim.records.size(); ++i) {
    const Record& r = sim.records[i];
    if (r.kind == Record::Kind::save || r.kind == Record::Kind::message) continue;
    ++number;
    if (r.kind == Record::Kind::chuck || (r.kind == Record::Kind::step && is_motion(r.step.kind))) {
      numbers.push_back(number);
    }
  }
  return numbers;
}

/// The first-start rack with the spindle empty and pocket 3 free.
ToolState pocket_3_free(const Config& config) {
  ToolState tools = with_in_spindle(config, 0);
  tools.pockets[3] = {};
  return tools;
}
ToolState spindle_empty(const Config& config) { return with_in_spindle(config, 0); }
ToolState tool_1_in_spindle(const Config& config) { return with_in_spindle(config, 1); }

struct Case {
  const char* name;
  ToolState (*tools)(const Config&);
  std::function<void(Changer&)> request;
  bool blended = false;  ///< the direct path, a run of rapids blended within 10 mm
};

std::vector<Case> every_sequence() {
  return {
      {"M6 T2 with T1", tool_1_in_spindle, [](Changer& c) { c.tool_change(2); }},
      {"M6 T3 with an empty spindle", spindle_empty, [](Changer& c) { c.tool_change(3); }},
      {"load T7 into pocket 3", pocket_3_free, [](Changer& c) { c.load(7, 3); }},
      {"unload T1", tool_1_in_spindle, [](Changer& c) { c.unload(1); }},
      {"verify pocket 3", pocket_3_free, [](Changer& c) { c.verify(3); }},
      {"measure all T1 T2", spindle_empty, [](Changer& c) { c.measure_all({1, 2}); }},
      {"M6 T2 with T1, on the direct path blended", tool_1_in_spindle,
       [](Changer& c) { c.tool_change(2); }, true},
      {"chuck release", spindle_empty,
       [](Changer& c) { c.chuck(Action::release, Point{200, 200, -50}); }},
  };
}

/// Where the simulated touch-off sensor trips.
constexpr double kSensorZ = -70.0;

TEST(StepByStep, shouldHoldEachMoveAndChuckActionOfEverySequenceUntilContinue) {
  for (const Case& each : every_sequence()) {
    SCOPED_TRACE(each.name);
    const Config config =
        each.blended
            ? parse_config(test::sample_config_with(R"({"path": "direct", "blend_tolerance": 10})"))
                  .config.value()
            : test::valid_config();
    test::SimRig plain(config, each.tools(config));
    plain.sim.sensor_z = kSensorZ;
    const std::size_t plain_from = plain.sim.records.size();
    const Walked at_speed = walk(plain, false, each.request);
    test::SimRig stepped(config, each.tools(config));
    stepped.sim.sensor_z = kSensorZ;
    const std::size_t stepped_from = stepped.sim.records.size();
    const Walked step_by_step = walk(stepped, true, each.request);

    EXPECT_EQ(step_by_step.lines, at_speed.lines) << "the same steps, in the same order";
    EXPECT_EQ(stepped.changer->tools(), plain.changer->tools());
    EXPECT_EQ(stepped.changer->status().phase, Phase::idle);
    // One step held for each move and chuck action, numbered as --plan numbers them.
    const std::vector<int> expected = plan_numbers(plain.sim, plain_from);
    EXPECT_FALSE(expected.empty());
    EXPECT_EQ(step_by_step.held, expected);
    // Nothing moved before the first Continue, one step after each.
    EXPECT_EQ(step_by_step.moved_per_continue.front(), 0);
    for (std::size_t i = 1; i < step_by_step.moved_per_continue.size(); ++i) {
      EXPECT_LE(step_by_step.moved_per_continue[i], 1) << "after Continue " << i;
    }
    EXPECT_EQ(plan_numbers(stepped.sim, stepped_from), expected);
  }
}

TEST(StepByStep, shouldShowTheStepsWordsWhereItGoesAndItsFeed) {
  const Config config = test::valid_config();
  test::SimRig rig(config, with_in_spindle(config, 0));
  rig.changer->step_by_step(true);
  rig.changer->tool_change(1);
  EXPECT_EQ(rig.run(), Lines{});
  Status held = rig.changer->status();
  EXPECT_EQ(held.phase, Phase::changing);
  EXPECT_TRUE(held.awaits_operator());
  EXPECT_TRUE(held.holds_program) << "the executor waits, however long the operator thinks";
  EXPECT_EQ(held.activity,
            "Step by step, M6 T1, step 1: rapid to safe Z (Z=-5.000). Press Continue to make it "
            "(Cancel aborts the sequence)");
  EXPECT_FALSE(rig.sim.pending) << "nothing published";

  rig.changer->operator_continue();
  EXPECT_EQ(rig.run(), Lines{"rapid safe Z"});
  EXPECT_EQ(rig.changer->status().activity,
            "Step by step, M6 T1, step 2: rapid to safe XY (X=120.000 Y=80.000). Press Continue "
            "to make it (Cancel aborts the sequence)");
  for (const char* move : {"rapid safe XY", "rapid over pocket 1", "rapid above-clearance of pocket 1",
                           "rapid above-chuck of pocket 1"}) {
    rig.changer->operator_continue();
    EXPECT_EQ(rig.run(), Lines{move});
  }
  EXPECT_EQ(rig.changer->status().activity,
            "Step by step, M6 T1, step 6: open the chuck at pocket 1 (X=50.000 Y=20.000 "
            "Z=-60.000). Press Continue to make it (Cancel aborts the sequence)");
  EXPECT_FALSE(rig.sim.chuck_open);
  EXPECT_FALSE(rig.sim.timer_armed) << "the chuck's dwell starts with the chuck";
  rig.changer->operator_continue();
  EXPECT_EQ(rig.run(), (Lines{"chuck open", "dwell 0.20"}));
  for (int i = 0; i < 2; ++i) {
    rig.changer->operator_continue();
    rig.run();
  }
  EXPECT_EQ(rig.changer->status().activity,
            "Step by step, M6 T1, step 12: feed at F500 to pocket 1 (Z=-80.000). Press Continue "
            "to make it (Cancel aborts the sequence)");
}

TEST(StepByStep, shouldStopBeforeEachMoveOfABlendedRun) {
  const Config config =
      parse_config(test::sample_config_with(R"({"path": "direct", "blend_tolerance": 10})"))
          .config.value();
  test::SimRig rig(config, with_in_spindle(config, 0));
  rig.changer->step_by_step(true);
  rig.changer->tool_change(1);
  rig.run();
  EXPECT_EQ(rig.changer->status().activity,
            "Step by step, M6 T1, step 1: rapid to safe Z (Z=-5.000). Press Continue to make it "
            "(Cancel aborts the sequence)");
  rig.changer->operator_continue();
  EXPECT_EQ(rig.run(), Lines{"rapid safe Z"});
  ASSERT_TRUE(rig.sim.asked);
  EXPECT_EQ(rig.sim.asked->stop, 2);
  rig.changer->operator_continue();
  rig.run();
  ASSERT_TRUE(rig.sim.pending || rig.sim.asked);
  EXPECT_EQ(rig.sim.asked->stop, 3) << "the run's second move stops on its own";
  for (const Record& r : rig.sim.records) {
    if (r.kind == Record::Kind::step) {
      EXPECT_TRUE(r.step.before.empty()) << "no run published whole";
    }
  }
}

TEST(StepByStep, shouldEndAsAnAbortWhenCancelledAtAHeldStep) {
  const Config config = test::valid_config();
  test::SimRig rig(config, with_in_spindle(config, 1));
  rig.changer->step_by_step(true);
  rig.changer->tool_change(2);
  rig.run();
  // On to the first chuck action, the release of tool 1 into its pocket.
  for (int i = 0; i < 40 && !(rig.sim.asked && rig.sim.asked->action == "open the chuck");
       ++i) {
    rig.changer->operator_continue();
    rig.run();
  }
  ASSERT_EQ(rig.sim.asked->action, "open the chuck");
  const ToolState before = rig.changer->tools();
  rig.changer->operator_cancel();
  EXPECT_EQ(rig.run(), (Lines{"chuck close", "fail cancelled by the operator before step " +
                                                 std::to_string(rig.sim.asked->stop) +
                                                 " of M6 T2 (step by step)"}));
  const Status after = rig.changer->status();
  EXPECT_EQ(after.phase, Phase::fault);
  EXPECT_FALSE(rig.sim.chuck_open) << "the chuck left defined: closed";
  EXPECT_EQ(rig.changer->tools().spindle, before.spindle);
  EXPECT_TRUE(rig.changer->tools().uncertain) << "as an abort: the operator confirms";
  // The mode ended with the sequence: clearing the fault closes nothing held.
  rig.changer->clear_fault(1, false);
  rig.run();
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
}

TEST(StepByStep, shouldTakeTheSwitchAtTheStartOfTheNextSequenceOnly) {
  const Config config = test::valid_config();
  test::SimRig rig(config, with_in_spindle(config, 1));
  rig.changer->tool_change(2);
  rig.changer->step_by_step(true);
  rig.run();
  EXPECT_EQ(rig.changer->status().phase, Phase::idle) << "switched on mid-change: no stop in it";
  rig.changer->tool_change(3);
  rig.run();
  EXPECT_TRUE(rig.changer->status().awaits_operator()) << "the next change stops";
  rig.changer->step_by_step(false);
  rig.changer->operator_continue();
  rig.run();
  EXPECT_TRUE(rig.changer->status().awaits_operator()) << "switched off mid-change: it still stops";
}

}  // namespace
}  // namespace fatc
