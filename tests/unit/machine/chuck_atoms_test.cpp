// The chuck atoms: release and clamp from G-code (M310/M311 in the sample
// INI, nc_files/fixed_atc_probe_chuck_*.ngc), with the interlocks of the legs.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/machine/changer.hpp"
#include "core/protocol/executor_link.hpp"
#include "core/dry_run/simulator.hpp"
#include "sim_rig.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::Lines;
using Action = ChuckRequest::Action;

const Point kLoading{20.0, 150.0, -10.0};  // test::kValidConfig's
const Point kOverTheWork{200.0, 200.0, -50.0};

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// Tool `spindle` in the spindle (0: empty), the rest of the rack as at first start.
struct ChuckRig : test::SimRig {
  explicit ChuckRig(int spindle = 0, const Config& c = test::valid_config())
      : SimRig(c, with_in_spindle(c, spindle)) {}
};

TEST(ChuckAtoms, shouldReleaseAnEmptySpindleAnywhereAndHoldItOpen) {
  ChuckRig rig;
  rig.changer->chuck(Action::release, kOverTheWork);
  EXPECT_EQ(rig.run(), (Lines{"chuck open", "dwell 0.50", "done T0"}));
  const Status held = rig.changer->status();
  EXPECT_EQ(held.phase, Phase::idle);
  EXPECT_FALSE(held.accepting) << "the panel offers no load while the chuck is open";
  EXPECT_TRUE(has(held.activity, "the chuck is open (released from G-code)")) << held.activity;
  EXPECT_TRUE(rig.sim.chuck_open);
  EXPECT_EQ(rig.last_message(), "chuck released (G-code); clamp it before other work");
}

TEST(ChuckAtoms, shouldRefuseEveryOtherRequestWhileTheChuckIsHeldOpen) {
  ChuckRig rig;
  rig.changer->chuck(Action::release, kOverTheWork);
  rig.run();
  rig.changer->tool_change(3);
  EXPECT_EQ(rig.run(), (Lines{"fail M6 T3 refused: the chuck is open (released from G-code); clamp "
                              "it first (o<fixed_atc_probe_chuck_clamp> call, or the M-code the "
                              "INI remaps to it)"}));
  rig.changer->load(7);
  EXPECT_TRUE(has(rig.last_message(), "load of tool 7 refused: the chuck is open"))
      << rig.last_message();
  EXPECT_TRUE(rig.sim.chuck_open) << "a refusal moves nothing";
}

TEST(ChuckAtoms, shouldClampAndTakeWorkAgain) {
  ChuckRig rig;
  rig.changer->chuck(Action::release, kOverTheWork);
  rig.run();
  rig.changer->chuck(Action::clamp, kOverTheWork);
  EXPECT_EQ(rig.run(), (Lines{"chuck close", "dwell 0.50", "done T0"}));
  EXPECT_TRUE(rig.changer->status().accepting);
  EXPECT_FALSE(rig.sim.chuck_open);
  rig.changer->tool_change(3);
  const Lines change = rig.run();
  ASSERT_FALSE(change.empty());
  EXPECT_EQ(change.back(), "done T3");
}

TEST(ChuckAtoms, shouldRefuseToDropARecordedToolAwayFromLoading) {
  ChuckRig rig(3);
  rig.changer->chuck(Action::release, kOverTheWork);
  EXPECT_EQ(rig.run(),
            (Lines{"fail chuck release refused: tool 3 is in the spindle and would drop; release "
                   "it only at loading (X20.000 Y150.000 Z-10.000 mm) or with the spindle empty; "
                   "the machine is at X200.000 Y200.000 Z-50.000 mm"}));
  EXPECT_FALSE(rig.sim.chuck_open);
  EXPECT_TRUE(rig.changer->status().accepting);
}

TEST(ChuckAtoms, shouldRefuseToDropARecordedToolWhereLinuxcncSaysNothingOfThePosition) {
  ChuckRig rig(3);
  rig.changer->chuck(Action::release, std::nullopt);
  const Lines lines = rig.run();
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_TRUE(has(lines[0], "(LinuxCNC does not say where the machine is)")) << lines[0];
}

