#include "core/dry_run/teach.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_run.hpp"
#include "io/files.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using OrderedJson = nlohmann::ordered_json;
using Kind = TeachTarget::Kind;
using test::CliRun;
const auto& run = test::run_cli;

const TeachTarget kPocket3{Kind::pocket, 3};
const TeachTarget kLoading{Kind::loading, 0};
const TeachTarget kSafe{Kind::safe, 0};
const TeachTarget kSensor{Kind::sensor, 0};

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The valid config with pocket 3 carrying keys teaching does not know, and
/// flush.pulses, an integer that must stay one.
std::string rack_config() {
  std::string text = test::kValidConfig;
  text.replace(text.find(R"("3": {"x": 150.0})"), 17,
               R"("3": {"tool": 7, "x": 150.0, "approach": "side", )"
               R"("side_offset": {"x": 0.0, "y": 40.0}})");
  text.insert(text.rfind('}'), R"(, "flush": {"pulses": 2, "pulse_seconds": 0.2})");
  return text;
}

OrderedJson json_of(const std::string& text) { return OrderedJson::parse(text); }

TEST(Teach, shouldWriteConfigJsonAsItIsWrittenByHand) {
  const std::string text = read_text(FATC_SOURCE_DIR "/config/config.json");
  EXPECT_EQ(format_config_json(json_of(text)), text);
}

TEST(Teach, shouldWriteXYZIntoThePocketsEntryKeepingItsOtherKeysInTheirOrder) {
  const TeachResult r = teach(rack_config(), kPocket3, {151.2, 20.0, -79.5}, std::nullopt);
  ASSERT_TRUE(r.text) << r.error;
  EXPECT_EQ(r.change,
            "pocket 3: x 150.0000 → 151.2000, y 20.0000 (unchanged), z -80.0000 → -79.5000");
  EXPECT_EQ(json_of(*r.text)["pockets"]["3"].dump(),
            R"({"tool":7,"x":151.2,"approach":"side","side_offset":{"x":0.0,"y":40.0},)"
            R"("y":20.0,"z":-79.5})");
  EXPECT_NE(r.text->find(R"(    "1": {"x": 50.0},)"), std::string::npos) << *r.text;
}

TEST(Teach, shouldKeepEveryOtherKeyOfTheFileInItsOrder) {
  const TeachResult r = teach(rack_config(), kPocket3, {151.2, 20.0, -79.5}, std::nullopt);
  ASSERT_TRUE(r.text) << r.error;
  OrderedJson before = json_of(rack_config());
  OrderedJson after = json_of(*r.text);
  before["pockets"].erase("3");
  after["pockets"].erase("3");
  EXPECT_EQ(after.dump(), before.dump()) << "same keys, values and order";
  EXPECT_NE(r.text->find(R"("flush": {"pulses": 2, "pulse_seconds": 0.2})"), std::string::npos)
      << "an integer stays an integer: " << *r.text;
}

TEST(Teach, shouldWriteLoadingAndSafeInPlace) {
  const TeachResult loading = teach(test::kValidConfig, kLoading, {25.0, 140.0, -12.0}, {});
  ASSERT_TRUE(loading.text) << loading.error;
  EXPECT_EQ(loading.change,
            "loading: x 20.0000 → 25.0000, y 150.0000 → 140.0000, z -10.0000 → "
            "-12.0000");
  EXPECT_EQ(json_of(*loading.text)["loading"].dump(), R"({"x":25.0,"y":140.0,"z":-12.0})");

  const TeachResult safe = teach(test::kValidConfig, kSafe, {130.0, 80.0, -2.0}, {});
  ASSERT_TRUE(safe.text) << safe.error;
  EXPECT_EQ(safe.change, "safe: x 120.0000 → 130.0000, y 80.0000 (unchanged), z -5.0000 → -2.0000");
  EXPECT_NE(safe.text->find(R"(  "safe": {"x": 130.0, "y": 80.0, "z": -2.0},)"), std::string::npos)
      << *safe.text;
  EXPECT_EQ(parse_config(*safe.text).config->safe.x, 130.0);
}

