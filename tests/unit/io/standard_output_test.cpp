// A write error on standard output (a full disk, > /dev/full) ends every
// mode that prints with exit 2 and one line naming it, never exit 0.
#include "io/standard_output.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <fstream>
#include <ostream>

#include "core/rack/tool_state.hpp"
#include "program_run.hpp"
#include "temp_folder.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

const std::string kConfig = FATC_SOURCE_DIR "/config/config.json";
const std::string kFullLine =
    "fixed_atc_probe: cannot write to standard output (No space left on device): what it "
    "printed is lost\n";

TEST(StandardOutput, shouldKeepTheFirstWriteErrorAndDropTheRest) {
  const int full = ::open("/dev/full", O_WRONLY | O_CLOEXEC);
  ASSERT_GE(full, 0);
  {
    io::StandardOutput written(full);
    std::ostream out(&written);
    out << "a line\n";
    EXPECT_EQ(written.error(), 0) << "nothing written before a flush";
    out.flush();
    EXPECT_EQ(written.error(), ENOSPC);
    EXPECT_FALSE(out.good());
  }
  ::close(full);
}

TEST(StandardOutput, shouldWriteEverythingWhereItCan) {
  const std::string path = ::testing::TempDir() + "fatc_standard_output";
  const int file = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  ASSERT_GE(file, 0);
  {
    io::StandardOutput written(file);
    std::ostream out(&written);
    out << std::string(70000, 'x') << "\n";  // over its buffer once
    out.flush();
    EXPECT_EQ(written.error(), 0);
  }
  ::close(file);
  EXPECT_EQ(test::text_of(path), std::string(70000, 'x') + "\n");
  std::remove(path.c_str());
}

class FullDisk : public test::TempFolder {
 protected:
  /// The program with `args`, its standard output /dev/full: exit status and stderr.
  std::pair<int, std::string> run_into_full(const std::vector<std::string>& args) {
    test::ProgramStart start;
    start.args = args;
    start.out = "/dev/full";
    start.err = folder_ + "/err";
    const int status = test::wait_for(test::start_program(start));
    return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status),
            test::text_of(folder_ + "/err")};
  }
};

TEST_F(FullDisk, shouldEndEveryModeThatPrintsWithOneLine) {
  const std::string state = folder_ + "/none.state";
  const std::string program = folder_ + "/p.ngc";
  std::ofstream(program) << "T2 M6\nM2\n";
  const std::string taught = folder_ + "/taught.json";
  std::ofstream(taught) << test::kValidConfig;
  const std::string confirmed = folder_ + "/confirmed.state";
  ToolState cut_off = ToolState::fresh(test::valid_config());
  cut_off.uncertain = true;
  std::ofstream(confirmed) << to_json(cut_off);
  const std::vector<std::vector<std::string>> modes = {
      {"--help"},
      {"--version"},
      {"--dot"},
      {"--check", "--config", kConfig, "--state", state},
      {"--plan", "--config", kConfig, "--from", "1", "--to", "2"},
      {"--lint", program, "--config", kConfig, "--state", state},
      {"--plot", folder_ + "/rack.svg", "--config", kConfig},
      {"--teach", "safe", "--at", "120,80,-5", "--config", taught},
      {"--confirm", "--config", taught, "--spindle", "0", "--state", confirmed},
  };
  for (const auto& args : modes) {
    const auto [code, err] = run_into_full(args);
    EXPECT_EQ(code, 2) << args[0];
    EXPECT_EQ(err, kFullLine) << args[0];
  }
}

}  // namespace
}  // namespace fatc
