#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/cli.hpp"

namespace fatc {
namespace {

struct CliRun {
  int code;
  std::string out;
  std::string err;
};

CliRun run(std::vector<std::string> args) {
  std::string error;
  const auto options = io::parse_options(args, error);
  if (!options) return {2, "", error};
  std::ostringstream out, err;
  const int code = io::run_tool_mode(*options, out, err);
  return {code, out.str(), err.str()};
}

const std::string kConfig = FATC_SOURCE_DIR "/config/config.json";

TEST(Cli, shouldPrintThePlanOfAChangeOneStepALine) {
  const CliRun r = run({"--plan", "--config", kConfig, "--from", "2", "--to", "5"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("M6 T5 with T2 in the spindle"), std::string::npos);
  EXPECT_NE(r.out.find("feed       X=100.000 Y=20.000 F600"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("done       T5"), std::string::npos);
}

TEST(Cli, shouldExitOneWhenThePlannedChangeIsRefused) {
  nlohmann::json config = nlohmann::json::parse(std::ifstream(kConfig));
  config["manual_tools"] = false;
  const std::string path = ::testing::TempDir() + "fatc_manual_tools_off.json";
  std::ofstream(path) << config.dump();
  const CliRun r = run({"--plan", "--config", path, "--from", "0", "--to", "42"});
  std::remove(path.c_str());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.out.find("tool 42 has no pocket in the config (and manual_tools is off)"), std::string::npos)
      << r.out << r.err;
}

TEST(Cli, shouldPlanAManualToolWithTheOperatorHandingItOver) {
  const CliRun r = run({"--plan", "--config", kConfig, "--from", "2", "--to", "42"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("insert tool 42 into the spindle"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("done       T42"), std::string::npos) << r.out;
}

TEST(Cli, shouldPassTheCheckOfTheSampleConfig) {
  const CliRun r = run({"--check", "--config", kConfig});
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("24 sequences checked, 0 violations"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("above_clearance"), std::string::npos);
}

TEST(Cli, shouldFailTheCheckOfABadConfigNamingTheKey) {
  const CliRun r = run({"--check", "--config", FATC_BAD_CONFIGS "/clearance_below_chuck.json"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("pocket_above_clearance_offset_z: must be above"), std::string::npos) << r.err;
}

TEST(Cli, shouldCheckAgainstTheSoftLimitsOfAnIni) {
  const CliRun r = run({"--check", "--config", kConfig, "--ini", FATC_BAD_CONFIGS "/narrow_limits.ini"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.out.find("is outside the soft limits"), std::string::npos) << r.out;
}

TEST(Cli, shouldExitTwoOnUsageMistakes) {
  EXPECT_EQ(run({"--plan", "--config", kConfig, "--from", "x", "--to", "1"}).code, 2);
  EXPECT_EQ(run({"--plan", "--config", kConfig}).code, 2);
  EXPECT_EQ(run({"--check"}).code, 2);
  EXPECT_EQ(run({"--bogus"}).err, "unknown argument \"--bogus\"");
}

TEST(Cli, shouldPrintTheDiagram) {
  const CliRun r = run({"--dot"});
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out.rfind("digraph", 0), 0u);
}

}  // namespace
}  // namespace fatc
