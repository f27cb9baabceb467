#include "cli/cli.hpp"
#include "cli/parse_options.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::CliRun;
const auto& run = test::run_cli;

const std::string kConfig = FATC_SOURCE_DIR "/config/config.json";

TEST(Cli, shouldPrintThePlanOfAChangeOneStepALine) {
  const CliRun r = run({"--plan", "--config", kConfig, "--from", "2", "--to", "5"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("M6 T5 with T2 in the spindle"), std::string::npos);
  EXPECT_NE(r.out.find("feed       X=100.000 Y=20.000 F600"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("done       T5"), std::string::npos);
}

TEST(Cli, shouldEstimateThePlannedChangeOnBothPaths) {
  const CliRun r = run({"--plan", "--config", kConfig, "--from", "2", "--to", "5"});
  const auto at = r.out.find("estimated ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const std::string line = r.out.substr(at, r.out.find('\n', at) - at);
  // The sample config's path first, the other in brackets.
  EXPECT_NE(line.find(" on the direct path ("), std::string::npos) << line;
  EXPECT_NE(line.find(" on the prototype path) (moves "), std::string::npos) << line;
  EXPECT_NE(r.out.find("\n  from safe: the moves at 3000 mm/min and 500 "
                      "mm/s², assumed (--ini gives the machine's [AXIS_*] and [TRAJ] limits), "
                      "each an exact stop (G61.1) at the axes' full acceleration as LinuxCNC "
                      "plans it, plus the dwells, 17 ms a step"),
            std::string::npos)
      << line;
  double prototype = 0.0, direct = 0.0;
  ASSERT_EQ(std::sscanf(line.c_str(), "estimated %lf s on the direct path (%lf s", &direct,
                        &prototype),
            2)
      << line;
  EXPECT_LT(direct, prototype) << line;
}

TEST(Cli, shouldPrintTheBoundFromTheInisVelocitiesAndAccelerations) {
  const std::string ini = FATC_SOURCE_DIR "/config/sim/fixed_atc_sim.ini";
  const CliRun r = run({"--plan", "--config", kConfig, "--from", "2", "--to", "5", "--ini", ini});
  const auto at = r.out.find("bound ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const std::string line = r.out.substr(at, r.out.find('\n', at) - at);
  double bound = 0.0, prototype = 0.0, blended = 0.0;
  ASSERT_EQ(std::sscanf(line.c_str(),
                        "bound %lf s: the direct path's moves at the velocities and "
                        "accelerations of %*s each an exact stop, plus the dwells "
                        "(the prototype path's: %lf s; with each run of rapids as one move, "
                        "more than blending could save: %lf s)",
                        &bound, &prototype, &blended),
            3)
      << line;
  EXPECT_LT(bound, prototype) << line;
  EXPECT_LT(blended, bound) << line;
  // The same model at the machine's limits: the estimate (LinuxCNC's planner,
  // the handshakes) of the direct path is never below its bound.
  double estimate = 0.0;
  ASSERT_EQ(std::sscanf(r.out.substr(r.out.find("estimated ")).c_str(),
                        "estimated %lf s on the direct path", &estimate),
            1);
  double meanwhile = 0.0, rest = 0.0;
  const auto running_down = r.out.find("while the spindle runs down: ");
  ASSERT_NE(running_down, std::string::npos) << r.out;
  ASSERT_EQ(std::sscanf(r.out.c_str() + running_down,
                        "while the spindle runs down: %lf s of the bound's moves (up to safe Z "
                        "and across at it), the rest %lf s once it stands",
                        &meanwhile, &rest),
            2)
      << r.out;
  EXPECT_GT(meanwhile, 0.0);
  EXPECT_NEAR(meanwhile + rest, bound, 0.1 + 1e-9) << "the same moves, parted where it stands";
  EXPECT_GT(estimate, bound) << r.out;

  const CliRun without = run({"--plan", "--config", kConfig, "--from", "2", "--to", "5"});
  EXPECT_NE(
      without.out.find("\nbound: --ini gives it (the machine's velocities and accelerations)\n"),
      std::string::npos)
      << without.out;
}

/// The sim's INI, its limits in `units` (mm or inch) per second.
std::string sim_ini_in(const std::string& units) {
  const std::string ini = ::testing::TempDir() + "fatc_sim_" + units + ".ini";
  std::ifstream in(FATC_SOURCE_DIR "/config/sim/fixed_atc_sim.ini");
  std::ofstream out(ini);
  const double scale = units == "inch" ? 1.0 / 25.4 : 1.0;
  for (std::string line; std::getline(in, line);) {
    const auto equals = line.find(" = ");
    const std::string key = line.substr(0, equals);
    if (key == "LINEAR_UNITS") {
      line = "LINEAR_UNITS = " + units;
    } else if (key.find("VELOCITY") != std::string::npos ||
               key.find("ACCELERATION") != std::string::npos) {
      char value[64];
      std::snprintf(value, sizeof value, "%.12g", std::stod(line.substr(equals + 3)) * scale);
      line = key + " = " + value;
    }
    out << line << "\n";
  }
  return ini;
}

TEST(Cli, shouldEstimateTheSameChangeOnAnInchIniAsOnItsMmTwin) {
  std::string parts[2];
  int i = 0;
  for (const char* units : {"mm", "inch"}) {
    const std::string ini = sim_ini_in(units);
    const CliRun r = run({"--plan", "--config", kConfig, "--from", "2", "--to", "5", "--ini", ini});
    std::remove(ini.c_str());
    const auto at = r.out.find("(moves ");
    ASSERT_NE(at, std::string::npos) << r.out;
    parts[i++] = r.out.substr(at, r.out.find('\n', at) - at);
  }
  EXPECT_EQ(parts[0], parts[1]);
}

TEST(Cli, shouldCountIocontrolsCyclesAtTheInisCycleTime) {
  // The sim's own: 0.01 s, as docs/setup.md advises.
  const CliRun sim = run({"--plan", "--config", kConfig, "--from", "2", "--to", "5", "--ini",
                          FATC_SOURCE_DIR "/config/sim/fixed_atc_sim.ini"});
  EXPECT_NE(sim.out.find("0.12 s a change (4.5 of iocontrol's 0.01 s cycles for T and M6, 75 "
                         "ms for the remap)"),
            std::string::npos)
      << sim.out;
  // LinuxCNC's usual 0.1 s.
  const std::string ini = ::testing::TempDir() + "fatc_usual_io.ini";
  std::ifstream in(FATC_SOURCE_DIR "/config/sim/fixed_atc_sim.ini");
  std::ofstream out(ini);
  bool in_emcio = false;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] == '[') in_emcio = line == "[EMCIO]";
    out << (in_emcio && line.rfind("CYCLE_TIME", 0) == 0 ? "CYCLE_TIME = 0.100" : line) << "\n";
  }
  out.close();
  const CliRun usual =
      run({"--plan", "--config", kConfig, "--from", "2", "--to", "5", "--ini", ini});
  std::remove(ini.c_str());
  EXPECT_NE(usual.out.find("0.53 s a change (4.5 of iocontrol's 0.1 s cycles"), std::string::npos)
      << usual.out;
}

TEST(Cli, shouldSayWhyThereIsNoBoundWhenTheIniLacksAVelocity) {
  const std::string ini = ::testing::TempDir() + "fatc_no_velocity.ini";
  std::ifstream in(FATC_SOURCE_DIR "/config/sim/fixed_atc_sim.ini");
  std::ofstream out(ini);
  bool in_axis_y = false;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] == '[') in_axis_y = line == "[AXIS_Y]";
    if (!(in_axis_y && line.rfind("MAX_VELOCITY", 0) == 0)) out << line << "\n";
  }
  out.close();
  const CliRun r = run({"--plan", "--config", kConfig, "--from", "2", "--to", "5", "--ini", ini});
  std::remove(ini.c_str());
  EXPECT_NE(r.out.find("\nbound: not known: " + ini +
                       ": [AXIS_Y]MAX_VELOCITY: missing (the bound needs every axis' velocity "
                       "and acceleration)\n"),
            std::string::npos)
      << r.out;
}

