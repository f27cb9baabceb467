// The command line is declared once (command_line.cpp): what the parser takes
// is what --help, the man page and docs/command-line.md say.
#include <gtest/gtest.h>

#include "io/command_line.hpp"

namespace fatc::io {
namespace {

TEST(CommandLine, shouldAcceptWhatEachModesSynopsisShows) {
  std::string error;
  const auto plan = parse_options({"--plan", "--config", "c.json", "--from", "1", "--to", "2",
                                   "--state", "s.json", "--ini", "m.ini"},
                                  error);
  ASSERT_TRUE(plan) << error;
  EXPECT_EQ(plan->state_path, "s.json");
  EXPECT_NE(usage().find("fixed_atc_probe --plan --config FILE --from A --to B [--ini FILE] "
                         "[--state FILE]"),
            std::string::npos)
      << usage();
}

TEST(CommandLine, shouldNameEveryModeAndOptionInEachReference) {
  const std::string help = usage();
  const std::string man = synopsis_man() + options_man();
  const std::string markdown = command_line_markdown();
  for (const ModeDeclaration& mode : modes()) {
    if (!*mode.flag) continue;
    EXPECT_NE(help.find(mode.flag), std::string::npos) << mode.flag;
    EXPECT_NE(man.find(mode.flag), std::string::npos) << mode.flag;
    EXPECT_NE(markdown.find(mode.flag), std::string::npos) << mode.flag;
  }
  for (const OptionDeclaration& option : options()) {
    EXPECT_NE(help.find(option.name), std::string::npos) << option.name;
    EXPECT_NE(man.find(option.name), std::string::npos) << option.name;
    EXPECT_NE(markdown.find(option.name), std::string::npos) << option.name;
  }
}

TEST(CommandLine, shouldTakeTheEqualsFormAndRefuseAValueOnAModeFlag) {
  std::string error;
  const auto check = parse_options({"--check", "--config=c.json", "--ini=m.ini"}, error);
  ASSERT_TRUE(check) << error;
  EXPECT_EQ(check->config_path, "c.json");
  EXPECT_EQ(*check->ini_path, "m.ini");
  EXPECT_FALSE(parse_options({"--dot=1"}, error));
  EXPECT_EQ(error, "--dot takes no value, got \"1\"");
}

TEST(CommandLine, shouldTakeANegativeCoordinateAsTheValueOfAt) {
  std::string error;
  const auto teach =
      parse_options({"--teach", "safe", "--at", "-10.5,-2,-30", "--config", "c.json"}, error);
  ASSERT_TRUE(teach) << error;
  EXPECT_DOUBLE_EQ(teach->teach_at->x, -10.5);
  EXPECT_DOUBLE_EQ(teach->teach_at->z, -30.0);
}

TEST(CommandLine, shouldSayWhichOptionAModeNeeds) {
  std::string error;
  EXPECT_FALSE(parse_options({"--plan", "--config", "c.json", "--from", "1"}, error));
  EXPECT_EQ(error, "--plan needs --to B (the tool M6 asks for)");
}

}  // namespace
}  // namespace fatc::io
