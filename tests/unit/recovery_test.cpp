// After a crash, an abort or a fault: what the changer knows, what it
// refuses, and how the operator's confirmation puts it right.
#include <gtest/gtest.h>

#include "core/changer.hpp"
#include "core/simulator.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

/// The state a change left when it was cut off while returning tool 2.
ToolState cut_off_while_returning(const Config& config) {
  ToolState tools = ToolState::fresh(config);
  tools.spindle = 2;
  tools.in_pocket.erase(2);
  tools.uncertain = true;
  tools.in_progress = InProgress{"M6 T5", "returning tool 2 to pocket 2", 2};
  return tools;
}

TEST(Recovery, shouldKeepWhatWasUnderWayAndMarkTheSpindleUncertainWhenAChangeIsAborted) {
  const Config config = test::valid_config();
  Simulator sim;
  Changer changer(config, sim, [&] {
    ToolState t = ToolState::fresh(config);
    t.spindle = 2;
    t.in_pocket.erase(2);
    return t;
  }());
  changer.ready();
  changer.tool_change(5);
  for (int i = 0; i < 4; ++i) sim.run(changer, 1);  // safe Z, safe XY, over the side, down
  changer.abort("LinuxCNC aborted the program during the sequence");
  ASSERT_TRUE(changer.cut_off().has_value());
  EXPECT_EQ(changer.cut_off()->sequence, "M6 T5");
  EXPECT_EQ(changer.cut_off()->step, "returning tool 2 to pocket 2");
  EXPECT_EQ(changer.cut_off()->pocket, 2);
  EXPECT_TRUE(changer.tools().uncertain);
  EXPECT_EQ(changer.status().phase, Phase::fault);
  EXPECT_NE(sim.messages(MessageKind::error).back().find("pocket 2 may or may not hold its tool"),
            std::string::npos)
      << sim.messages(MessageKind::error).back();
  EXPECT_FALSE(sim.chuck_open);
}

TEST(Recovery, shouldFaultAtStartAndSayWhereWhenTheSavedStateWasCutOff) {
  const Config config = test::valid_config();
  Simulator sim;
  Changer changer(config, sim, cut_off_while_returning(config));
  changer.ready();
  EXPECT_EQ(changer.status().phase, Phase::fault);
  const std::string said = sim.messages(MessageKind::error).back();
  EXPECT_NE(said.find("cut off during M6 T5, returning tool 2 to pocket 2"), std::string::npos)
      << said;
  EXPECT_TRUE(sim.steps().size() == 1 && sim.steps()[0].kind == StepKind::fail)
      << "only the fail step for a waiting executor";
  changer.tool_change(3);
  EXPECT_NE(sim.messages(MessageKind::error).back().find("M6 T3 refused: the changer is in fault"),
            std::string::npos);
  changer.load(4);
  EXPECT_NE(sim.messages(MessageKind::error).back().find("load of tool 4 refused"),
            std::string::npos);
  EXPECT_TRUE(sim.motion_steps().empty());
}

struct Confirmation {
  const char* name;
  int spindle;
  std::optional<bool> pocket_holds_tool;
  bool pocket_full_after;
};
std::ostream& operator<<(std::ostream& out, const Confirmation& c) { return out << c.name; }
class Confirmed : public ::testing::TestWithParam<Confirmation> {};