TEST(Cli, shouldExitOneWhenThePlannedChangeIsRefused) {
  nlohmann::json config = nlohmann::json::parse(std::ifstream(kConfig));
  config["manual_tools"] = false;
  const std::string path = ::testing::TempDir() + "fatc_manual_tools_off.json";
  std::ofstream(path) << config.dump();
  const CliRun r = run({"--plan", "--config", path, "--from", "0", "--to", "42"});
  std::remove(path.c_str());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.out.find("tool 42 is in no pocket of the rack (and manual_tools is off)"),
            std::string::npos)
      << r.out << r.err;
}

TEST(Cli, shouldPlanAManualToolWithTheOperatorHandingItOver) {
  const CliRun r = run({"--plan", "--config", kConfig, "--from", "2", "--to", "42"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("insert tool 42 into the spindle"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("done       T42"), std::string::npos) << r.out;
}

TEST(Cli, shouldSayWhichSensorsTheConfigWires) {
  nlohmann::json config = nlohmann::json::parse(std::ifstream(kConfig));
  config["sensors"] = {
      {"tool_present", true}, {"air_pressure", true}, {"pocket_occupancy", {3, 1}}};
  config["sensor_timeout_seconds"] = 0.5;
  const std::string path = ::testing::TempDir() + "fatc_sensors.json";
  std::ofstream(path) << config.dump();
  const CliRun r = run({"--check", "--config", path, "--state", path + ".none"});
  std::remove(path.c_str());
  EXPECT_NE(r.out.find("sensors wired: tool-present, air-pressure-ok, pocket-occupied-1 3 "
                       "(sensor_timeout_seconds 0.5)\n"),
            std::string::npos)
      << r.out << r.err;
  EXPECT_NE(run({"--check", "--config", kConfig}).out.find("sensors wired: none\n"),
            std::string::npos);
}

TEST(Cli, shouldPlanAChangeWithEverySensorWiredAsTheRackWouldBehave) {
  nlohmann::json config = nlohmann::json::parse(std::ifstream(kConfig));
  config["sensors"] = {{"tool_present", true}, {"drawbar_open", true}, {"drawbar_closed", true},
                       {"air_pressure", true}, {"zero_speed", true},   {"pocket_occupancy", true}};
  const std::string path = ::testing::TempDir() + "fatc_sensors_plan.json";
  std::ofstream(path) << config.dump();
  const CliRun wired = run({"--plan", "--config", path, "--from", "2", "--to", "5"});
  std::remove(path.c_str());
  const CliRun plain = run({"--plan", "--config", kConfig, "--from", "2", "--to", "5"});
  EXPECT_EQ(wired.code, 0) << wired.err;
  EXPECT_EQ(wired.out, plain.out);
}

TEST(Cli, shouldPassTheCheckOfTheSampleConfig) {
  const CliRun r = run({"--check", "--config", kConfig});
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("36 sequences checked, 0 violations"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("above_clearance"), std::string::npos);
}

TEST(Cli, shouldFailTheCheckOfABadConfigNamingTheKey) {
  const CliRun r = run({"--check", "--config", FATC_BAD_CONFIGS "/clearance_below_chuck.json"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("pocket_above_clearance_offset_z: must be above"), std::string::npos)
      << r.err;
}

TEST(Cli, shouldCheckAgainstTheSoftLimitsOfAnIni) {
  const CliRun r =
      run({"--check", "--config", kConfig, "--ini", FATC_BAD_CONFIGS "/narrow_limits.ini"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.out.find("is outside the soft limits"), std::string::npos) << r.out;
}

TEST(Cli, shouldExitTwoOnUsageMistakes) {
  EXPECT_EQ(run({"--plan", "--config", kConfig, "--from", "x", "--to", "1"}).code, 2);
  EXPECT_EQ(run({"--plan", "--config", kConfig}).code, 2);
  EXPECT_EQ(run({"--check"}).code, 2);
  EXPECT_EQ(run({"--bogus"}).err, "unknown argument \"--bogus\"");
}

TEST(Cli, shouldRefuseAnOptionGivenTwice) {
  const CliRun r = run({"--check", "--config", "a.json", "--config", "b.json"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "--config given twice (\"a.json\" and \"b.json\")");
  EXPECT_EQ(run({"--check", "--check", "--config", kConfig}).err, "--check given twice");
}

TEST(Cli, shouldRefuseTwoModesAtOnce) {
  EXPECT_EQ(run({"--check", "--plan", "--config", kConfig}).err,
            "--check and --plan cannot be combined");
  EXPECT_EQ(run({"--dot", "--help"}).err, "--dot and --help cannot be combined");
}

TEST(Cli, shouldRefuseAnEmptyPathInsteadOfSkippingTheFile) {
  const CliRun r = run({"--check", "--config", kConfig, "--ini", ""});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "--ini: expected a file path, got nothing");
  EXPECT_EQ(run({"--config", ""}).err, "--config: expected a file path, got nothing");
}

TEST(Cli, shouldRefuseAnOptionWhereAValueBelongs) {
  EXPECT_EQ(run({"--config", "--check"}).err, "--config needs a value, got the option \"--check\"");
}

TEST(Cli, shouldRefuseAnOptionTheModeDoesNotRead) {
  EXPECT_EQ(run({"--check", "--config", kConfig, "--from", "1"}).err,
            "--from is not used by --check");
  EXPECT_EQ(run({"--config", kConfig, "--ini", "m.ini"}).err,
            "--ini is not used by the component (no --check, --plan, --dot)");
  EXPECT_EQ(run({"--plan", "--config", kConfig, "--from", "1", "--to", "2", "--at", "1,2,3"}).err,
            "--at is not used by --plan");
  EXPECT_EQ(run({"--dot", "--config", kConfig}).err, "--config is not used by --dot");
}

TEST(Cli, shouldEscapeAnUnknownArgument) {
  EXPECT_EQ(run({"--\x1b[2Jbogus"}).err, "unknown argument \"--\\x1b[2Jbogus\"");
}

TEST(Cli, shouldCheckTheStateFileNextToTheConfigByDefault) {
  std::string error;
  const auto options = io::parse_options({"--check", "--config", "/x/config.json"}, error);
  ASSERT_TRUE(options) << error;
  EXPECT_EQ(options->state_path, "/x/config.json.state");
  const auto component = io::parse_options({"--config", "/x/config.json"}, error);
  EXPECT_EQ(component->state_path, "/x/config.json.state") << "the same file the component reads";
}

/// A folder with files for one --check run.
class CheckRun : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/fatc_check_XXXXXX";
    folder_ = ::mkdtemp(pattern);
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }
  std::string file(const std::string& name, const std::string& text) {
    const std::string path = folder_ + "/" + name;
    std::ofstream(path) << text;
    return path;
  }
  std::string folder_;
};

const char* const kGoodState =
    R"({"version": 1, "spindle": 3, "uncertain": false, "in_pocket": [1, 2, 4, 5, 6], "lengths": {"3": 17.5}})";

TEST_F(CheckRun, shouldReadTheStateAndSayWhatItHolds) {
  const std::string state = file("state.json", kGoodState);
  const CliRun r = run({"--check", "--config", kConfig, "--state", state});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find(state + ": spindle T3, 5 tools in their pockets, 1 lengths"),
            std::string::npos)
      << r.out;
}

TEST_F(CheckRun, shouldFailOnABadOrUnreadableStateEvenWhenTheConfigIsGood) {
  const std::string state = file("state.json", R"({"version": 1, "spindle": 1e309})");
  const CliRun bad = run({"--check", "--config", kConfig, "--state", state});
  EXPECT_EQ(bad.code, 1);
  EXPECT_EQ(bad.err,
            state + ": line 1, column 31: invalid JSON: number overflow parsing '1e309'\n");
  EXPECT_EQ(bad.out,
            "36 sequences checked against the rack keep-out, 0 violations\n"
            "state file not valid: where the tools are not checked\n");
  ASSERT_EQ(::mkfifo((folder_ + "/fifo").c_str(), 0600), 0);
  const CliRun fifo = run({"--check", "--config", kConfig, "--state", folder_ + "/fifo"});
  EXPECT_EQ(fifo.code, 1);
  EXPECT_EQ(fifo.err, folder_ + "/fifo: expected a regular file, got a FIFO\n");
  EXPECT_EQ(fifo.out,
            "36 sequences checked against the rack keep-out, 0 violations\n"
            "state file unreadable: where the tools are not checked\n");
}

TEST_F(CheckRun, shouldSayWhatIsWrongInEachOfTheThreeFiles) {
  const std::string config = file("config.json", R"({"chuck_seconds": 1e10})");
  const std::string state = file("state.json", R"({"version": 1, "spindle": 0, "spindle": 2})");
  const std::string ini = file("machine.ini", "[TRAJ]\nLINEAR_UNITS = furlong\n");
  const CliRun r = run({"--check", "--config", config, "--state", state, "--ini", ini});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find(config + ": chuck_seconds: must be from 0.01 to 60 seconds, got 1e+10\n"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(ini + ": [TRAJ]LINEAR_UNITS (line 2): expected mm, metric, in, inch, "
                             "imperial or machine units per mm, got \"furlong\"\n"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(state + ": spindle: appears twice\n"), std::string::npos) << r.err;
}

TEST_F(CheckRun, shouldSayMinAboveMaxInOneLineNotOnceAWaypoint) {
  const std::string ini = file(
      "machine.ini",
      "[TRAJ]\nLINEAR_UNITS = mm\n[AXIS_X]\nMIN_LIMIT = 500\nMAX_LIMIT = -10\n"
      "[AXIS_Y]\nMIN_LIMIT = -10\nMAX_LIMIT = 300\n[AXIS_Z]\nMIN_LIMIT = -120\nMAX_LIMIT = 0\n");
  const CliRun r = run({"--check", "--config", kConfig, "--ini", ini});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err,
            ini + ": [AXIS_X]MIN_LIMIT (line 4): must not be above MAX_LIMIT (-10), got 500\n");
}

TEST_F(CheckRun, shouldPassTheSampleConfigOnTheSimulatedMill) {
  const CliRun r =
      run({"--check", "--config", kConfig, "--ini", FATC_SOURCE_DIR "/config/sim/fixed_atc_sim.ini",
           "--state", folder_ + "/none.json"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("none.json: no state saved yet"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("36 sequences checked, 0 violations"), std::string::npos) << r.out;
}

/// The simulated mill's INI with `from` replaced by `to` in its text.
std::string sim_ini_with(const std::string& from, const std::string& to) {
  std::ifstream in(FATC_SOURCE_DIR "/config/sim/fixed_atc_sim.ini");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST_F(CheckRun, shouldRefuseAStepTimeoutTheChangersWaitsOutlast) {
  std::ifstream sample(FATC_SOURCE_DIR "/config/config.json");
  std::string text((std::istreambuf_iterator<char>(sample)), std::istreambuf_iterator<char>());
  const std::string ten = R"("spindle_stop_timeout_seconds": 10.0)";
  ASSERT_NE(text.find(ten), std::string::npos);
  text.replace(text.find(ten), ten.size(), R"("spindle_stop_timeout_seconds": 45)");
  const std::string config = file("config.json", text);
  const std::string ini = file("sim.ini", sim_ini_with("STEP_TIMEOUT = 30", "STEP_TIMEOUT = 30"));
  const CliRun r = run({"--check", "--config", config, "--ini", ini});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find(ini + ": [FIXED_ATC_PROBE]STEP_TIMEOUT (line "), std::string::npos) << r.err;
  EXPECT_NE(
      r.err.find(
          "): 30 s is not longer than 45 s, the longest the changer may keep the executor "
          "waiting for a step (its plans with every sensor answering at its timeout, "
          "spindle_stop_timeout_seconds 45 s, and a first grip that fails): the executor "
          "would stop the program while the changer waits; raise it\n"),
      std::string::npos)
      << r.err;
}

TEST_F(CheckRun, shouldNameEachMissingOrMalformedExecutorKey) {
  std::string text = sim_ini_with("STEP_READY_IN = 03", "STEP_READY_IN = 3");
  text.replace(text.find("EXECUTOR_CALL_OUT = 01"), 22, "EXECUTOR_CALL_OUT = 02");
  text.replace(text.find("STEP_TIMEOUT = 30\n"), 18, "");
  const std::string ini = file("sim.ini", text);
  const CliRun r = run({"--check", "--config", kConfig, "--ini", ini});
  EXPECT_EQ(r.code, 1);
  const std::vector<std::string> said = {
      ini +
          ": [FIXED_ATC_PROBE]STEP_TIMEOUT: missing; the executor (fixed_atc_probe_execute.ngc) "
          "reads it\n",
      "): expected two digits as in the motion pin names (03), got \"3\"\n",
      "): motion.analog-out-02 is PROBE_Z_OUT's too; each needs its own\n"};
  for (const std::string& line : said) {
    EXPECT_NE(r.err.find(line), std::string::npos) << line << " in\n" << r.err;
  }
}

// ---- what --check says when an input cannot be read ----

TEST_F(CheckRun, shouldSayTheSoftLimitsWereNotCheckedWhenTheIniIsUnreadable) {
  const CliRun r = run({"--check", "--config", kConfig, "--ini", folder_ + "/none.ini", "--state",
                        folder_ + "/none.state"});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err, folder_ + "/none.ini: cannot open (No such file or directory)\n");
  EXPECT_EQ(r.out, folder_ +
                       "/none.state: no state saved yet: the component starts with each pocket "
                       "holding its first-start tool\n"
                       "36 sequences checked against the rack keep-out, 0 violations\n"
                       "INI unreadable: soft limits not checked\n");
}

TEST_F(CheckRun, shouldSayTheSoftLimitsWereNotCheckedWhenTheIniIsNotValid) {
  const std::string ini = file("machine.ini", "[TRAJ]\nLINEAR_UNITS = furlong\n");
  const CliRun r = run({"--check", "--config", kConfig, "--ini", ini});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.out.substr(r.out.find('\n') + 1),
            "36 sequences checked against the rack keep-out, 0 violations\n"
            "INI not valid: soft limits not checked\n");
}

TEST_F(CheckRun, shouldNotEndInZeroViolationsWhenTheExecutorSectionIsNotValid) {
  const std::string ini = file("sim.ini", sim_ini_with("PROBE_Z_OUT = 02", "PROBE_Z_OUT = 0\u202e2"));
  const CliRun r = run({"--check", "--config", kConfig, "--ini", ini});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("[FIXED_ATC_PROBE]PROBE_Z_OUT (line "), std::string::npos) << r.err;
  const std::string last = r.out.substr(r.out.rfind('\n', r.out.size() - 2) + 1);
  EXPECT_EQ(last, "INI [FIXED_ATC_PROBE] not valid (1 problem): M6, the panel's flows and the chuck M-codes would not run as set up\n");
  EXPECT_EQ(r.out.find("station"), std::string::npos) << "no full report: " << r.out;
}

