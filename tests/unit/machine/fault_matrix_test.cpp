// The fault matrix of the core: an M6 from tool 1 to tool 2 cut off at every
// step of its plan by every way a sequence can end early. Each case must end
// faulted with the chuck closed, the spindle flagged uncertain (saved so),
// M6 and the operator flows refused until the operator confirms, and the
// confirmation must give an idle changer that believes what it was told.
// The real LinuxCNC runs the same matrix in tests/integration/faults/fault_matrix.py.
#include <gtest/gtest.h>

#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "core/machine/changer.hpp"
#include "core/dry_run/simulator.hpp"
#include "link_rig.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

constexpr int kFrom = 1;
constexpr int kTo = 2;

ToolState holding(const Config& config, int tool) {
  ToolState tools = ToolState::fresh(config);
  tools.spindle = tool;
  test::take_out(tools, tool);
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

/// Where the handshake stands at one turn: who asked, who offered, which step.
struct Phase4 {
  bool request = false;
  bool ready = false;
  int step = 0;
  bool operator==(const Phase4& o) const {
    return request == o.request && ready == o.ready && step == o.step;
  }
};

/// An M6 from tool 1 to tool 2 through the link, against the fake executor.
struct LinkedChange {
  explicit LinkedChange(const Config& config)
      : changer(config, ports, holding(config, kFrom)), executor(in) {
    changer.ready();
    changer.spindle_stopped(true);
    in.interpreter_idle = false;
    in.number = kTo;
    executor.call(ExecutorCall::tool_change);
  }
  Phase4 phase() const {
    return {in.step_request, rig.last.step_ready, changer.status().step_number};
  }
  test::LinkedPorts ports;
  Changer changer;
  LinkInputs in;
  test::FakeExecutor executor;
  test::LinkRig rig{ports, changer, in, executor};
};

/// The turns at which the handshake (or the step) changes: every phase of the
/// four-phase handshake of every step, and the first turn of every dwell.
std::vector<int> handshake_turns(const Config& config) {
  LinkedChange change(config);
  std::vector<int> turns;
  Phase4 last{};
  for (int turn = 0; turn < 20000 && change.executor.running; ++turn) {
    change.rig.turn();
    if (!(change.phase() == last)) turns.push_back(turn);
    last = change.phase();
  }
  return turns;
}

TEST(FaultMatrix, shouldFaultSafelyAndChangeAgainWhenTheProgramIsAbortedAtAnyPhaseOfTheHandshake) {
  const Config config = test::valid_config();
  const std::vector<int> turns = handshake_turns(config);
  ASSERT_GT(turns.size(), 30u);
  int phases_seen[2][2] = {};
  int cases = 0;
  for (const int at : turns) {
    for (const bool executor_took_its_turn : {true, false}) {
      SCOPED_TRACE("aborted at turn " + std::to_string(at) +
                   (executor_took_its_turn ? "" : ", before the executor's turn"));
      LinkedChange change(config);
      for (int turn = 0; turn < at; ++turn) change.rig.turn();
      change.rig.turn(executor_took_its_turn);
      const Phase4 cut = change.phase();
      if (!change.changer.status().busy()) continue;  // the change already ended
      phases_seen[cut.request][cut.ready]++;

      // LinuxCNC's Stop: the interpreter goes idle, the executor with it; the
      // request output keeps whatever value the executor left on it.
      change.in.interpreter_idle = true;
      change.executor.running = false;
      for (int turn = 0; turn < 400; ++turn) change.rig.turn();
      EXPECT_EQ(change.changer.status().phase, Phase::fault);
      EXPECT_FALSE(change.ports.chuck_open);
      EXPECT_TRUE(change.changer.tools().uncertain);
      EXPECT_FALSE(change.rig.last.step_ready && change.rig.last.step.kind != StepKind::resync &&
                   change.rig.last.step.kind != StepKind::fail);

      const bool at_pocket = change.changer.cut_off() && change.changer.cut_off()->pocket != 0;
      change.changer.clear_fault(0, at_pocket ? std::optional<bool>(true) : std::nullopt);
      ASSERT_EQ(change.changer.status().phase, Phase::idle);

      // The next program's M6 finds the link clean and changes normally.
      change.in.interpreter_idle = false;
      change.in.number = 3;
      change.executor.performed.clear();
      change.executor.call(ExecutorCall::tool_change);
      for (int turn = 0; turn < 20000 && change.executor.running; ++turn) change.rig.turn();
      EXPECT_FALSE(change.executor.running);
      EXPECT_EQ(change.changer.tools().spindle, 3);
      EXPECT_EQ(change.changer.status().phase, Phase::idle);
      std::vector<std::string> performed, planned;
      for (const Step& step : change.executor.performed) {
        if (step.kind != StepKind::resync) performed.push_back(describe(step));
      }
      for (const Step& step : plan_change(config, 0, 3, 0.0).steps()) {
        planned.push_back(describe(step));
      }
      EXPECT_EQ(performed, planned);
      EXPECT_TRUE(change.ports.unexpected_events.empty());
      ++cases;
    }
  }
  std::cout << cases << " cuts; at request/ready 0/0 " << phases_seen[0][0] << ", 0/1 "
            << phases_seen[0][1] << ", 1/0 " << phases_seen[1][0] << ", 1/1 " << phases_seen[1][1]
            << "\n";
  // Every phase of the handshake was cut at least once.
  for (int request = 0; request < 2; ++request) {
    for (int ready = 0; ready < 2; ++ready) {
      EXPECT_GT(phases_seen[request][ready], 0) << "request " << request << " ready " << ready;
    }
  }
}

}  // namespace
}  // namespace fatc