TEST(Teach, shouldTeachTheSensorsXYAndKeepTheLowestZTheProbeMayGo) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const TeachResult r = teach(test::kValidConfig, kSensor, {21.5, 150.0, nan}, {});
  ASSERT_TRUE(r.text) << r.error << ": the Z given is not used";
  EXPECT_EQ(r.change,
            "sensor (probe_limit): x 20.0000 → 21.5000, y 150.0000 (unchanged); z -90.0000 kept "
            "(the lowest the probe may go)");
  EXPECT_EQ(json_of(*r.text)["probe_limit"].dump(), R"({"x":21.5,"y":150.0,"z":-90.0})");
}

TEST(Teach, shouldRoundToFourDecimalsInMm) {
  const TeachResult r = teach(test::kValidConfig, kSafe, {120.123456, 80.00004, -0.00004}, {});
  ASSERT_TRUE(r.text) << r.error;
  EXPECT_EQ(json_of(*r.text)["safe"].dump(), R"({"x":120.1235,"y":80.0,"z":0.0})");
  EXPECT_EQ(r.change, "safe: x 120.0000 → 120.1235, y 80.0000 (unchanged), z -5.0000 → 0.0000");
}

TEST(Teach, shouldRoundToFiveDecimalsInInch) {
  std::string inch = test::kValidConfig;
  inch.insert(1, R"("units": "inch",)");
  const TeachResult r = teach(inch, kSafe, {120.123456, 80.0, -5.000004}, {});
  ASSERT_TRUE(r.text) << r.error;
  EXPECT_EQ(json_of(*r.text)["safe"].dump(), R"({"x":120.12346,"y":80.0,"z":-5.0})");
  EXPECT_EQ(r.change,
            "safe: x 120.00000 → 120.12346, y 80.00000 (unchanged), z -5.00000 (unchanged)");
  EXPECT_EQ(json_of(*r.text)["units"], "inch");
  EXPECT_EQ(declared_units(inch), Units::inch);
  EXPECT_EQ(declared_units(test::kValidConfig), Units::mm);
}

TEST(Teach, shouldRefuseTheSensorInAPocketsKeepOutWhateverTheProbingOptions) {
  // Load and measure-all probe there even with no probing after a change.
  std::string no_probing = test::kValidConfig;
  no_probing.insert(no_probing.find('{') + 1, R"("probe_after_change": "off", )");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const std::string& text : {std::string(test::kValidConfig), no_probing}) {
    const TeachResult r = teach(text, kSensor, {152.0, 24.0, nan}, {});
    EXPECT_FALSE(r.text);
    EXPECT_NE(r.error.find(": not written: probe_limit: the touch-off sensor at X152 Y24 lies in "
                           "the rack's keep-out at pocket 3 (rack_keepout_margin 20): place it "
                           "clear of the rack"),
              std::string::npos)
        << r.error;
  }
  // A pocket taught over the sensor: the same line.
  const TeachResult pocket = teach(no_probing, kPocket3, {25.0, 150.0, -80.0}, {});
  EXPECT_FALSE(pocket.text);
  EXPECT_NE(pocket.error.find("probe_limit: the touch-off sensor at X20 Y150 lies in the rack's "
                              "keep-out at pocket 3"),
            std::string::npos)
      << pocket.error;
}

TEST(Teach, shouldRefuseAPocketThatDoesNotExist) {
  const TeachResult r = teach(test::kValidConfig, {Kind::pocket, 9}, {350.0, 20.0, -80.0}, {});
  EXPECT_FALSE(r.text);
  EXPECT_EQ(r.error,
            "teach pocket 9 at X350 Y20 Z-80: not written: there is no pocket 9 (pockets: 1, 2, "
            "3, 4, 5, 6); teaching does not add pockets");
}

TEST(Teach, shouldRefuseAPositionCloserToAnotherPocketThanTheSideOffset) {
  const TeachResult r = teach(test::kValidConfig, kPocket3, {195.0, 20.0, -80.0}, {});
  EXPECT_FALSE(r.text);
  EXPECT_EQ(r.error,
            "teach pocket 3 at X195 Y20 Z-80: not written: pockets.4: only 5 from pocket 3, "
            "closer than the side offset (40)");
}

