#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "core/rack/tool_state.hpp"
#include "io/files.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

ToolState sample() {
  ToolState state;
  state.spindle = 3;
  state.pockets = {{1, {1, true}},  {2, {2, true}}, {3, {3, false}},
                   {4, {0, false}}, {5, {5, true}}, {6, {6, false}}};
  state.lengths = {{1, 42.125}, {3, 17.5}};
  return state;
}

TEST(ToolState, shouldStartWithEveryPocketFullAndTheSpindleEmpty) {
  const ToolState fresh = ToolState::fresh(test::valid_config());
  EXPECT_EQ(fresh.spindle, 0);
  EXPECT_EQ(test::tools_in_rack(fresh), (std::set<int>{1, 2, 3, 4, 5, 6}));
  for (int pocket = 1; pocket <= 6; ++pocket) EXPECT_EQ(fresh.tool_of(pocket), pocket);
  EXPECT_FALSE(fresh.uncertain);
}

TEST(ToolState, shouldNameTwentyPocketsAndCountTheRest) {
  std::vector<int> numbers;
  for (int n = 1; n <= 30; ++n) numbers.push_back(n);
  EXPECT_EQ(pocket_list(numbers),
            "pockets 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20 "
            "\u2026 and 10 more");
  EXPECT_EQ(pocket_list({4}), "pocket 4");
}

TEST(ToolState, shouldRoundTripThroughJson) {
  ToolState state = sample();
  state.uncertain = true;
  const auto back = tool_state_from_json(to_json(state));
  ASSERT_TRUE(back.state) << back.error;
  EXPECT_EQ(*back.state, state);
}

struct Corruption {
  const char* text;
  const char* expected;
};

class CorruptState : public ::testing::TestWithParam<Corruption> {};

TEST_P(CorruptState, shouldNameWhatIsWrong) {
  const auto result = tool_state_from_json(GetParam().text);
  ASSERT_FALSE(result.state);
  EXPECT_EQ(result.error.rfind(GetParam().expected, 0), 0u) << result.error;
}

// clang-format off
INSTANTIATE_TEST_SUITE_P(Each, CorruptState, ::testing::Values(
  Corruption{"", "line 1, column 1: invalid JSON: syntax error while parsing value - unexpected end of input"},
  Corruption{"{\"version\": 1, \"spindle\": 3", "line 1, column 28: invalid JSON: syntax error while parsing object - unexpected end of input"},
  Corruption{"[]", "state: expected a JSON object"},
  Corruption{"{\"version\": 3, \"spindle\": 0, \"uncertain\": false, \"in_pocket\": [], \"lengths\": {}}", "version: expected 1 or 2, got 3"},
  Corruption{"{\"version\": 2, \"spindle\": 0, \"uncertain\": false, \"in_pocket\": [], \"lengths\": {}}", "in_pocket: unknown key"},
  Corruption{"{\"version\": 2, \"spindle\": 0, \"uncertain\": false, \"pockets\": [], \"lengths\": {}}", "pockets: expected an object of pocket number to {tool, in_pocket}, got an array"},
  Corruption{"{\"version\": 2, \"spindle\": 0, \"uncertain\": false, \"pockets\": {\"0\": {\"tool\": 1, \"in_pocket\": true}}, \"lengths\": {}}", "pockets.0: the key must be a pocket number"},
  Corruption{"{\"version\": 2, \"spindle\": 0, \"uncertain\": false, \"pockets\": {\"1\": {\"tool\": -1, \"in_pocket\": true}}, \"lengths\": {}}", "pockets.1.tool: expected 0 or a tool number, got -1"},
  Corruption{"{\"version\": 2, \"spindle\": 0, \"uncertain\": false, \"pockets\": {\"1\": {\"tool\": 1}}, \"lengths\": {}}", "pockets.1.in_pocket: expected true or false, got nothing"},
  Corruption{"{\"version\": 2, \"spindle\": 0, \"uncertain\": false, \"pockets\": {\"1\": {\"tool\": 0, \"in_pocket\": true}}, \"lengths\": {}}", "pockets.1.in_pocket: a free pocket (tool 0) cannot hold its tool"},
  Corruption{"{\"version\": 2, \"spindle\": 0, \"uncertain\": false, \"pockets\": {\"1\": {\"tool\": 7, \"in_pocket\": true}, \"2\": {\"tool\": 7, \"in_pocket\": false}}, \"lengths\": {}}", "pockets.2.tool: tool 7 is recorded in pocket 1 too"},
  Corruption{"{\"version\": 2, \"spindle\": 7, \"uncertain\": false, \"pockets\": {\"1\": {\"tool\": 7, \"in_pocket\": true}}, \"lengths\": {}}", "spindle: tool 7 is recorded both in the spindle and in pocket 1"},
  Corruption{"{\"version\": 2, \"spindle\": 0, \"uncertain\": false, \"pockets\": {\"1\": {\"tool\": 7, \"in_pocket\": true, \"x\": 1}}, \"lengths\": {}}", "pockets.1.x: unknown key"},
  Corruption{"{\"version\": 1, \"uncertain\": false, \"in_pocket\": [], \"lengths\": {}}", "spindle: missing"},
  Corruption{"{\"version\": 1, \"spindle\": -2, \"uncertain\": false, \"in_pocket\": [], \"lengths\": {}}", "spindle: expected 0 or a tool number, got -2"},
  Corruption{"{\"version\": 1, \"spindle\": 0, \"uncertain\": \"no\", \"in_pocket\": [], \"lengths\": {}}", "uncertain: expected true or false"},
  Corruption{"{\"version\": 1, \"spindle\": 0, \"uncertain\": false, \"in_pocket\": [1, \"x\"], \"lengths\": {}}", "in_pocket.1: expected a tool number"},
  Corruption{"{\"version\": 1, \"spindle\": 0, \"uncertain\": false, \"in_pocket\": [1, 1], \"lengths\": {}}", "in_pocket.1: tool 1 listed twice"},
  Corruption{"{\"version\": 1, \"spindle\": 2, \"uncertain\": false, \"in_pocket\": [2], \"lengths\": {}}", "spindle: tool 2 is recorded both in the spindle and in pocket 2"},
  Corruption{"{\"version\": 1, \"spindle\": 0, \"uncertain\": false, \"in_pocket\": [], \"lengths\": {\"a\": 1}}", "lengths.a: the key must be a tool number"},
  Corruption{"{\"version\": 1, \"spindle\": 0, \"uncertain\": false, \"in_pocket\": [], \"lengths\": {\"1\": \"long\"}}", "lengths.1: expected a finite number"},
  Corruption{"{\"version\": 1, \"spindle\": 0, \"uncertain\": false, \"in_pocket\": [], \"lengths\": {}, \"extra\": 1}", "extra: unknown key"}
));
// clang-format on