TEST_F(CheckRun, shouldSayNothingWasCheckedAgainstTheRackWhenTheConfigIsUnreadable) {
  ASSERT_EQ(::mkfifo((folder_ + "/config.json").c_str(), 0600), 0);
  const CliRun r = run({"--check", "--config", folder_ + "/config.json", "--state",
                        folder_ + "/none.state", "--ini", folder_ + "/none.ini"});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err, folder_ + "/config.json: expected a regular file, got a FIFO\n" + folder_ +
                       "/none.ini: cannot open (No such file or directory)\n");
  const std::string last = r.out.substr(r.out.rfind('\n', r.out.size() - 2) + 1);
  EXPECT_EQ(last,
            "config unreadable: the rack and its sequences not checked; INI unreadable: soft "
            "limits not checked\n");
  EXPECT_EQ(r.out.find("violations"), std::string::npos) << r.out;
}

TEST_F(CheckRun, shouldEscapeADuplicatedAnalogPinOfTheExecutor) {
  std::string text = sim_ini_with("PROBE_Z_OUT = 02", "PROBE_Z_OUT = 0\u202e1");
  text.replace(text.find("EXECUTOR_CALL_OUT = 01"), 22, "EXECUTOR_CALL_OUT = 0\u202e1");
  const std::string ini = file("sim.ini", text);
  const CliRun r = run({"--check", "--config", kConfig, "--ini", ini});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("): motion.analog-out-0\\u{202e}1 is PROBE_Z_OUT's too; each needs its "
                       "own\n"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("\u202e"), std::string::npos) << "no raw direction override";
}