TEST(Teach, shouldRefuseAPocketWhoseApproachPassesThroughAnotherPocketsKeepOut) {
  // Far enough from pocket 4 (47 > 40), but its side (185, 15) is in pocket 4's column.
  const TeachResult r = teach(test::kValidConfig, kPocket3, {185.0, -25.0, -80.0}, {});
  EXPECT_FALSE(r.text);
  EXPECT_EQ(
      r.error.rfind("teach pocket 3 at X185 Y-25 Z-80: not written: M6 T3 from empty (pocket 3), step ", 0),
      0u)
      << r.error;
  EXPECT_NE(r.error.find("side of pocket 3): passes through the rack at pocket 4"),
            std::string::npos)
      << r.error;
}

TEST(Teach, shouldRefuseAPositionOutsideTheSoftLimitsOnlyWithThem) {
  const SoftLimits limits{{-10.0, 400.0}, {-10.0, 300.0}, {-120.0, 0.0}};
  const TeachResult outside = teach(test::kValidConfig, kSafe, {450.0, 80.0, -5.0}, limits);
  EXPECT_FALSE(outside.text);
  EXPECT_EQ(
      outside.error.rfind("teach safe at X450 Y80 Z-5: not written: M6 T1 from empty (pocket 1), step ", 0),
      0u)
      << outside.error;
  EXPECT_NE(outside.error.find("X=450.000 is outside the soft limits -10.000 .. 400.000"),
            std::string::npos)
      << outside.error;
  EXPECT_TRUE(teach(test::kValidConfig, kSafe, {450.0, 80.0, -5.0}, std::nullopt).text);
  EXPECT_TRUE(teach(test::kValidConfig, kSafe, {350.0, 80.0, -5.0}, limits).text);
}

TEST(Teach, shouldRefuseValuesThatAreNotFiniteOrOutOfRange) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(teach(test::kValidConfig, kLoading, {nan, 150.0, -10.0}, {}).error,
            "teach loading at Xnan Y150 Z-10: not written: X is not a finite number");
  EXPECT_EQ(teach(test::kValidConfig, kPocket3, {150.0, 20.0, -inf}, {}).error,
            "teach pocket 3 at X150 Y20 Z-inf: not written: Z is not a finite number");
  EXPECT_EQ(teach(test::kValidConfig, kSensor, {20.0, inf, -90.0}, {}).error,
            "teach sensor at X20 Yinf: not written: Y is not a finite number");
  EXPECT_EQ(teach(test::kValidConfig, kSafe, {1e300, 80.0, -5.0}, {}).error,
            "teach safe at X1e+300 Y80 Z-5: not written: safe.x: must be from -100000 to 100000 "
            "mm, got 1e+300");
  EXPECT_EQ(teach(test::kValidConfig, kSafe, {-1.7e308, 80.0, -5.0}, {}).error,
            "teach safe at X-1.7e+308 Y80 Z-5: not written: safe.x: must be from -100000 to "
            "100000 mm, got -1.7e+308");
  EXPECT_EQ(teach(test::kValidConfig, kLoading, {20.0, 150.0, -95.0}, {}).error,
            "teach loading at X20 Y150 Z-95: not written: probe_limit.z: must not be above "
            "loading.z (-95), got -90");
}

TEST(Teach, shouldRefuseAConfigThatIsNotValidJsonWithTheParseErrorLine) {
  const TeachResult r = teach(R"({"units": "mm", "safe": )", kSafe, {120.0, 80.0, -5.0}, {});
  EXPECT_FALSE(r.text);
  EXPECT_EQ(r.error.rfind("teach safe at X120 Y80 Z-5: not written: line 1, column ", 0), 0u)
      << r.error;
  EXPECT_NE(r.error.find("invalid JSON"), std::string::npos) << r.error;
  EXPECT_EQ(teach(R"({"safe": {"x": 1}, "safe": {"x": 2}})", kSafe, {1, 2, 3}, {}).error,
            "teach safe at X1 Y2 Z3: not written: safe: appears twice");
  EXPECT_EQ(teach("[1, 2]", kSafe, {1, 2, 3}, {}).error,
            "teach safe at X1 Y2 Z3: not written: config: expected a JSON object at the top, got "
            "an array");
  EXPECT_EQ(teach("", kSafe, {1, 2, 3}, {}).error.rfind("teach safe at X1 Y2 Z3: not written: ", 0),
            0u);
}