class StateFile : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/fatc_state_XXXXXX";
    folder_ = ::mkdtemp(pattern);
    path_ = folder_ + "/state.json";
  }
  void TearDown() override {
    std::remove(path_.c_str());
    std::remove((path_ + ".tmp").c_str());
    ::rmdir(folder_.c_str());
  }
  std::string folder_;
  std::string path_;
};

TEST_F(StateFile, shouldBeAFreshStateWhenMissing) {
  const Config config = test::valid_config();
  const auto result = io::load_state_file(path_, config);
  ASSERT_TRUE(result.state);
  EXPECT_EQ(*result.state, ToolState::fresh(config));
}

TEST_F(StateFile, shouldSaveAndLoadTheSameState) {
  io::save_state_file(path_, sample(), io::kCommandLineWait);
  const auto result = io::load_state_file(path_, test::valid_config());
  ASSERT_TRUE(result.state) << result.error;
  EXPECT_EQ(*result.state, sample());
  std::ifstream leftover(path_ + ".tmp");
  EXPECT_FALSE(leftover.good()) << "the temporary file is renamed, not left behind";
}

TEST_F(StateFile, shouldNameTheFileWhenCorruptNeverReset) {
  std::ofstream(path_) << "{\"version\": 1, \"spindle\": ";
  const auto result = io::load_state_file(path_, test::valid_config());
  ASSERT_FALSE(result.state);
  EXPECT_EQ(result.error.rfind(path_ + ": line 1, column 27: invalid JSON", 0), 0u) << result.error;
}

TEST_F(StateFile, shouldRefuseAPocketTheConfigDoesNotHave) {
  ToolState state = sample();
  state.pockets[9] = {9, true};
  io::save_state_file(path_, state, io::kCommandLineWait);
  const auto result = io::load_state_file(path_, test::valid_config());
  ASSERT_FALSE(result.state);
  EXPECT_EQ(result.error,
            path_ + ": pockets.9: tool 9 is recorded in pocket 9, which config.json does not have");
}

TEST_F(StateFile, shouldKeepTheOldFileWhenTheFolderIsGone) {
  EXPECT_THROW(
      io::save_state_file("/nonexistent/folder/state.json", sample(), io::kCommandLineWait),
      std::runtime_error);
}

}  // namespace
}  // namespace fatc