TEST_F(CheckRun, shouldListAtMostTwentyPocketSensorsInTheCheck) {
  nlohmann::json config = nlohmann::json::parse(test::kValidConfig);
  config["pockets"] = nlohmann::json::object();
  config["sensors"]["pocket_occupancy"] = nlohmann::json::array();
  for (int pocket = 1; pocket <= 30; ++pocket) {
    config["pockets"][std::to_string(pocket)] = {{"x", 50.0 * pocket}};
    config["sensors"]["pocket_occupancy"].push_back(pocket);
  }
  const CliRun r = run(
      {"--check", "--config", file("config.json", config.dump()), "--state", folder_ + "/none"});
  EXPECT_NE(r.out.find("sensors wired: pocket-occupied-1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 "
                       "17 18 19 20 \u2026 and 10 more (sensor_timeout_seconds"),
            std::string::npos)
      << r.out;
}

TEST_F(CheckRun, shouldCutEveryLineItPrintsAtFourHundredCharacters) {
  // An INI whose path is as long as a path may be shown, and whose refusal
  // is long: the line stops at 400 characters, "…" the last.
  std::string folder = folder_;
  while (folder.size() < 190) {
    folder += "/" + std::string(40, 'd');
    ::mkdir(folder.c_str(), 0700);
  }
  const std::string ini = folder + "/sim.ini";
  std::ofstream(ini) << sim_ini_with("STEP_TIMEOUT = 30", "STEP_TIMEOUT = 1");
  const CliRun r =
      run({"--check", "--config", kConfig, "--ini", ini, "--state", folder_ + "/none"});
  EXPECT_NE(r.err.find("STEP_TIMEOUT (line "), std::string::npos) << r.err;
  std::size_t start = 0;
  for (std::size_t end = r.err.find('\n'); end != std::string::npos;
       start = end + 1, end = r.err.find('\n', start)) {
    const std::string line = r.err.substr(start, end - start);
    std::size_t chars = 0;
    for (const char c : line) chars += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
    EXPECT_LE(chars, 400u) << line;
  }
  EXPECT_NE(r.err.find("\u2026\n"), std::string::npos) << r.err;
}

