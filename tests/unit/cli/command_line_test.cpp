// The command line is declared once (command_line.cpp): what the parser takes
// is what --help, the man page and docs/command-line.md say.
#include <gtest/gtest.h>

#include <clocale>
#include <cstdio>

#include "cli/command_line.hpp"
#include "cli/parse_options.hpp"
#include "cli/usage.hpp"
#include "core/config/quote.hpp"

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

/// --teach safe --at `at`: the position read, or the line that refused it.
std::string taught_at(const std::string& at) {
  std::string error;
  const auto teach = parse_options({"--teach", "safe", "--at", at, "--config", "c.json"}, error);
  if (!teach) return error;
  char read[96];
  std::snprintf(read, sizeof read, "%.17g %.17g %.17g", teach->teach_at->x, teach->teach_at->y,
                teach->teach_at->z);
  return read;
}

TEST(CommandLine, shouldReadThePositionsAMachinistTypes) {
  EXPECT_EQ(taught_at("120,80,-5"), "120 80 -5");
  EXPECT_EQ(taught_at("+1.5,-.5,.25"), "1.5 -0.5 0.25");
  EXPECT_EQ(taught_at("-.5,-1,-2"), "-0.5 -1 -2");
  EXPECT_EQ(taught_at("12.,0,-0"), "12 0 -0");
  EXPECT_EQ(taught_at("1e2,2.5E-1,-3e+1"), "100 0.25 -30");
  EXPECT_EQ(taught_at(" 10 , 20\t, -80 "), "10 20 -80");
  EXPECT_EQ(taught_at("0.1,0,0"), "0.10000000000000001 0 0");
}

TEST(CommandLine, shouldRefuseEveryOtherNumberNamingTheOptionAndTheAxis) {
  const std::string form = " (expected X,Y,Z like 120.5,80,-5 in machine coordinates; got ";
  EXPECT_EQ(taught_at("0x33,20,-80"), "--at: X \"0x33\" is not a decimal number" + form +
                                          "\"0x33,20,-80\")");
  EXPECT_EQ(taught_at("1,inf,0"), "--at: Y \"inf\" is not a decimal number" + form +
                                      "\"1,inf,0\")");
  EXPECT_EQ(taught_at("1,2,nan"), "--at: Z \"nan\" is not a decimal number" + form +
                                      "\"1,2,nan\")");
  EXPECT_EQ(taught_at("1,,3"), "--at: Y is empty" + form + "\"1,,3\")");
  EXPECT_EQ(taught_at("1,2,"), "--at: Z is empty" + form + "\"1,2,\")");
  EXPECT_EQ(taught_at("1,2"), "--at: expected X,Y,Z (three numbers with commas between), got "
                              "\"1,2\"");
  // Each of these is no decimal number a machinist means; X is the one named.
  for (const std::string x : {"12mm", "1e999", "-1e400", "1e", "e5", ".", "+", "+-1", "1..2",
                              "1.2.3", "0x1p3", "INF", "NaN", "infinity", "1 2", "\xe2\x88\x92" "5",
                              "\xef\xbc\x91", "1_000", "١٢"}) {
    EXPECT_EQ(taught_at(x + ",0,0").rfind("--at: X ", 0), 0u) << x << ": " << taught_at(x + ",0,0");
  }
  // A decimal comma (a German locale's 1,5) makes four fields, not 1.5.
  EXPECT_EQ(taught_at("1,5,2,-80").rfind("--at: Z \"2,-80\" is not a decimal number", 0), 0u)
      << taught_at("1,5,2,-80");
}

TEST(CommandLine, shouldReadNumbersTheSameWhateverTheLocale) {
  // A program that calls setlocale (LinuxCNC's libraries may) must not read 1.5 as 1.
  const char* before = std::setlocale(LC_NUMERIC, nullptr);
  const std::string kept = before ? before : "C";
  for (const char* locale : {"de_DE.UTF-8", "fr_FR.UTF-8", "C.UTF-8"}) {
    if (std::setlocale(LC_NUMERIC, locale) == nullptr) continue;
    EXPECT_EQ(taught_at("1.5,-2.25,3"), "1.5 -2.25 3") << locale;
  }
  std::setlocale(LC_NUMERIC, kept.c_str());
}

TEST(CommandLine, shouldTakeToolNumbersAsDigitsOnly) {
  std::string error;
  const auto plan = parse_options({"--plan", "--config", "c.json", "--from", "007", "--to", "0"},
                                  error);
  ASSERT_TRUE(plan) << error;
  EXPECT_EQ(*plan->from_tool, 7);
  EXPECT_EQ(*plan->to_tool, 0);
  for (const std::string tool : {"+3", "-1", "3.0", "0x3", "3e0", "T3", " 3", "3 ", "inf", "nan",
                                 "1234567890", "\xef\xbc\x93"}) {
    EXPECT_FALSE(parse_options({"--plan", "--config", "c.json", "--from", "1", "--to", tool},
                               error))
        << tool;
    EXPECT_EQ(error, "--to: expected a tool number, at most 9 digits and nothing else (0 for "
                     "none), got " + quote(tool));
  }
  EXPECT_FALSE(parse_options({"--confirm", "--config", "c.json", "--spindle", "0x1"}, error));
  EXPECT_EQ(error.rfind("--spindle: expected a tool number", 0), 0u) << error;
  for (const std::string pocket : {"pocket:0x3", "pocket:+3", "pocket:3.0", "pocket:", "pocket:-1",
                                   "pocket: 3", "pocket:1e1"}) {
    EXPECT_FALSE(parse_options({"--teach", pocket, "--at", "1,2,3", "--config", "c.json"}, error))
        << pocket;
    EXPECT_EQ(error, "--teach: expected pocket:N, loading, safe, sensor or datum, got " + quote(pocket));
  }
}

}  // namespace
}  // namespace fatc::io