TEST(ChuckAtoms, shouldReleaseARecordedToolAtLoadingWithinTheToleranceAndKeepItsRecord) {
  ChuckRig rig(3);
  rig.changer->chuck(Action::release, Point{20.04, 149.96, -10.03});
  EXPECT_EQ(rig.run(), (Lines{"chuck open", "dwell 0.50", "done T3"}));
  EXPECT_EQ(rig.changer->tools().spindle, 3);
  EXPECT_TRUE(has(rig.last_message(), "tool 3 stays recorded in the spindle"))
      << rig.last_message();

  ChuckRig off(3);
  off.changer->chuck(Action::release, Point{20.0, 150.0, -10.06});
  EXPECT_EQ(off.run().size(), 1u) << "0.06 mm off loading is not at loading";
  EXPECT_FALSE(off.sim.chuck_open);
}

TEST(ChuckAtoms, shouldRefuseAReleaseWhileTheSpindleIsOn) {
  ChuckRig rig;
  rig.changer->spindle_stopped(false);
  rig.changer->chuck(Action::release, kOverTheWork);
  EXPECT_EQ(rig.run(),
            (Lines{"fail chuck release refused: the spindle is on; stop it first (M5)"}));
  EXPECT_FALSE(rig.sim.chuck_open);
}

TEST(ChuckAtoms, shouldRefuseAReleaseWithoutAir) {
  ChuckRig rig(0, test::valid_config(R"("sensors": {"air_pressure": true})"));
  rig.sim.rack.air = false;
  rig.sim.report_sensors(*rig.changer);
  rig.changer->chuck(Action::release, kOverTheWork);
  EXPECT_EQ(rig.run(), (Lines{"fail chuck release refused: air pressure is low (air-pressure-ok "
                              "off): the chuck cannot open"}));
}

TEST(ChuckAtoms, shouldWaitForZeroSpeedBeforeOpening) {
  ChuckRig rig(0, test::valid_config(R"("sensors": {"zero_speed": true})"));
  rig.sim.rack.spindle_still = false;
  rig.sim.report_sensors(*rig.changer);
  rig.changer->chuck(Action::release, kOverTheWork);
  EXPECT_EQ(rig.changer->status().phase, Phase::chuck);
  EXPECT_EQ(rig.changer->status().activity,
            "waiting for the spindle to stop before the chuck opens for the release from G-code");
  EXPECT_FALSE(rig.sim.chuck_open);
  rig.sim.rack.spindle_still = true;
  rig.sim.report_sensors(*rig.changer);
  // The wait armed its timer (spindle_stop_timeout_seconds); zero speed came first.
  EXPECT_EQ(rig.run(), (Lines{"dwell 10.00", "chuck open", "dwell 0.50", "done T0"}));
}

TEST(ChuckAtoms, shouldFaultWhenTheDrawbarDoesNotOpen) {
  ChuckRig rig(0, test::valid_config(R"("sensors": {"drawbar_open": true})"));
  rig.sim.rack.drawbar_jammed = true;
  rig.changer->chuck(Action::release, kOverTheWork);
  const Lines lines = rig.run();
  ASSERT_FALSE(lines.empty());
  EXPECT_TRUE(has(lines.back(),
                  "fail the drawbar did not open for the release from G-code within "
                  "1.0 s (drawbar-open off)"))
      << lines.back();
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
  EXPECT_FALSE(rig.sim.chuck_open) << "a fault closes the chuck";
}

TEST(ChuckAtoms, shouldFaultWhenTheDrawbarDoesNotClose) {
  ChuckRig rig(0, test::valid_config(R"("sensors": {"drawbar_closed": true})"));
  rig.changer->chuck(Action::release, kOverTheWork);
  rig.run();
  rig.sim.rack.drawbar_jammed = true;
  rig.changer->chuck(Action::clamp, kOverTheWork);
  const Lines lines = rig.run();
  ASSERT_FALSE(lines.empty());
  EXPECT_TRUE(has(lines.back(), "the drawbar did not close for the clamp from G-code"))
      << lines.back();
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
}