/// The program itself run with `args` (a shell line): its exit status and
/// what it printed on stdout and stderr.
CliRun run_program(const std::string& args) {
  const std::string command = std::string(FATC_PROGRAM) + " " + args + " 2>&1";
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return {-1, "", "popen failed"};
  std::string said;
  char buffer[4096];
  while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) said.append(buffer, n);
  return {WEXITSTATUS(::pclose(pipe)), said, ""};
}

TEST(Usage, shouldBeOneLineThatPointsToHelp) {
  const CliRun twice = run_program("--plan --config c.json --check");
  EXPECT_EQ(twice.code, 2);
  EXPECT_EQ(twice.out, "fixed_atc_probe: --plan and --check cannot be combined (see --help)\n");
  const CliRun unknown = run_program("--bogus");
  EXPECT_EQ(unknown.code, 2);
  EXPECT_EQ(unknown.out, "fixed_atc_probe: unknown argument \"--bogus\" (see --help)\n");
  const CliRun bare = run_program("--check");
  EXPECT_EQ(bare.code, 2);
  EXPECT_EQ(bare.out, "fixed_atc_probe: --config FILE is required (see --help)\n");
  EXPECT_NE(run_program("--help").out.find("usage: fixed_atc_probe"), std::string::npos);
}

TEST_F(CheckRun, shouldNotStartTheComponentOnAStateThatIsItsConfig) {
  const std::string config = file("config.json", test::kValidConfig);
  const CliRun r = run_program("--config " + config + " --state " + config);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.out, "fixed_atc_probe: --state \"" + config +
                       "\" is the file given as --config: nothing written\n");
}

