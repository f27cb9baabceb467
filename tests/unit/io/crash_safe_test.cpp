// The state file survives a writer killed at any moment: a child saves two
// states in turn as fast as it can and is killed with SIGKILL at random
// moments; every time, the file is complete and valid (the old state or the
// new one, never a part, never missing), and the next save works whatever
// temporary file the killed writer left behind.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <thread>

#include "io/files.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

class CrashSafeSave : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/fatc_crash_XXXXXX";
    folder_ = ::mkdtemp(pattern);
    path_ = folder_ + "/state.json";
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  static ToolState small() {
    ToolState state;
    state.spindle = 0;
    for (int pocket = 1; pocket <= 6; ++pocket) state.pockets[pocket] = {pocket, true};
    return state;
  }
  /// Much longer than small(): a torn write of it would not parse.
  static ToolState large() {
    ToolState state;
    state.spindle = 3;
    for (int pocket = 1; pocket <= 6; ++pocket) state.pockets[pocket] = {pocket, pocket != 3};
    for (int tool = 1; tool <= 6; ++tool) state.lengths[tool] = 40.0 + tool / 8.0;
    state.in_progress = InProgress{"M6 T4", "returning tool 3 to pocket 3", 3};
    state.uncertain = true;
    return state;
  }

  /// A temporary file of the state's writer (".state.json.XXXXXXXXXXXX.tmp") is in the folder.
  bool temporary_left() const {
    for (const auto& entry : std::filesystem::directory_iterator(folder_)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind(".state.json.", 0) == 0 && name.size() == 28) return true;
    }
    return false;
  }

  std::string folder_;
  std::string path_;
};

TEST_F(CrashSafeSave, shouldLeaveTheOldOrTheNewStateWhenKilledAtAnyMoment) {
  const ToolState a = small();
  const ToolState b = large();
  io::save_state_file(path_, a, io::kCommandLineWait);
  std::mt19937 random(20240611);
  std::uniform_int_distribution<int> pause_us(0, 4000);
  int found_a = 0, found_b = 0, temporary_files = 0;
  constexpr int kKills = 200;
  for (int kill = 0; kill < kKills; ++kill) {
    int saved[2];
    ASSERT_EQ(::pipe(saved), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      ::close(saved[0]);
      try {
        for (;;) {
          io::save_state_file(path_, b, io::kCommandLineWait);
          io::save_state_file(path_, a, io::kCommandLineWait);
          // At work: however slow the disk, the kill below comes after this.
          if (saved[1] >= 0 && ::write(saved[1], "s", 1) == 1) {
            ::close(saved[1]);
            saved[1] = -1;
          }
        }
      } catch (const std::exception& e) {
        std::cerr << "the writer failed: " << e.what() << "\n";
      }
      ::_exit(3);
    }
    ::close(saved[1]);
    char byte = 0;
    ASSERT_EQ(::read(saved[0], &byte, 1), 1) << "the writer never finished its first saves";
    ::close(saved[0]);
    std::this_thread::sleep_for(std::chrono::microseconds(pause_us(random)));
    ASSERT_EQ(::kill(child, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL)
        << "the writer stopped by itself (status " << status << ") before kill " << kill;

    const auto loaded = io::load_state_file(path_, test::valid_config());
    ASSERT_TRUE(loaded.state) << "after kill " << kill << ": " << loaded.error;
    ASSERT_TRUE(*loaded.state == a || *loaded.state == b) << "after kill " << kill;
    (*loaded.state == a ? found_a : found_b)++;
    if (temporary_left()) ++temporary_files;

    // Whatever the killed writer left, the next save works and cleans up.
    io::save_state_file(path_, a, io::kCommandLineWait);
    ASSERT_FALSE(temporary_left()) << "after kill " << kill;
  }
  std::cout << "[ figures  ] " << kKills << " kills: old or new state each time (" << found_a
            << " times the small one, " << found_b << " the large one), " << temporary_files
            << " temporary files left by the killed writer, each cleaned by the next save\n";
  RecordProperty("found_small", found_a);
  RecordProperty("found_large", found_b);
  RecordProperty("temporary_files_left", temporary_files);
  // The kills must have hit the writer at work, not only before its first save.
  EXPECT_GT(found_b, 10);
  EXPECT_GT(found_a, 10);
}

TEST_F(CrashSafeSave, shouldNotFollowASymlinkAtTheOldOrALeftoverTemporaryName) {
  const std::string target = folder_ + "/precious";
  std::ofstream(target) << "keep me";
  io::save_state_file(path_, small(), io::kCommandLineWait);
  // The name the old writer used, and one shaped as this writer's own.
  std::filesystem::create_symlink(target, path_ + ".tmp");
  std::filesystem::create_symlink(target, folder_ + "/.state.json.AAAAAAAAAAAA.tmp");
  io::save_state_file(path_, large(), io::kCommandLineWait);
  std::ifstream in(target);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "keep me");
  EXPECT_EQ(*io::load_state_file(path_, test::valid_config()).state, large());
  EXPECT_FALSE(temporary_left()) << "a leftover of this writer's shape is removed, not followed";
  EXPECT_TRUE(std::filesystem::is_symlink(path_ + ".tmp")) << "another name is left alone";
}

TEST_F(CrashSafeSave, shouldRemoveAReadOnlyTemporaryFileLeftBehind) {
  io::save_state_file(path_, small(), io::kCommandLineWait);
  const std::string left = folder_ + "/.state.json.BBBBBBBBBBBB.tmp";
  std::ofstream(left) << "{\"version\": 1, \"spi";
  ::chmod(left.c_str(), 0444);
  io::save_state_file(path_, large(), io::kCommandLineWait);
  const auto loaded = io::load_state_file(path_, test::valid_config());
  ASSERT_TRUE(loaded.state) << loaded.error;
  EXPECT_EQ(*loaded.state, large());
  EXPECT_FALSE(temporary_left());
}

}  // namespace
}  // namespace fatc