TEST(ChuckAtoms, shouldCloseAHeldChuckWhenTheMachineGoesOffAndAskWhatTheSpindleHolds) {
  ChuckRig rig;
  rig.changer->chuck(Action::release, kOverTheWork);
  rig.run();
  rig.changer->not_ready();
  EXPECT_EQ(rig.run(), (Lines{"chuck close"}));
  EXPECT_TRUE(has(rig.last_message(),
                  "the chuck, left released by G-code, closed: the machine "
                  "went off; say what the spindle holds"))
      << rig.last_message();
  EXPECT_TRUE(rig.changer->tools().uncertain) << "a hand may have been at the spindle";
  rig.changer->ready();
  rig.run();
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
  rig.changer->clear_fault(0);
  rig.run();
  EXPECT_TRUE(rig.changer->status().accepting);
}

TEST(ChuckAtoms, shouldRecordTheHeldChuckSoThatARestartAsksWhatTheSpindleHolds) {
  ChuckRig rig;
  rig.changer->chuck(Action::release, kOverTheWork);
  rig.run();
  ASSERT_TRUE(rig.changer->tools().in_progress.has_value());
  EXPECT_EQ(rig.changer->tools().in_progress->step, "the chuck held open (released from G-code)");
  EXPECT_TRUE(rig.changer->status().chuck_held);
  rig.changer->chuck(Action::clamp, kOverTheWork);
  rig.run();
  EXPECT_FALSE(rig.changer->tools().in_progress.has_value());
  EXPECT_FALSE(rig.changer->status().chuck_held);
}

TEST(ChuckAtoms, shouldHoldTheChuckOpenThroughAnAbort) {
  ChuckRig rig;
  rig.changer->chuck(Action::release, kOverTheWork);
  rig.run();
  rig.changer->abort("LinuxCNC aborted the program during the sequence");
  EXPECT_TRUE(rig.run().empty()) << "nothing moves on an abort";
  EXPECT_TRUE(rig.sim.chuck_open);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_TRUE(rig.changer->status().chuck_held);
}

TEST(ChuckAtoms, shouldLetTheOperatorTakeARecordedToolOutThenAskAfterTheClamp) {
  ChuckRig rig(3, test::valid_config(R"("sensors": {"tool_present": true})"));
  rig.changer->chuck(Action::release, kLoading);
  EXPECT_EQ(rig.run(), (Lines{"chuck open", "dwell 0.50", "done T3"}));
  rig.sim.report_sensors(*rig.changer);  // the tool is out: tool-present off
  rig.run();
  EXPECT_EQ(rig.changer->status().phase, Phase::idle) << "no fault with the hand at the spindle";
  EXPECT_TRUE(rig.sim.chuck_open);
  rig.changer->chuck(Action::clamp, kLoading);
  const Lines clamp = rig.run();
  const Status after = rig.changer->status();
  EXPECT_EQ(after.phase, Phase::fault);
  EXPECT_TRUE(has(after.activity,
                  "after the clamp from G-code tool-present reads the spindle "
                  "empty (off), but tool 3 is recorded in it"))
      << after.activity;
  ASSERT_FALSE(clamp.empty());
  EXPECT_EQ(clamp.back().rfind("fail ", 0), 0u)
      << "the clamp's executor fails its program before it goes on: " << clamp.back();
  EXPECT_TRUE(rig.changer->tools().uncertain);
}

TEST(ChuckAtoms, shouldCheckToolPresentAfterEveryClampBeforeTheProgramGoesOn) {
  ChuckRig rig(0, test::valid_config(R"("sensors": {"tool_present": true})"));
  rig.changer->chuck(Action::clamp, kOverTheWork);
  EXPECT_EQ(rig.run(), (Lines{"chuck close", "dwell 0.50", "done T0"}))
      << "an empty spindle that reads empty";
}

