// A taught config (ConfigChanged): taken only while idle, refused in one line
// otherwise, and Changer::why_not_teach says the same before anything is read
// or written. And Status::over_mdi, which tells the adapter to start the
// executor over MDI.

#include <gtest/gtest.h>

#include <string>

#include "core/machine/changer.hpp"
#include "core/dry_run/simulator.hpp"
#include "sim_rig.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::SimRig;

constexpr double kTaughtSafeX = 130.0;
const std::string kNotIdle = "teach safe refused: only while the changer is idle";
const Point kSomewhere{20.0, 150.0, -10.0};

/// The test config with `safe` taught 10 mm further along X.
Config taught(const Config& config) {
  Config changed = config;
  changed.safe.x = kTaughtSafeX;
  return changed;
}

/// A changer with the spindle empty and every pocket full.
struct Rig : SimRig {
  explicit Rig(const std::string& extra = "")
      : SimRig(test::valid_config(extra), ToolState::fresh(test::valid_config(extra))) {}
  /// Hands the changer the taught config; says whether it took it.
  bool teach() { return changer->reconfigure(taught(config), "teach safe"); }
  std::string last_error() const {
    const auto errors = sim.messages(MessageKind::error);
    return errors.empty() ? "" : errors.back();
  }
  /// The refusal why_not_teach gives now, with LinuxCNC's status and a position.
  std::string refusal() const {
    return "teach safe refused: " + changer->why_not_teach(true, kSomewhere).value_or("none");
  }
};

bool moves_to_x(const Simulator& sim, double x) {
  for (const Step& step : sim.motion_steps()) {
    if ((step.axes & axis_x) && step.target.x == x) return true;
  }
  return false;
}

TEST(Reconfigure, shouldGoToTheTaughtSafeFromTheNextRequestWhenTakenWhileIdle) {
  Rig rig;
  EXPECT_FALSE(rig.changer->why_not_teach(true, kSomewhere).has_value());
  EXPECT_TRUE(rig.teach());
  EXPECT_EQ(rig.changer->config().safe.x, kTaughtSafeX);
  EXPECT_EQ(rig.last_error(), "");
  rig.changer->tool_change(2);
  rig.run();
  EXPECT_EQ(rig.changer->tools().spindle, 2);
  EXPECT_TRUE(moves_to_x(rig.sim, kTaughtSafeX));
  EXPECT_FALSE(moves_to_x(rig.sim, rig.config.safe.x)) << "the old safe is gone";
}

TEST(Reconfigure, shouldRefuseATaughtConfigAndKeepItsOwnWhileAFlowRuns) {
  Rig rig;
  rig.changer->unload(3);
  rig.run();
  ASSERT_TRUE(rig.changer->status().awaits_operator());
  EXPECT_EQ(rig.refusal(), kNotIdle);
  EXPECT_FALSE(rig.teach());
  EXPECT_EQ(rig.last_error(), kNotIdle);
  EXPECT_EQ(rig.changer->config().safe.x, rig.config.safe.x);
  EXPECT_EQ(rig.changer->status().phase, Phase::unloading) << "the flow goes on";
  rig.changer->operator_continue();
  rig.run();
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rig.changer->tools().spindle, 0);
}

TEST(Reconfigure, shouldRefuseATaughtConfigWhileTheMachineIsOffOrFaulted) {
  Rig rig;
  rig.changer->not_ready();
  EXPECT_EQ(rig.refusal(), kNotIdle);
  EXPECT_FALSE(rig.teach());
  EXPECT_EQ(rig.last_error(), kNotIdle);
  rig.changer->ready();
  rig.changer->tool_change(2);
  rig.changer->abort("the abort pin was raised");
  ASSERT_EQ(rig.changer->status().phase, Phase::fault);
  EXPECT_EQ(rig.refusal(), kNotIdle);
  EXPECT_FALSE(rig.teach());
  EXPECT_EQ(rig.last_error(), kNotIdle);
  EXPECT_EQ(rig.changer->config().safe.x, rig.config.safe.x);
}

TEST(Reconfigure, shouldSayAProgramRunsWhenTaughtWhileTaskIsBusy) {
  Rig rig;
  rig.changer->task_availability("a program or MDI command is running");
  const std::string words =
      "teach safe refused: a program or MDI command is running; teach once it stopped";
  EXPECT_EQ(rig.refusal(), words);
  EXPECT_FALSE(rig.teach());
  EXPECT_EQ(rig.last_error(), words);
  rig.changer->task_availability(std::nullopt);
  EXPECT_TRUE(rig.teach());
}

TEST(Reconfigure, shouldSayWhatItComparesWhenTaughtWhileTheSensorsDisagree) {
  Rig rig(R"("sensors": {"tool_present": true})");
  rig.sim.rack.spindle = 7;  // a tool the tool state does not know of
  rig.sim.report_sensors(*rig.changer);
  ASSERT_EQ(rig.changer->status().awaiting, Awaiting::sensor);
  const std::string words = "teach safe refused: " + rig.changer->status().activity;
  EXPECT_NE(words.find("comparing the sensors with the saved tool state"), std::string::npos);
  EXPECT_EQ(rig.refusal(), words);
  EXPECT_FALSE(rig.teach());
  EXPECT_EQ(rig.last_error(), words);
}

TEST(Reconfigure, shouldSayTheChuckIsOpenWhenTaughtWhileAReleaseHoldsIt) {
  Rig rig;
  rig.changer->chuck(ChuckRequest::Action::release, kSomewhere);
  rig.run();
  ASSERT_TRUE(rig.changer->status().chuck_held);
  const std::string words = "teach safe refused: " + rig.changer->status().activity;
  EXPECT_NE(words.find("the chuck is open"), std::string::npos);
  EXPECT_EQ(rig.refusal(), words);
  EXPECT_FALSE(rig.teach());
  EXPECT_EQ(rig.last_error(), words);
}

TEST(WhyNotTeach, shouldNeedLinuxCncsStatusAndAMachinePositionWhenIdle) {
  Rig rig;
  EXPECT_EQ(rig.changer->why_not_teach(false, std::nullopt),
            "no LinuxCNC status to read the machine position from");
  EXPECT_EQ(rig.changer->why_not_teach(true, std::nullopt),
            "LinuxCNC's status says nothing of the machine position now");
  EXPECT_EQ(rig.changer->why_not_teach(true, kSomewhere), std::nullopt);
  EXPECT_TRUE(rig.sim.messages(MessageKind::error).empty()) << "a question, not a request";
}

TEST(OverMdi, shouldSayAnOperatorFlowRunsOverMdiAndAnM6DoesNot) {
  Rig rig;
  EXPECT_FALSE(rig.changer->status().over_mdi) << "idle";
  rig.changer->unload(3);
  EXPECT_TRUE(rig.changer->status().over_mdi);
  rig.run();
  EXPECT_TRUE(rig.changer->status().over_mdi) << "at the operator's question";
  rig.changer->operator_continue();
  rig.run();
  EXPECT_FALSE(rig.changer->status().over_mdi) << "idle again";
  rig.changer->tool_change(2);
  EXPECT_FALSE(rig.changer->status().over_mdi) << "M6 runs inside its program";
  rig.run();
  rig.changer->measure_all({2});
  EXPECT_TRUE(rig.changer->status().over_mdi);
  rig.changer->operator_cancel();
  rig.run();
}

}  // namespace
}  // namespace fatc