TEST(Teach, shouldRefuseWhatTheRestOfTheConfigGetsWrong) {
  std::string typo = test::kValidConfig;
  typo.insert(1, R"("chuck_second": 0.5,)");
  EXPECT_EQ(teach(typo, kSafe, {120.0, 80.0, -5.0}, {}).error,
            "teach safe at X120 Y80 Z-5: not written: chuck_second: unknown key, did you mean "
            "\"chuck_seconds\"?");
  std::string not_object = test::kValidConfig;
  not_object.replace(not_object.find(R"({"x": 150.0})"), 12, "150");
  EXPECT_EQ(teach(not_object, kPocket3, {150.0, 20.0, -80.0}, {}).error,
            "teach pocket 3 at X150 Y20 Z-80: not written: pockets.3: expected an object, got 150");
}

TEST(Teach, shouldReadTargetsAsTheCommandLineGivesThem) {
  EXPECT_EQ(parse_teach_target("pocket:12")->pocket, 12);
  EXPECT_EQ(parse_teach_target("sensor")->kind, Kind::sensor);
  EXPECT_EQ(parse_teach_target("loading")->kind, Kind::loading);
  EXPECT_EQ(parse_teach_target("safe")->kind, Kind::safe);
  for (const char* bad :
       {"pocket:", "pocket:0", "pocket:03", "pocket:-1", "pocket 3", "Safe", ""}) {
    EXPECT_FALSE(parse_teach_target(bad)) << bad;
  }
}

/// A folder holding a config to teach through the command line.
class TeachCli : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/fatc_teach_XXXXXX";
    folder_ = ::mkdtemp(pattern);
    config_ = folder_ + "/config.json";
    std::ofstream(config_) << test::kValidConfig;
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  std::string folder_;
  std::string config_;
};

TEST_F(TeachCli, shouldWriteTheConfigAndKeepTheOldOneAsBak) {
  const std::string before = read_text(config_);
  std::ofstream(config_ + ".bak") << "an older backup";
  ::chmod(config_.c_str(), 0640);
  const CliRun r = run({"--teach", "pocket:3", "--at", "151.2,20,-79.5", "--config", config_});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out,
            "pocket 3: x 150.0000 → 151.2000, y 20.0000 (unchanged), z -80.0000 → -79.5000\n"
            "written (previous file kept as " +
                config_ + ".bak)\n");
  EXPECT_EQ(read_text(config_ + ".bak"), before);
  const ConfigResult loaded = io::load_config_file(config_);
  ASSERT_TRUE(loaded.config) << loaded.errors.front();
  struct stat st;
  ASSERT_EQ(::stat(config_.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u) << "the config keeps its permissions";
  EXPECT_FALSE(std::filesystem::exists(config_ + ".tmp"));
  EXPECT_FALSE(std::filesystem::exists(config_ + ".bak.tmp"));
}

TEST_F(TeachCli, shouldLeaveTheConfigAndTheBakAsTheyWereWhenRefused) {
  std::ofstream(config_ + ".bak") << "an older backup";
  const std::string before = read_text(config_);
  const CliRun r = run({"--teach", "pocket:3", "--at", "195,20,-80", "--config", config_});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, config_ +
                       ": teach pocket 3 at X195 Y20 Z-80: not written: pockets.4: only 5 from "
                       "pocket 3, closer than the side offset (40)\n");
  EXPECT_EQ(read_text(config_), before);
  EXPECT_EQ(read_text(config_ + ".bak"), "an older backup");
}

TEST_F(TeachCli, shouldCheckAgainstTheSoftLimitsOfTheIni) {
  const std::string before = read_text(config_);
  const CliRun narrow = run({"--teach", "safe", "--at", "120,80,-5", "--config", config_, "--ini",
                             FATC_BAD_CONFIGS "/narrow_limits.ini"});
  EXPECT_EQ(narrow.code, 1);
  EXPECT_NE(narrow.err.find("is outside the soft limits"), std::string::npos) << narrow.err;
  EXPECT_EQ(read_text(config_), before);
  EXPECT_FALSE(std::filesystem::exists(config_ + ".bak"));
  const CliRun sim = run({"--teach", "sensor", "--at", "21,150,0", "--config", config_, "--ini",
                          FATC_SOURCE_DIR "/config/sim/fixed_atc_sim.ini"});
  EXPECT_EQ(sim.code, 0) << sim.err;
}

