// The executor link and the changer together, the way the component joins
// them, against a fake executor that follows nc_files/fixed_atc_probe_execute.ngc.
// Prints the timeline of one M6 (pins in, events, what the changer does, pins
// out) so that the handshake can be read as it happens.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "core/machine/changer.hpp"
#include "core/protocol/executor_link.hpp"
#include "core/dry_run/simulator.hpp"
#include "link_rig.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::FakeExecutor;
using test::LinkedPorts;
using test::show;

/// A changer on and idle, the spindle stopped, and a program's M6 T2 whose
/// executor has just been called.
class LinkWithChanger : public ::testing::Test {
 protected:
  LinkWithChanger() {
    changer.ready();
    changer.spindle_stopped(true);
    in.interpreter_idle = false;  // a program runs
    in.number = 2;                // T2 prepared
    executor.call(ExecutorCall::tool_change);
  }
  const Config config = test::valid_config();
  LinkedPorts ports;
  Changer changer{config, ports, ToolState::fresh(config)};
  LinkInputs in;
  FakeExecutor executor{in};
  test::LinkRig rig{ports, changer, in, executor};
};

TEST_F(LinkWithChanger, shouldPerformThePlannedStepsInOrderAndAnswerIocontrolWhenOneM6Runs) {
  for (int turn = 0; turn < 2000 && executor.running; ++turn) rig.turn();

  // The builtin M6 at the end of the remap: iocontrol's level handshake.
  in.tool_change = true;
  ports.link.read(in, ports.now);
  const bool changed = ports.link.write(changer.status().phase == Phase::idle).changed;
  ports.log.push_back("in: tool-change 1 -> out: changed " + std::to_string(changed));
  in.tool_change = false;
  ports.link.read(in, ports.now);
  const bool dropped = !ports.link.write(true).changed;
  ports.log.push_back("in: tool-change 0 -> out: changed " + std::to_string(!dropped));

  for (const auto& line : ports.log) std::cout << line << "\n";

  std::vector<std::string> planned;
  for (const Step& step : plan_change(config, 0, 2, 0.0).steps()) planned.push_back(describe(step));
  std::vector<std::string> performed;
  for (const Step& step : executor.performed) performed.push_back(describe(step));
  EXPECT_EQ(performed, planned);
  EXPECT_FALSE(executor.running);
  EXPECT_EQ(changer.tools().spindle, 2);
  EXPECT_TRUE(changed);
  EXPECT_TRUE(dropped);
  EXPECT_TRUE(ports.unexpected_events.empty());
}

// LinuxCNC 2.10 (master) keeps the executor's step-request output high
// through an estop and is on again within ExecutorLink::kAbortGrace: the
// fault matrix's next M6 took the step still offered to the dead run and
// moved the machine 70 mm before it was refused.
TEST_F(LinkWithChanger, shouldPerformNoStepOfTheCutOffChangeWhenTheNextM6ComesRightAfterAnEstop) {

  // Up to the second move offered, the executor asking for it: the estop.
  int moves_offered = 0;
  for (int turn = 0; turn < 2000 && moves_offered < 2; ++turn) {
    rig.turn(false);
    if (rig.last.step_ready && is_motion(rig.last.step.kind) && in.step_request) {
      if (++moves_offered == 2) break;
    }
    executor.turn(rig.last);
  }
  ASSERT_EQ(moves_offered, 2);
  ASSERT_EQ(executor.performed.size(), 1u);
  executor.running = false;  // the program is gone; motion keeps the request high
  in.interpreter_idle = true;
  rig.machine_not_ready();
  rig.turn();
  ASSERT_EQ(changer.status().phase, Phase::fault) << "cut off during the change";

  // On again at once, and the next M6's executor: its M64 finds the request high.
  changer.ready();
  rig.turn();
  executor.performed.clear();
  in.number = 3;
  in.interpreter_idle = false;
  executor.call(ExecutorCall::tool_change);
  for (int turn = 0; turn < 200 && executor.running; ++turn) rig.turn();

  for (const auto& line : ports.log) std::cout << line << "\n";
  std::vector<std::string> performed;
  for (const Step& step : executor.performed) performed.push_back(describe(step));
  ASSERT_EQ(performed.size(), 2u) << ::testing::PrintToString(performed);
  EXPECT_EQ(executor.performed.front().kind, StepKind::resync);
  EXPECT_EQ(executor.performed.back().kind, StepKind::fail);
  EXPECT_EQ(executor.performed.back().label.rfind("M6 T3 refused: the changer is in fault", 0), 0u)
      << executor.performed.back().label;
  EXPECT_FALSE(executor.running);
  EXPECT_EQ(changer.status().phase, Phase::fault);
  EXPECT_TRUE(ports.unexpected_events.empty());
}

}  // namespace
}  // namespace fatc
