// The fault matrix of the core: an M6 from tool 1 to tool 2 cut off at every
// step of its plan by every way a sequence can end early. Each case must end
// faulted with the chuck closed, the spindle flagged uncertain (saved so),
// M6 and the operator flows refused until the operator confirms, and the
// confirmation must give an idle changer that believes what it was told.
// The real LinuxCNC runs the same matrix in tests/integration/fault_matrix.py.
#include <gtest/gtest.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/changer.hpp"
#include "core/simulator.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

constexpr int kFrom = 1;
constexpr int kTo = 2;

ToolState holding(const Config& config, int tool) {
  ToolState tools = ToolState::fresh(config);
  tools.spindle = tool;
  tools.in_pocket.erase(tool);
  return tools;
}

/// How many steps (moves, chuck actions, dwells) the plan of the change has.
int plan_length(const Config& config) {
  const Simulator plan = plan_change(config, kFrom, kTo, -60.0);
  int steps = 0;
  for (const Record& record : plan.records) {
    if (record.kind == Record::Kind::chuck || record.kind == Record::Kind::dwell ||
        (record.kind == Record::Kind::step && record.step.kind != StepKind::done)) {
      ++steps;
    }
  }
  return steps;
}

ToolState last_saved(const Simulator& sim) {
  for (auto record = sim.records.rbegin(); record != sim.records.rend(); ++record) {
    if (record->kind == Record::Kind::save) return record->saved;
  }
  ADD_FAILURE() << "nothing was saved";
  return {};
}

struct Fault {
  std::string name;
  std::function<void(Changer&)> strike;
};

const std::vector<Fault>& faults() {
  static const std::vector<Fault> all = {
      {"abort", [](Changer& c) { c.abort("LinuxCNC aborted the program"); }},
      {"estop", [](Changer& c) { c.not_ready(); }},
      {"executor_lost", [](Changer& c) { c.abort("the executor stopped answering"); }},
  };
  return all;
}

TEST(FaultMatrix, shouldNumberTheStepsOfASequenceAsThePlanDoes) {
  const Config config = test::valid_config();
  Simulator sim;
  Changer changer(config, sim, holding(config, kFrom));
  changer.ready();
  changer.tool_change(kTo);
  int seen = 0;
  while (changer.status().busy()) {
    int steps = 0;
    for (const Record& record : sim.records) {
      if (record.kind == Record::Kind::chuck || record.kind == Record::Kind::dwell ||
          record.kind == Record::Kind::step) {
        ++steps;
      }
    }
    EXPECT_EQ(changer.status().step_number, steps);
    seen = steps;
    ASSERT_EQ(sim.run(changer, 1), 1);
  }
  EXPECT_EQ(seen, plan_length(config));
  EXPECT_EQ(changer.status().step_number, 0);
}

/// The steps at which the change waits for something (a move, a dwell): where
/// a fault can arrive. A chuck action waits for nothing; the dwell after it
/// is where a fault finds the chuck as that action left it.
std::vector<int> steps_that_wait(const Config& config) {
  Simulator sim;
  Changer changer(config, sim, holding(config, kFrom));
  changer.ready();
  changer.tool_change(kTo);
  std::vector<int> waits;
  while (changer.status().busy()) {
    waits.push_back(changer.status().step_number);
    if (sim.run(changer, 1) != 1) break;
  }
  return waits;
}

TEST(FaultMatrix, shouldEndFaultedSafeAndUncertainWhereverAChangeIsCutOff) {
  const Config config = test::valid_config();
  const std::vector<int> waits = steps_that_wait(config);
  ASSERT_GT(waits.size(), 15u);
  EXPECT_EQ(waits.back(), plan_length(config));
  int cases = 0;
  for (const Fault& fault : faults()) {
    for (const int at : waits) {
      SCOPED_TRACE(fault.name + " at step " + std::to_string(at));
      Simulator sim;
      Changer changer(config, sim, holding(config, kFrom));
      changer.ready();
      changer.tool_change(kTo);
      while (changer.status().step_number < at) ASSERT_EQ(sim.run(changer, 1), 1);
      ASSERT_EQ(changer.status().step_number, at);

      fault.strike(changer);
      if (fault.name == "estop") changer.ready();
      EXPECT_EQ(changer.status().phase, Phase::fault);
      EXPECT_FALSE(sim.chuck_open);
      EXPECT_TRUE(changer.tools().uncertain);
      EXPECT_EQ(last_saved(sim), changer.tools());
      const std::string said = sim.messages(MessageKind::error).back();
      EXPECT_NE(said.find("not certain"), std::string::npos) << said;

      const std::size_t before = sim.motion_steps().size();
      changer.tool_change(3);
      changer.load(4);
      changer.unload(5);
      EXPECT_EQ(sim.motion_steps().size(), before);
      EXPECT_EQ(changer.status().phase, Phase::fault);
      const auto errors = sim.messages(MessageKind::error);
      ASSERT_GE(errors.size(), 3u);
      for (std::size_t i = errors.size() - 3; i < errors.size(); ++i) {
        EXPECT_NE(errors[i].find("refused"), std::string::npos) << errors[i];
      }

      // The operator looked: the spindle is empty, the pocket holds its tool.
      const bool at_pocket = changer.cut_off() && changer.cut_off()->pocket != 0;
      changer.clear_fault(0, at_pocket ? std::optional<bool>(true) : std::nullopt);
      EXPECT_EQ(changer.status().phase, Phase::idle);
      EXPECT_FALSE(changer.tools().uncertain);
      EXPECT_FALSE(changer.tools().in_progress.has_value());
      EXPECT_EQ(changer.tools().spindle, 0);
      EXPECT_EQ(changer.status().step_number, 0);
      ++cases;
    }
  }
  EXPECT_EQ(cases, static_cast<int>(faults().size() * waits.size()));
}

}  // namespace
}  // namespace fatc