TEST_F(TeachCli, shouldRefuseASymlinkedConfigWritingNothing) {
  const std::string link = folder_ + "/link.json";
  std::filesystem::create_symlink(config_, link);
  const std::string before = read_text(config_);
  const CliRun r = run({"--teach", "safe", "--at", "130,80,-5", "--config", link});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, link + ": a symbolic link (to " + config_ +
                       "): not written, the link would become a file of its own; give the file "
                       "it points to\n");
  EXPECT_TRUE(std::filesystem::is_symlink(link));
  EXPECT_EQ(read_text(config_), before);
  EXPECT_FALSE(std::filesystem::exists(link + ".bak"));
}

TEST_F(TeachCli, shouldExitTwoOnBadArgumentsAndUnreadableFiles) {
  EXPECT_EQ(run({"--teach", "pocket:x", "--at", "1,2,3", "--config", config_}).err,
            "--teach: expected pocket:N, loading, safe, sensor or datum, got \"pocket:x\"");
  EXPECT_EQ(run({"--teach", "", "--at", "1,2,3", "--config", config_}).err,
            "--teach: expected pocket:N, loading, safe, sensor or datum, got \"\"");
  EXPECT_EQ(run({"--teach", "safe", "--config", config_}).err,
            "--teach needs --at X,Y,Z (the machine position, G53)");
  // Blanks around a number are a machinist's ( 1,2,3); the rest is refused naming --at.
  for (const char* at : {"1,2", "1,2,3,4", "1,,3", "x,2,3", ""}) {
    const CliRun r = run({"--teach", "safe", "--at", at, "--config", config_});
    EXPECT_EQ(r.code, 2) << at;
    EXPECT_EQ(r.err.rfind("--at: ", 0), 0u) << r.err;
  }
  EXPECT_EQ(run({"--teach", "safe", "--at", "1,2,3"}).err, "--config FILE is required");
  EXPECT_EQ(run({"--check", "--config", config_, "--at", "1,2,3"}).err,
            "--at is not used by --check");
  EXPECT_EQ(run({"--teach", "safe", "--at", "1,2,3", "--config", config_, "--state", "s"}).err,
            "--state is not used by --teach");

  const CliRun missing = run({"--teach", "safe", "--at", "1,2,3", "--config", folder_ + "/none"});
  EXPECT_EQ(missing.code, 2);
  EXPECT_EQ(missing.err, folder_ + "/none: cannot open (No such file or directory)\n");
  const CliRun folder = run({"--teach", "safe", "--at", "1,2,3", "--config", folder_});
  EXPECT_EQ(folder.code, 2);
  EXPECT_EQ(folder.err, folder_ + ": expected a regular file, got a directory: not written\n");
  const CliRun ini = run(
      {"--teach", "safe", "--at", "1,2,3", "--config", config_, "--ini", folder_ + "/none.ini"});
  EXPECT_EQ(ini.code, 2);
  EXPECT_FALSE(std::filesystem::exists(config_ + ".bak"));
}

TEST_F(TeachCli, shouldRefuseNotANumberAndAConfigThatIsNotJson) {
  // nan is no number a machinist types: refused where the command line is read.
  const CliRun nan = run({"--teach", "loading", "--at", "nan,150,-10", "--config", config_});
  EXPECT_EQ(nan.code, 2);
  EXPECT_EQ(nan.err.rfind("--at: X \"nan\" is not a decimal number", 0), 0u) << nan.err;
  std::ofstream(config_) << "{\"units\": \"mm\",";
  const CliRun broken = run({"--teach", "loading", "--at", "20,150,-10", "--config", config_});
  EXPECT_EQ(broken.code, 1);
  EXPECT_NE(broken.err.find("not written: line 1, column "), std::string::npos) << broken.err;
  EXPECT_EQ(read_text(config_), "{\"units\": \"mm\",");
  EXPECT_FALSE(std::filesystem::exists(config_ + ".bak"));
}

}  // namespace
}  // namespace fatc
