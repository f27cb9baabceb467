// Typed prompts: the words the operator reads, made in one place, and the
// simulated operator acting on the fields; measure-which decided in the core.

#include "core/machine/prompt.hpp"

#include <gtest/gtest.h>

#include <string>

#include "core/machine/flows/measure_which.hpp"
#include "sim_rig.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::SimRig;

Prompt asking(Prompt::Kind kind, int tool) {
  Prompt prompt;
  prompt.kind = kind;
  prompt.tool = tool;
  return prompt;
}

TEST(Prompt, shouldAskForAToolInTheWordsOfAnOperatorFlowOrOfAnM6) {
  Prompt insert = asking(Prompt::Kind::insert_tool, 3);
  EXPECT_EQ(words(insert), "Insert tool 3 into the spindle, then press Continue (Cancel to stop)");
  insert.m6_tool = 3;
  EXPECT_EQ(
      words(insert),
      "M6 T3: insert tool 3 into the spindle, then press Continue (Cancel stops the program)");
  Prompt remove = asking(Prompt::Kind::remove_tool, 12);
  EXPECT_EQ(words(remove), "Remove tool 12 from the spindle, then press Continue (Cancel to stop)");
  remove.m6_tool = 4;
  EXPECT_EQ(words(remove),
            "M6 T4: remove tool 12 from the spindle, then press Continue (Cancel "
            "stops the program)");
}

TEST(Prompt, shouldOfferTheJogAndNameTheVerifyStopWithItsCoordinates) {
  EXPECT_EQ(words(asking(Prompt::Kind::jog_to_sensor, 4)),
            "Tool 4 is in the spindle. Jog it closer to the touch-off sensor if you like, then "
            "press Continue to probe (Cancel to stop)");
  Prompt stop = asking(Prompt::Kind::verify_stop, 0);
  stop.pocket = 3;
  stop.stop = 2;
  stop.stops = 5;
  stop.waypoint = "side of pocket 3";
  stop.at = {150.0, 60.0, -80.0};
  stop.known_axes = axis_x | axis_z;
  EXPECT_EQ(words(stop),
            "Verify pocket 3, stop 2 of 5: side of pocket 3 (X=150.000 Z=-80.000). Look at the "
            "clearance, then press Continue (Cancel stops here)");
}

TEST(Prompt, shouldHandTheTypedPromptToThePortsWhenAnM6AsksForAManualTool) {
  const Config config = test::valid_config();
  SimRig rig(config, ToolState::fresh(config));
  rig.changer->tool_change(9);  // in no pocket: handed in at loading
  rig.run();
  ASSERT_TRUE(rig.sim.asked.has_value());
  EXPECT_EQ(rig.sim.asked->kind, Prompt::Kind::insert_tool);
  EXPECT_EQ(rig.sim.asked->tool, 9);
  EXPECT_EQ(rig.sim.asked->m6_tool, 9);
  EXPECT_EQ(rig.sim.messages(MessageKind::prompt).back(), words(*rig.sim.asked));
  EXPECT_EQ(rig.changer->status().activity, words(*rig.sim.asked));
  rig.changer->operator_continue();
  rig.run();
  EXPECT_EQ(rig.changer->tools().spindle, 9);
}

TEST(Prompt, shouldLetTheSimulatedOperatorDoWhatTheTypedPromptSays) {
  const Config config = test::valid_config(R"("sensors": {"tool_present": true})");
  SimRig rig(config, ToolState::fresh(config));
  rig.changer->tool_change(9);
  rig.run();
  rig.sim.operator_obeys(*rig.changer);
  EXPECT_EQ(rig.sim.rack.spindle, 9) << "inserted";
  rig.sim.report_sensors(*rig.changer);
  rig.changer->operator_continue();
  rig.run();
  ASSERT_EQ(rig.changer->tools().spindle, 9);
  rig.changer->tool_change(0);  // handed out at loading
  rig.run();
  ASSERT_EQ(rig.sim.asked->kind, Prompt::Kind::remove_tool);
  rig.sim.operator_obeys(*rig.changer);
  EXPECT_EQ(rig.sim.rack.spindle, 0) << "removed";
  rig.sim.report_sensors(*rig.changer);
  rig.changer->operator_continue();
  rig.run();
  EXPECT_EQ(rig.changer->tools().spindle, 0);
  rig.sim.rack.spindle = 5;
  rig.sim.operator_obeys(*rig.changer);
  EXPECT_EQ(rig.sim.rack.spindle, 5) << "nothing asked now: the operator does nothing";
}

TEST(MeasureWhich, shouldNameEveryRackToolForZeroAndTheUnmeasuredForOne) {
  ToolState tools = ToolState::fresh(test::valid_config());
  tools.lengths = {{2, 30.0}, {5, 41.5}};
  const MeasureChoice every = measure_which(0, tools);
  EXPECT_EQ(every.kind, MeasureChoice::Kind::tools);
  EXPECT_EQ(every.tools, tools.rack_tools());
  const MeasureChoice unmeasured = measure_which(1, tools);
  EXPECT_EQ(unmeasured.kind, MeasureChoice::Kind::tools);
  EXPECT_EQ(unmeasured.tools, (std::vector<int>{1, 3, 4, 6}));
}

TEST(MeasureWhich, shouldLeaveTheProgramsToolsToLinuxCncsInterpreterForTwo) {
  const MeasureChoice program = measure_which(2, ToolState::fresh(test::valid_config()));
  EXPECT_EQ(program.kind, MeasureChoice::Kind::program_tools);
  EXPECT_TRUE(program.tools.empty());
}

TEST(MeasureWhich, shouldRefuseAnyOtherValueNamingTheThreeItTakes) {
  for (const int which : {-1, 3}) {
    const MeasureChoice refused = measure_which(which, ToolState::fresh(test::valid_config()));
    EXPECT_EQ(refused.kind, MeasureChoice::Kind::refused);
    EXPECT_EQ(refused.refusal,
              "measure all refused: measure-which must be 0 (every tool in the rack), 1 (the "
              "unmeasured) or 2 (the program's), got " +
                  std::to_string(which));
  }
}

}  // namespace
}  // namespace fatc