TEST_F(CheckRun, shouldNotStartTheComponentOnACutOffPocketTheConfigDoesNotHave) {
  const std::string config = file("config.json", test::kValidConfig);
  ToolState tools = ToolState::fresh(test::valid_config());
  tools.uncertain = true;
  tools.in_progress = InProgress{"M6 T4", "returning tool 3 to pocket 9", 9};
  const std::string state = file("config.json.state", to_json(tools));
  const CliRun r = run_program("--config " + config);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.out, "fixed_atc_probe: " + state +
                       ": in_progress.pocket: the sequence was cut off at pocket 9, which "
                       "config.json does not have\n");
}

TEST(Cli, shouldPrintTheDiagram) {
  const CliRun r = run({"--dot"});
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out.rfind("digraph", 0), 0u);
}

}  // namespace
}  // namespace fatc

namespace fatc {
namespace {

TEST_F(CheckRun, shouldReadTheStateFileTheIniNamesWhenNoStateIsGiven) {
  // The component gets [FIXED_ATC_PROBE]STATE from the HAL file LinuxCNC runs
  // in the INI's folder: --check with --ini reads that one, not CONFIG.state.
  const std::string ini = file("sim.ini", sim_ini_with("STATE = fixed_atc_state.json",
                                                       "STATE = the_machines_state.json"));
  const std::string state = file("the_machines_state.json", "{");
  const CliRun r = run({"--check", "--config", kConfig, "--ini", ini});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find(state), std::string::npos) << r.err;
  const CliRun given = run({"--check", "--config", kConfig, "--ini", ini, "--state", state + "x"});
  EXPECT_EQ(given.err.find(state + ":"), std::string::npos) << "--state wins: " << given.err;
}

TEST_F(CheckRun, shouldListFiftySkippedToolTableLinesAndCountTheRest) {
  // --lint caps its findings; --check read the same table line by line, 100,000 of them.
  std::string table = "T1 Z1\n";
  for (int i = 0; i < 100000; ++i) table += "T1 Z1\n";
  const std::string path = file("tool.tbl", table);
  const CliRun r =
      run({"--check", "--config", kConfig, "--tool-table", path, "--state", folder_ + "/none"});
  EXPECT_LT(std::count(r.out.begin(), r.out.end(), '\n'), 150) << r.out.substr(0, 2000);
  EXPECT_NE(r.out.find("  line 51: tool 1 again (first on line 1)\n  ... and 99950 more\n"),
            std::string::npos)
      << r.out.substr(0, 2000);
}

TEST_F(CheckRun, shouldListFiftyToolsOfNoLengthAndCountTheRestBeforeWhatFits) {
  std::string table;
  for (int tool = 1; tool <= 1000; ++tool) table += "T" + std::to_string(tool) + " P1 Z0\n";
  const std::string path = file("tool.tbl", table);
  const CliRun r =
      run({"--check", "--config", kConfig, "--tool-table", path, "--state", folder_ + "/none"});
  EXPECT_NE(r.out.find("  T50: LinuxCNC's tool table gives Z0.0000 mm"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("  T51: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  ... and 950 more\n  1000 tools of the table fit every pocket\n"),
            std::string::npos)
      << r.out;
}

/// --operator with `ini`: it needs no LinuxCNC to say what is wrong with the path.
CliRun operator_with_ini(const std::string& ini) {
  return run_program("--operator continue --ini '" + ini + "'");
}

TEST_F(CheckRun, shouldSayWhatIsWrongWithTheOperatorsIniPathItself) {
  const CliRun missing = operator_with_ini(folder_ + "/none.ini");
  EXPECT_EQ(missing.code, 2);
  EXPECT_EQ(missing.out,
            "fixed_atc_probe: " + folder_ + "/none.ini: cannot open (No such file or directory)\n");
  const CliRun folder = operator_with_ini(folder_);
  EXPECT_EQ(folder.code, 2);
  EXPECT_EQ(folder.out,
            "fixed_atc_probe: " + folder_ + ": expected a regular file, got a directory\n");
  const std::string empty = file("empty.ini", "");
  const CliRun nothing = operator_with_ini(empty);
  EXPECT_EQ(nothing.code, 2);
  EXPECT_EQ(nothing.out,
            "fixed_atc_probe: " + empty +
                " is empty, so it names no [FIXED_ATC_PROBE]STATE: give --state FILE\n");
  const std::string other = file("other.ini", "[EMC]\nMACHINE = mill\n");
  EXPECT_EQ(operator_with_ini(other).out,
            "fixed_atc_probe: " + other + " names no [FIXED_ATC_PROBE]STATE: give --state FILE\n");
  if (::geteuid() != 0) {  // root reads it all the same
    const std::string locked = file("locked.ini", "[FIXED_ATC_PROBE]\nSTATE = s.json\n");
    ::chmod(locked.c_str(), 0);
    const CliRun unreadable = operator_with_ini(locked);
    EXPECT_EQ(unreadable.code, 2);
    EXPECT_EQ(unreadable.out, "fixed_atc_probe: " + locked + ": cannot open (Permission denied)\n");
  }
}

TEST_F(CheckRun, shouldShowTheEscapeSequencesOfAnIniPathNotActOnThem) {
  const CliRun r = operator_with_ini(folder_ + "/\x1b[2J.ini");
  EXPECT_EQ(r.out, "fixed_atc_probe: " + folder_ +
                       "/\\x1b[2J.ini: cannot open (No such file or directory)\n");
}

TEST_F(CheckRun, shouldSayAStateFileOfThePlanIsNotThereRatherThanNameItAsTheRacks) {
  const std::string none = folder_ + "/none.state";
  const CliRun r =
      run({"--plan", "--config", kConfig, "--from", "1", "--to", "2", "--state", none});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')),
            "M6 T2 with T1 in the spindle, the rack as at first start: no state saved in " + none +
                " yet");
  const CliRun folder =
      run({"--plan", "--config", kConfig, "--from", "1", "--to", "2", "--state", folder_});
  EXPECT_EQ(folder.code, 1);
  EXPECT_EQ(folder.err, folder_ + ": expected a regular file, got a directory\n");
}

}  // namespace
}  // namespace fatc
