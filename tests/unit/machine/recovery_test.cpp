// After a crash, an abort or a fault: what the changer knows, what it
// refuses, and how the operator's confirmation puts it right.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "cli/cli.hpp"
#include "cli/parse_options.hpp"
#include "core/dry_run/simulator.hpp"
#include "core/machine/changer.hpp"
#include "io/files.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

/// The state a change left when it was cut off while returning tool 2.
ToolState cut_off_while_returning(const Config& config) {
  ToolState tools = ToolState::fresh(config);
  tools.spindle = 2;
  test::take_out(tools, 2);
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
    test::take_out(t, 2);
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
  EXPECT_NE(sim.messages(MessageKind::error).back().find("pocket 2 may or may not hold tool 2"),
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
  EXPECT_EQ(changer.tools().holds(2), GetParam().pocket_full_after);
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

TEST(Recovery, shouldRefuseAClearFaultThatPutsAToolInTwoPlaces) {
  // Cut off returning tool 2 to pocket 2: tool 2 cannot be in the spindle
  // and in pocket 2 at once (the clear-fault pin refuses what --confirm does).
  const Config config = test::valid_config();
  Simulator sim;
  Changer changer(config, sim, cut_off_while_returning(config));
  changer.ready();
  const int saves = sim.saves;
  changer.clear_fault(2, true);
  EXPECT_EQ(changer.status().phase, Phase::fault);
  EXPECT_EQ(sim.saves, saves) << "nothing recorded";
  EXPECT_EQ(sim.messages(MessageKind::error).back(),
            "clear fault refused: tool 2 cannot be both in the spindle and in its pocket 2; check "
            "confirm-tool and confirm-pocket");
  changer.clear_fault(2, false);
  EXPECT_EQ(changer.status().phase, Phase::idle);
}

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

namespace fatc {
namespace {

struct ConfirmFiles {
  ConfirmFiles() {
    char pattern[] = "/tmp/fatc_confirm.XXXXXX";
    folder = ::mkdtemp(pattern);
    config = folder + "/config.json";
    state = folder + "/state.json";
    std::ofstream(config) << test::kValidConfig;
    io::save_state_file(state, cut_off_while_returning(test::valid_config()), io::kCommandLineWait);
  }
  ~ConfirmFiles() { std::system(("rm -rf " + folder).c_str()); }
  int run(std::vector<std::string> args, std::string& said) {
    std::string error;
    const auto options = io::parse_options(args, error);
    if (!options) {
      said = error;
      return 2;
    }
    std::ostringstream out, err;
    const int code = io::run_tool_mode(*options, out, err);
    said = out.str() + err.str();
    return code;
  }
  std::string folder, config, state;
};

TEST(ConfirmCommand, shouldRecordTheOperatorsWordInTheStateFileWithoutLinuxCnc) {
  ConfirmFiles f;
  std::string said;
  ASSERT_EQ(f.run({"--confirm", "--config", f.config, "--state", f.state, "--spindle", "0",
                   "--pocket", "yes"},
                  said),
            0)
      << said;
  EXPECT_EQ(said, f.state +
                      ": the spindle holds nothing; pocket 2 holds tool 2; nothing is "
                      "uncertain now\n");
  const auto read = io::load_state_file(f.state, test::valid_config());
  ASSERT_TRUE(read.state) << read.error;
  EXPECT_EQ(read.state->spindle, 0);
  EXPECT_TRUE(read.state->holds(2));
  EXPECT_FALSE(read.state->uncertain);
  EXPECT_FALSE(read.state->in_progress.has_value());
}

TEST(ConfirmCommand, shouldRefuseAPocketAnswerWhenNoPocketWasInvolvedAndLeaveTheFileAlone) {
  ConfirmFiles f;
  std::string said;
  ASSERT_EQ(f.run({"--confirm", "--config", f.config, "--state", f.state, "--spindle", "2"}, said),
            0);
  EXPECT_EQ(f.run({"--confirm", "--config", f.config, "--state", f.state, "--spindle", "0",
                   "--pocket", "no"},
                  said),
            1);
  EXPECT_NE(said.find("--pocket no: no sequence was cut off at a pocket"), std::string::npos) << said;
  EXPECT_EQ(io::load_state_file(f.state, test::valid_config()).state->spindle, 2);
}

TEST(ConfirmCommand, shouldSayWhatIsMissingOrWrongOnTheCommandLine) {
  ConfirmFiles f;
  std::string said;
  EXPECT_EQ(f.run({"--confirm", "--config", f.config}, said), 2);
  EXPECT_EQ(said, "--confirm needs --spindle N (0: the spindle is empty)");
  EXPECT_EQ(f.run({"--confirm", "--config", f.config, "--spindle", "1", "--pocket", "maybe"}, said),
            2);
  EXPECT_EQ(said, "--pocket: expected yes or no, got \"maybe\"");
  EXPECT_EQ(f.run({"--check", "--config", f.config, "--spindle", "1"}, said), 2);
  EXPECT_EQ(said, "--spindle is not used by --check");
}

}  // namespace
}  // namespace fatc

namespace fatc {
namespace {

TEST(Sequence, shouldGoToSafeFirstWhenANewChangeStartsWhereTheLastOneEnded) {
  // The last sequence ended at safe, but a program or a jog may have moved
  // the machine since: a new one never takes the old position for granted.
  const Config config = test::valid_config();
  Simulator sim;
  ToolState tools = ToolState::fresh(config);
  tools.spindle = 3;
  test::take_out(tools, 3);
  Changer changer(config, sim, tools);
  changer.ready();
  changer.tool_change(0);
  sim.run(changer);
  const std::size_t before = sim.motion_steps().size();
  changer.tool_change(5);
  sim.run(changer);
  const auto moves = sim.motion_steps();
  ASSERT_GT(moves.size(), before + 2);
  EXPECT_EQ(moves[before].label, "safe Z");
  EXPECT_EQ(moves[before + 1].label, "safe XY");
  EXPECT_EQ(changer.tools().spindle, 5);
}

}  // namespace
}  // namespace fatc
