// --confirm refuses an answer that contradicts the record, and a state file
// whose cut-off pocket the config does not have, in one line each, writing
// nothing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "cli_run.hpp"
#include "io/files.hpp"
#include "temp_folder.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::CliRun;
const auto& run = test::run_cli;

class Confirm : public test::TempFolder {
 protected:
  void SetUp() override {
    TempFolder::SetUp();
    config_ = folder_ + "/config.json";
    state_ = folder_ + "/state.json";
    std::ofstream(config_) << test::kValidConfig;
  }

  /// An M6 cut off while it returned tool 2 to pocket 2: the spindle may still hold it.
  void cut_off_at_pocket(int pocket, int tool_of_pocket) {
    ToolState tools = ToolState::fresh(test::valid_config());
    tools.pockets[pocket] = {tool_of_pocket, false};
    tools.spindle = tool_of_pocket;
    tools.uncertain = true;
    tools.in_progress =
        InProgress{"M6 T5", "returning to pocket " + std::to_string(pocket), pocket};
    std::ofstream(state_) << to_json(tools);
  }
  std::string state_text() const { return test::text_of(state_); }
  CliRun confirm(std::vector<std::string> answer) {
    std::vector<std::string> args = {"--confirm", "--config", config_, "--state", state_};
    args.insert(args.end(), answer.begin(), answer.end());
    return run(args);
  }

  std::string config_, state_;
};

TEST_F(Confirm, shouldRefuseTheCutOffPocketsToolInTheSpindleAndInItsPocketAtOnce) {
  cut_off_at_pocket(2, 2);
  const std::string before = state_text();
  const CliRun r = confirm({"--spindle", "2", "--pocket", "yes"});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err, state_ +
                       ": --spindle 2 --pocket yes: tool 2 cannot be both in the spindle and in "
                       "its pocket 2\n");
  EXPECT_EQ(state_text(), before);
}

TEST_F(Confirm, shouldRefusePocketYesWhereNoToolBelongs) {
  cut_off_at_pocket(2, 0);
  const std::string before = state_text();
  const CliRun r = confirm({"--spindle", "0", "--pocket", "yes"});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(
      r.err,
      state_ +
          ": --spindle 0 --pocket yes: no tool belongs in pocket 2, where the sequence was cut off\n");
  EXPECT_EQ(state_text(), before);
}

TEST_F(Confirm, shouldRefusePocketNoWhenNothingWasCutOffAtAPocket) {
  ToolState tools = ToolState::fresh(test::valid_config());
  tools.uncertain = true;
  std::ofstream(state_) << to_json(tools);
  const CliRun r = confirm({"--spindle", "0", "--pocket", "no"});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err, state_ + ": --spindle 0 --pocket no: no sequence was cut off at a pocket\n");
}

TEST_F(Confirm, shouldTakeTheToolInTheSpindleAndNotInItsPocket) {
  cut_off_at_pocket(2, 2);
  const CliRun r = confirm({"--spindle", "2", "--pocket", "no"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, state_ +
                       ": the spindle holds tool 2; pocket 2 does not hold tool 2; nothing is "
                       "uncertain now\n");
}

TEST_F(Confirm, shouldRefuseACutOffPocketTheConfigDoesNotHave) {
  cut_off_at_pocket(2, 2);
  std::string text = state_text();
  text.replace(text.find("\"pocket\": 2"), 11, "\"pocket\": 99");
  std::ofstream(state_) << text;
  const std::string line = state_ +
                           ": in_progress.pocket: the sequence was cut off at pocket 99, which "
                           "config.json does not have\n";
  const CliRun answered = confirm({"--spindle", "0", "--pocket", "yes"});
  EXPECT_EQ(answered.code, 1);
  EXPECT_EQ(answered.err, line);
  EXPECT_EQ(state_text(), text);

  const CliRun checked = run({"--check", "--config", config_, "--state", state_});
  EXPECT_EQ(checked.code, 1);
  EXPECT_EQ(checked.err, line);
  const CliRun linted =
      run({"--lint", folder_ + "/program.ngc", "--config", config_, "--state", state_});
  EXPECT_EQ(linted.code, 2);
  EXPECT_EQ(linted.err, line);
}

TEST_F(Confirm, shouldRefuseAStateFileThatIsTheConfig) {
  const CliRun r = run({"--confirm", "--config", config_, "--state", config_, "--spindle", "0"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "--state \"" + config_ + "\" is the file given as --config: nothing written\n");
  EXPECT_TRUE(io::load_config_file(config_).config) << "the config is as it was";
}

TEST_F(Confirm, shouldRefuseAStateFileThatIsNotThereAndWriteNone) {
  // A mistyped --state would get a state file of its own while the real one stays uncertain.
  const CliRun r = confirm({"--spindle", "0"});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err, state_ +
                       ": no such state file, so nothing to confirm and nothing written (is "
                       "it the --state the component was given?)\n");
  EXPECT_FALSE(std::filesystem::exists(state_));
}

TEST_F(Confirm, shouldSayWhatIsWrongWithAStatePathThatIsAFolderOrEmpty) {
  const CliRun folder =
      run({"--confirm", "--config", config_, "--state", folder_, "--spindle", "0"});
  EXPECT_EQ(folder.code, 1);
  EXPECT_EQ(folder.err, folder_ + ": expected a regular file, got a directory\n");
  std::ofstream(state_).close();
  const CliRun empty = confirm({"--spindle", "0"});
  EXPECT_EQ(empty.code, 1);
  EXPECT_EQ(empty.err.rfind(state_ + ": ", 0), 0u) << empty.err;
  EXPECT_EQ(std::count(empty.err.begin(), empty.err.end(), '\n'), 1) << empty.err;
}

}  // namespace
}  // namespace fatc
