// Verify a pocket: a dry run through one pocket's approach at the verify
// feed, the chuck closed, held at each waypoint until Continue.
#include <gtest/gtest.h>

#include <memory>

#include "core/machine/changer.hpp"
#include "core/config/config.hpp"
#include "core/dry_run/simulator.hpp"
#include "core/rack/tool_state.hpp"
#include "sim_rig.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::Lines;
using test::valid_config;

/// Tool `spindle` in the spindle, its pocket 3 empty (0: the spindle empty
/// and pocket 3 free).
ToolState verify_tools(const Config& config, int spindle) {
  ToolState tools = with_in_spindle(config, spindle);
  if (spindle == 0) tools.pockets[3] = {};
  return tools;
}

struct VerifyRig : test::SimRig {
  explicit VerifyRig(const Config& c = valid_config(), int spindle = 3)
      : SimRig(c, verify_tools(c, spindle)) {}
  /// Continue at every stop; the moves of the whole run, in order.
  Lines run_to_the_end() {
    Lines all = run();
    for (int stop = 0; stop < 20 && changer->status().awaits_operator(); ++stop) {
      changer->operator_continue();
      for (auto& line : run()) all.push_back(line);
    }
    return all;
  }
};

/// The valid config with every pocket approached from above.
Config from_above() {
  const std::string side = R"("pocket_default": {"y": 20.0, "z": -80.0})";
  std::string text = test::kValidConfig;
  text.replace(text.find(side), side.size(),
               R"("pocket_default": {"y": 20.0, "z": -80.0, "approach": "top"})");
  return parse_config(text).config.value();
}

TEST(VerifyPocket, shouldGoInFromTheSideAndOutAgainOneWaypointAtATime) {
  VerifyRig rig;
  rig.changer->verify(3);
  EXPECT_EQ(rig.run(), (Lines{"feed safe Z"}));
  const Status at_safe_z = rig.changer->status();
  EXPECT_EQ(at_safe_z.phase, Phase::verifying);
  EXPECT_TRUE(at_safe_z.awaits_operator());
  EXPECT_TRUE(at_safe_z.holds_program) << "the executor run is held: nothing can be jogged";
  EXPECT_EQ(at_safe_z.pocket, 3);
  EXPECT_EQ(at_safe_z.activity,
            "Verify pocket 3, stop 1 of 7: safe Z (Z=-5.000). Look at the clearance, then "
            "press Continue (Cancel stops here)");

  const Lines rest = rig.run_to_the_end();
  EXPECT_EQ(rest, (Lines{"feed safe XY", "feed over the side of pocket 3", "feed side of pocket 3",
                         "feed pocket 3", "feed side of pocket 3", "feed safe Z", "feed safe XY",
                         "done T3"}));
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rig.changer->tools(), rig.tools) << "a dry run records nothing";
  EXPECT_EQ(rig.last_message(),
            "verify of pocket 3 done: 8 moves through its approach at F500, back at safe XY");
}

TEST(VerifyPocket, shouldStopAtTheSideWithItsCoordinates) {
  VerifyRig rig;
  rig.changer->verify(3);
  rig.run();
  for (int i = 0; i < 3; ++i) {
    rig.changer->operator_continue();
    rig.run();
  }
  EXPECT_EQ(rig.changer->status().activity,
            "Verify pocket 3, stop 4 of 7: side of pocket 3 (X=150.000 Y=60.000 Z=-80.000). "
            "Look at the clearance, then press Continue (Cancel stops here)");
}

TEST(VerifyPocket, shouldGoStraightDownAndUpForATopPocket) {
  VerifyRig rig(from_above());
  rig.changer->verify(3);
  EXPECT_EQ(rig.run_to_the_end(),
            (Lines{"feed safe Z", "feed safe XY", "feed over pocket 3",
                   "feed above-clearance of pocket 3", "feed pocket 3",
                   "feed above-clearance of pocket 3", "feed safe Z", "feed safe XY", "done T3"}));
}

TEST(VerifyPocket, shouldNeverTouchTheChuck) {
  VerifyRig rig(valid_config(R"("air_blast": true)"), 0);
  rig.changer->verify(3);
  rig.run();
  rig.changer->verify(4);  // refused: busy
  for (const auto& line : rig.run_to_the_end()) {
    EXPECT_EQ(line.find("chuck"), std::string::npos) << line;
    EXPECT_EQ(line.find("blast"), std::string::npos) << line;
  }
}

TEST(VerifyPocket, shouldMoveAtVerifyFeedAndNoFasterThanThePocketFeedInside) {
  for (const auto& [verify_feed, outside, inside] :
       {std::tuple{0.0, 500.0, 500.0}, {200.0, 200.0, 200.0}, {2000.0, 2000.0, 500.0}}) {
    VerifyRig rig(
        valid_config(verify_feed > 0 ? "\"verify_feed\": " + std::to_string(verify_feed) : ""));
    rig.changer->verify(3);
    rig.run_to_the_end();
    for (const Step& step : rig.sim.motion_steps()) {
      EXPECT_EQ(step.kind, StepKind::feed) << step.label;
      const bool slow =
          step.label == "pocket 3" || (step.label == "side of pocket 3" && step.axes == axis_xy);
      EXPECT_EQ(step.feed, slow ? inside : outside) << verify_feed << " " << step.label;
    }
  }
}