TEST(ChuckAtoms, shouldRefuseWithAFailStepWhenTheMachineIsNotReadyOrFaulted) {
  ChuckRig rig;
  rig.changer->not_ready();
  rig.run();
  rig.changer->chuck(Action::clamp, kOverTheWork);
  EXPECT_EQ(rig.run(), (Lines{"fail chuck clamp refused: the machine is not on and homed, or is "
                              "in estop"}));

  ChuckRig faulted(0, test::valid_config(R"("sensors": {"drawbar_open": true})"));
  faulted.sim.rack.drawbar_jammed = true;
  faulted.changer->chuck(Action::release, kOverTheWork);
  faulted.run();
  ASSERT_EQ(faulted.changer->status().phase, Phase::fault);
  faulted.changer->chuck(Action::clamp, kOverTheWork);
  const Lines lines = faulted.run();
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_TRUE(has(lines[0],
                  "fail chuck clamp refused: the changer is in fault (the drawbar did "
                  "not open"))
      << lines[0];
}

TEST(ChuckAtoms, shouldRefuseASecondAtomWhileTheFirstWaits) {
  ChuckRig rig(0, test::valid_config(R"("sensors": {"zero_speed": true})"));
  rig.sim.rack.spindle_still = false;
  rig.sim.report_sensors(*rig.changer);
  rig.changer->chuck(Action::release, kOverTheWork);
  rig.changer->chuck(Action::clamp, kOverTheWork);
  const Lines lines = rig.run();
  EXPECT_NE(std::find(lines.begin(), lines.end(),
                      "fail chuck clamp refused: the changer is busy with the chuck"),
            lines.end())
      << testing::PrintToString(lines);
}

TEST(ChuckAtoms, shouldReachTheChangerFromTheExecutorCalls) {
  ExecutorLink link;
  const auto t0 = ExecutorLink::Time{};
  LinkInputs in;
  in.interpreter_idle = false;
  in.step_request = true;
  in.call = static_cast<int>(ExecutorCall::chuck_release);
  auto events = link.read(in, t0);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, LinkEvent::Kind::chuck_release);

  ExecutorLink other;
  in.call = static_cast<int>(ExecutorCall::chuck_clamp);
  events = other.read(in, t0);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, LinkEvent::Kind::chuck_clamp);

  ExecutorLink busy;  // an operator flow's step waits for its MDI run
  busy.publish(failure_step("a fault's step, stale"));
  in.call = static_cast<int>(ExecutorCall::chuck_release);
  events = busy.read(in, t0);
  ASSERT_EQ(events.size(), 1u) << "a stale fail step is no flow's: the release goes on";
  EXPECT_EQ(events[0].kind, LinkEvent::Kind::chuck_release);
  ExecutorLink flowing;
  Step next;
  next.kind = StepKind::rapid;
  next.label = "safe Z";
  flowing.publish(next);
  events = flowing.read(in, t0);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, LinkEvent::Kind::refused_call);
  EXPECT_EQ(events[0].reason,
            "chuck release refused: the changer waits to run an operator flow's next step; try "
            "once the flow is done");
  EXPECT_EQ(flowing.write(false).step.kind, StepKind::fail);
  in.step_request = false;
  flowing.read(in, t0);
  flowing.write(false);
  in.interpreter_idle = true;  // the executor aborted its program with the fail
  flowing.read(in, t0 + std::chrono::seconds(1));
  EXPECT_TRUE(flowing.needs_run(t0 + std::chrono::seconds(1))) << "the flow's step is kept";
  in.interpreter_idle = false;
  in.step_request = true;

  ExecutorLink m6;  // an M6 while the flow's step waits: refused the same way
  m6.publish(next);
  in.call = static_cast<int>(ExecutorCall::tool_change);
  in.number = 3;
  events = m6.read(in, t0);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, LinkEvent::Kind::refused_call);
  EXPECT_EQ(events[0].reason.rfind("M6 T3 refused: the changer waits to run an operator flow's", 0),
            0u)
      << events[0].reason;

  ExecutorLink wrong;
  in.call = 5;
  events = wrong.read(in, t0);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, LinkEvent::Kind::refused_call) << "the component says it";
  const LinkOutputs out = wrong.write(true);
  ASSERT_TRUE(out.step_ready);
  EXPECT_EQ(out.step.kind, StepKind::fail);
  EXPECT_TRUE(has(out.step.label, "3 (chuck release) or 4 (chuck clamp)")) << out.step.label;
}

}  // namespace
}  // namespace fatc
