// --teach as a hostile or hurried user runs it: two at once, one while the
// component teaches, and with links, FIFOs, second names or its own INI at
// the names it writes. No update is lost; a teach that cannot write says so
// in one line and leaves every file as it was.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "cli_run.hpp"
#include "io/file_writer.hpp"
#include "io/files.hpp"
#include "temp_folder.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::CliRun;
const auto& run = test::run_cli;

class TeachWriters : public test::TempFolder {
 protected:
  void SetUp() override {
    TempFolder::SetUp();
    config_ = folder_ + "/config.json";
    std::ofstream(config_) << test::kValidConfig;
  }
  static std::string text(const std::string& path) { return test::text_of(path); }
  CliRun teach(const std::string& target, const std::string& at) {
    return run({"--teach", target, "--at", at, "--config", config_});
  }
  double pocket_x(int pocket) const {
    return io::load_config_file(config_).config->pockets.at(pocket).at.x;
  }

  std::string config_;
};

/// "pocket 1: x 50.0000 → 50.1000, ...": the x the teach read, and the one it wrote.
std::pair<double, double> x_change(const std::string& out) {
  double from = 0.0, to = 0.0;
  const auto at = out.find(": x ");
  EXPECT_NE(at, std::string::npos) << out;
  if (at == std::string::npos) return {from, to};
  EXPECT_EQ(std::sscanf(out.c_str() + at, ": x %lf \xe2\x86\x92 %lf", &from, &to), 2) << out;
  return {from, to};
}

TEST_F(TeachWriters, shouldLoseNoUpdateWhenTwoTeachAtOnce) {
  // Each teaches its own pocket again and again: what a teach reads of its
  // pocket must be what it wrote the time before, whatever the other wrote.
  constexpr int kRounds = 15;
  auto teacher = [&](int pocket, double first_x, std::vector<std::string>& failures) {
    double written = first_x;
    for (int round = 1; round <= kRounds; ++round) {
      const double x = first_x + round * 0.5;
      char at[64];
      std::snprintf(at, sizeof at, "%g,20,-80", x);
      const CliRun r = teach("pocket:" + std::to_string(pocket), at);
      if (r.code != 0) {
        failures.push_back(r.err);
        continue;
      }
      const auto [from, to] = x_change(r.out);
      if (from != written) {
        failures.push_back("pocket " + std::to_string(pocket) + " read " + std::to_string(from) +
                           ", wrote before " + std::to_string(written));
      }
      written = to;
    }
  };
  std::vector<std::string> first_failures, second_failures;
  std::thread first(teacher, 1, 50.0, std::ref(first_failures));
  std::thread second(teacher, 6, 300.0, std::ref(second_failures));
  first.join();
  second.join();
  EXPECT_TRUE(first_failures.empty()) << first_failures.front();
  EXPECT_TRUE(second_failures.empty()) << second_failures.front();
  EXPECT_EQ(pocket_x(1), 50.0 + kRounds * 0.5);
  EXPECT_EQ(pocket_x(6), 300.0 + kRounds * 0.5);
}

TEST_F(TeachWriters, shouldWaitForTheComponentsTeachAndKeepIt) {
  std::thread component([&] {
    // As ConfigTeacher: the file taken, read, changed, replaced (the backup aside).
    const io::FileWriter file(config_, io::kComponentWait);
    std::string before = text(config_);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    std::string after = before;
    after.replace(after.find("\"x\": 300.0"), 10, "\"x\": 305.0");
    file.replace(after);
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const CliRun r = teach("pocket:1", "51,20,-80");
  component.join();
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(pocket_x(6), 305.0) << "the component's teach is kept";
  EXPECT_EQ(pocket_x(1), 51.0);
}

TEST_F(TeachWriters, shouldSayTheConfigIsBusyWhenTheOtherWriterKeepsIt) {
  const io::FileWriter other(config_, std::chrono::milliseconds(0));
  try {
    const io::FileWriter late(config_, std::chrono::milliseconds(20));
    FAIL() << "taken twice";
  } catch (const std::exception& e) {
    EXPECT_EQ(std::string(e.what()),
              config_ + ": another program is writing it (waited 0.02 s): not written");
  }
}

TEST_F(TeachWriters, shouldRefuseALinkPlantedAtTheBackupWritingNothing) {
  const std::string precious = folder_ + "/precious";
  std::ofstream(precious) << "keep me";
  std::filesystem::create_symlink(precious, config_ + ".bak");
  const std::string before = text(config_);
  const CliRun r = teach("safe", "130,80,-5");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, config_ + ".bak: a symbolic link (to " + precious +
                       "): not written, the link would become a file of its own; give the file it "
                       "points to\n");
  EXPECT_EQ(text(precious), "keep me");
  EXPECT_EQ(text(config_), before);
}

TEST_F(TeachWriters, shouldRefuseAFifoAtTheBackupWithoutWaiting) {
  ASSERT_EQ(::mkfifo((config_ + ".bak").c_str(), 0600), 0);
  const std::string before = text(config_);
  const CliRun r = teach("safe", "130,80,-5");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, config_ + ".bak: expected a regular file, got a FIFO: not written\n");
  EXPECT_EQ(text(config_), before);
}

TEST_F(TeachWriters, shouldRefuseABackupThatIsItsOwnIni) {
  const std::string ini = config_ + ".bak";
  std::ofstream(ini) << "[TRAJ]\nLINEAR_UNITS = mm\n";
  const CliRun r = run({"--teach", "safe", "--at", "130,80,-5", "--config", config_, "--ini", ini});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "the backup \"" + ini + "\" is the file given as --ini: nothing written\n");
  EXPECT_EQ(text(ini), "[TRAJ]\nLINEAR_UNITS = mm\n");
}

TEST_F(TeachWriters, shouldRefuseAReadOnlyConfig) {
  ::chmod(config_.c_str(), 0444);
  const std::string before = text(config_);
  const CliRun r = teach("safe", "130,80,-5");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, config_ + ": read-only (mode 0444): not written\n");
  EXPECT_EQ(text(config_), before);
  EXPECT_FALSE(std::filesystem::exists(config_ + ".bak"));
}

TEST_F(TeachWriters, shouldRefuseAConfigWithASecondName) {
  const std::string other = folder_ + "/other_mill.json";
  ASSERT_EQ(::link(config_.c_str(), other.c_str()), 0);
  const CliRun r = teach("safe", "130,80,-5");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, config_ +
                       ": has 2 names (hard links): not written, the other names would keep the "
                       "old text\n");
  EXPECT_FALSE(std::filesystem::exists(config_ + ".bak"));
}

}  // namespace
}  // namespace fatc