TEST(VerifyPocket, shouldStayWhereItIsWhenCancelledAndSaySo) {
  VerifyRig rig;
  rig.changer->verify(3);
  rig.run();
  for (int i = 0; i < 4; ++i) {
    rig.changer->operator_continue();
    rig.run();
  }
  rig.changer->operator_cancel();
  EXPECT_EQ(rig.run(), (Lines{"done T3"})) << "nothing moves: the run ends where it stands";
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(
      rig.last_message(),
      "verify of pocket 3 cancelled by the operator; the spindle stays where it stopped: pocket 3 "
      "(X=150.000 Y=20.000 Z=-80.000), below the rack's clearance: jog it out the way it "
      "came in before the next change");
  EXPECT_FALSE(rig.changer->cut_off()) << "the sequence is over";
}

TEST(VerifyPocket, shouldRefuseAPocketThatHoldsATool) {
  VerifyRig rig;
  rig.changer->verify(2);
  EXPECT_TRUE(rig.run().empty());
  EXPECT_EQ(rig.sim.messages(MessageKind::error).back(),
            "verify of pocket 2 refused: pocket 2 holds tool 2; fetch it first (M6 T2) to verify "
            "with it in the spindle");
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
}

TEST(VerifyPocket, shouldRefuseWhatItCannotDoInOneLine) {
  VerifyRig rig;
  rig.changer->verify(9);
  rig.changer->verify(0);
  rig.changer->spindle_stopped(false);
  rig.changer->verify(3);
  rig.changer->spindle_stopped(true);
  rig.changer->task_availability("a program is running");
  rig.changer->verify(3);
  EXPECT_TRUE(rig.run().empty()) << "nothing moved";
  EXPECT_EQ(rig.sim.messages(MessageKind::error),
            (std::vector<std::string>{
                "verify of pocket 9 refused: pocket-number 9 is not a pocket of the config "
                "(pockets 1, 2, 3, 4, 5, 6)",
                "verify of pocket 0 refused: pocket-number 0 is not a pocket of the config "
                "(pockets 1, 2, 3, 4, 5, 6)",
                "verify of pocket 3 refused: the spindle is turning; stop it first",
                "verify of pocket 3 refused: a program is running"}));
}

TEST(VerifyPocket, shouldRefuseOtherWorkWhileItRunsAndBeRefusedWhileBusy) {
  VerifyRig rig;
  rig.changer->verify(3);
  rig.run();
  rig.changer->load(7);
  EXPECT_EQ(rig.sim.messages(MessageKind::error).back(),
            "load of tool 7 refused: the changer is busy verifying pocket 3");
  rig.run_to_the_end();
  rig.changer->tool_change(5);
  rig.changer->verify(3);
  rig.run();
  EXPECT_EQ(rig.sim.messages(MessageKind::error).back(),
            "verify of pocket 3 refused: the changer is busy changing to tool 5");
}

TEST(VerifyPocket, shouldEndWithoutAFaultWhenAborted) {
  VerifyRig rig;
  rig.changer->verify(3);
  rig.run();
  rig.changer->operator_continue();  // the move to safe XY is under way
  rig.changer->abort("the program was aborted");
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_FALSE(rig.changer->tools().uncertain) << "the chuck stayed closed";
  EXPECT_FALSE(rig.changer->cut_off());
  EXPECT_EQ(rig.last_message(),
            "verify of pocket 3 stopped (the program was aborted); nothing was recorded. The "
            "spindle may be in the rack: jog it out the way it came in before the next change");
  rig.changer->tool_change(4);
  rig.run();
  EXPECT_EQ(rig.changer->tools().spindle, 4) << "ready for work";
}

TEST(VerifyPocket, shouldWaitForTheMachineWhenItGoesOff) {
  VerifyRig rig;
  rig.changer->verify(3);
  rig.run();
  rig.changer->not_ready();
  EXPECT_EQ(rig.changer->status().phase, Phase::not_ready);
  EXPECT_FALSE(rig.changer->tools().uncertain);
  rig.changer->ready();
  rig.run();
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
}

TEST(VerifyPocket, shouldOpenTheRackCoverFirstAndCloseItAfter) {
  VerifyRig rig(valid_config(R"("rack_cover": {})"));
  rig.changer->verify(3);
  const Lines lines = rig.run_to_the_end();
  ASSERT_GE(lines.size(), 3u);
  EXPECT_EQ(lines.front(), "cover open");
  EXPECT_EQ(lines[lines.size() - 2], "done T3");
  EXPECT_EQ(lines.back(), "cover close");
}

}  // namespace
}  // namespace fatc