TEST_P(Confirmed, shouldRecordWhatTheOperatorSaysAndMoveNothing) {
  const Config config = test::valid_config();
  Simulator sim;
  Changer changer(config, sim, cut_off_while_returning(config));
  changer.ready();
  const std::size_t records = sim.records.size();
  changer.clear_fault(GetParam().spindle, GetParam().pocket_holds_tool);
  EXPECT_EQ(changer.status().phase, Phase::idle);
  EXPECT_EQ(changer.tools().spindle, GetParam().spindle);
  EXPECT_EQ(changer.tools().in_pocket.count(2) == 1, GetParam().pocket_full_after);
  EXPECT_FALSE(changer.tools().uncertain);
  EXPECT_FALSE(changer.cut_off().has_value());
  for (std::size_t i = records; i < sim.records.size(); ++i) {
    EXPECT_NE(sim.records[i].kind, Record::Kind::step) << describe(sim.records[i]);
    EXPECT_NE(sim.records[i].kind, Record::Kind::chuck) << describe(sim.records[i]);
  }
  ASSERT_EQ(sim.records.back().kind, Record::Kind::message);
  EXPECT_EQ(sim.records[sim.records.size() - 2].kind, Record::Kind::save);
}

INSTANTIATE_TEST_SUITE_P(Each, Confirmed,
                         ::testing::Values(Confirmation{"tool_went_home", 0, true, true},
                                           Confirmation{"tool_still_in_spindle", 2, false, false},
                                           Confirmation{"pocket_not_asked", 0, std::nullopt, false},
                                           Confirmation{"another_tool", 7, false, false}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(Recovery, shouldAcceptAChangeAfterTheOperatorConfirmed) {
  const Config config = test::valid_config();
  Simulator sim;
  Changer changer(config, sim, cut_off_while_returning(config));
  changer.ready();
  changer.clear_fault(0, true);
  changer.tool_change(5);
  sim.run(changer);
  EXPECT_EQ(changer.tools().spindle, 5);
  EXPECT_EQ(changer.status().phase, Phase::idle);
  EXPECT_TRUE(sim.unexpected_events.empty());
}

TEST(Recovery, shouldReadBackWhatWasUnderWayAsUncertainFromTheStateFile) {
  const Config config = test::valid_config();
  ToolState tools = cut_off_while_returning(config);
  tools.uncertain = false;  // the file alone must make it so
  const ToolStateResult read = tool_state_from_json(to_json(tools));
  ASSERT_TRUE(read.state) << read.error;
  ASSERT_TRUE(read.state->in_progress.has_value());
  EXPECT_EQ(*read.state->in_progress, *tools.in_progress);
  EXPECT_TRUE(read.state->uncertain);
}

}  // namespace
}  // namespace fatc

namespace fatc {
namespace {

TEST(UnsafeStep, shouldFaultWithoutSendingAMoveOutsideTheRunningMachinesSoftLimits) {
  const Config config = test::valid_config();
  Simulator sim;
  Changer changer(config, sim, ToolState::fresh(config));
  // Safe Z of the test config is -5: a machine whose Z stops at -10 cannot go there.
  changer.soft_limits(SoftLimits{{-1000, 1000}, {-1000, 1000}, {-200, -10}});
  changer.ready();
  changer.tool_change(2);
  sim.run(changer);
  EXPECT_TRUE(sim.motion_steps().empty()) << describe(sim.motion_steps().front());
  EXPECT_EQ(changer.status().phase, Phase::fault);
  const std::string said = sim.messages(MessageKind::error).back();
  EXPECT_NE(said.find("unsafe step not sent: rapid"), std::string::npos) << said;
  EXPECT_NE(said.find("Z=-5.000 is outside the soft limits -200.000 .. -10.000"), std::string::npos)
      << said;
  EXPECT_TRUE(sim.unexpected_events.empty());
}

TEST(UnsafeStep, shouldRunTheChangeWhenEveryMoveIsWithinTheSoftLimits) {
  const Config config = test::valid_config();
  Simulator sim;
  Changer changer(config, sim, ToolState::fresh(config));
  changer.soft_limits(SoftLimits{{-1000, 1000}, {-1000, 1000}, {-200, 0}});
  changer.ready();
  changer.tool_change(2);
  sim.run(changer);
  EXPECT_EQ(changer.tools().spindle, 2);
  EXPECT_EQ(changer.status().phase, Phase::idle);
}

}  // namespace
}  // namespace fatc
