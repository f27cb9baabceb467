// --version: the name, the release of CMakeLists.txt's project() (the
// package's version) and, built from a git checkout, its commit.
#include <gtest/gtest.h>

#include <regex>

#include "program_run.hpp"
#include "temp_folder.hpp"

namespace fatc {
namespace {

using Version = test::TempFolder;

TEST_F(Version, shouldPrintTheNameTheReleaseAndTheCommitOnOneLine) {
  test::ProgramStart start;
  start.args = {"--version"};
  start.out = folder_ + "/out";
  start.err = folder_ + "/err";
  const int status = test::wait_for(test::start_program(start));
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  const std::string said = test::text_of(folder_ + "/out");
  // The commit only where the build had git and a checkout of its own.
  const std::regex line("fixed_atc_probe " FATC_PROJECT_VERSION "( \\([0-9a-f]{7,}\\))?\n");
  EXPECT_TRUE(std::regex_match(said, line)) << said;
  EXPECT_EQ(test::text_of(folder_ + "/err"), "");
}

TEST_F(Version, shouldRefuseAnOptionBesideIt) {
  test::ProgramStart start;
  start.args = {"--version", "--config", "c.json"};
  start.err = folder_ + "/err";
  const int status = test::wait_for(test::start_program(start));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_EQ(test::text_of(folder_ + "/err"),
            "fixed_atc_probe: --config is not used by --version (see --help)\n");
}

}  // namespace
}  // namespace fatc
