// --lint: a G-code program run through LinuxCNC's own interpreter (the
// installed rs274, standalone: no LinuxCNC runs), not the machine. Each
// feature and each hostile input asserts its exact line. The programs are in
// lint_programs/ (linuxcnc/: samples LinuxCNC installs); binary, FIFO and
// endless cases are made here at run time.
#include "cli/lint.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli.hpp"
#include "cli/parse_options.hpp"
#include "core/program/preflight.hpp"
#include "core/program/tool_table.hpp"
#include "io/files.hpp"
#include "linuxcnc/offline/interpreter.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const std::string kConfig = FATC_SOURCE_DIR "/config/config.json";
const std::string kPrograms = FATC_SOURCE_DIR "/tests/unit/lint_programs";
/// The sample machine: its M6 remap, subroutine folder and tool table.
const std::string kSimIni = FATC_SOURCE_DIR "/config/sim/fixed_atc_sim.ini";
const std::string kSimTable = FATC_SOURCE_DIR "/config/sim/sim.tbl";

struct LintRun {
  int code;
  std::string out;
  std::string err;
  double seconds;      ///< wall time
  double cpu_seconds;  ///< the lint's own work, whatever else the machine runs
  double all_cpu_seconds;  ///< with rs274's
};

/// CPU seconds of the processes this one waited for.
double children_cpu_seconds() {
  rusage usage;
  ::getrusage(RUSAGE_CHILDREN, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
         (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) / 1e6;
}

LintRun run(std::vector<std::string> args) {
  const auto start = Clock::now();
  const std::clock_t cpu_start = std::clock();
  const double children_start = children_cpu_seconds();
  std::string error;
  const auto options = io::parse_options(args, error);
  if (!options) return {2, "", error, 0.0, 0.0, 0.0};
  std::ostringstream out, err;
  const int code = io::run_tool_mode(*options, out, err);
  const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  return {code,      out.str(),
          err.str(), std::chrono::duration<double>(Clock::now() - start).count(),
          cpu,       cpu + children_cpu_seconds() - children_start};
}

/// Linear time, judged on the CPU the lint and rs274 took (the wall clock of
/// a shared machine says little); the wall clock only guards against a hang.
#define EXPECT_CPU_BELOW(run, limit)         \
  do {                                       \
    EXPECT_LT((run).all_cpu_seconds, limit); \
    EXPECT_LT((run).seconds, 60.0);          \
  } while (false)

/// Within a second of the lint's own time; the wall clock, shared with
/// whatever else the machine runs (ctest -j, builds), only guards against a hang.
#define EXPECT_WITHIN_A_SECOND(run)    \
  do {                                 \
    EXPECT_LT((run).cpu_seconds, 1.0); \
    EXPECT_LT((run).seconds, 5.0);     \
  } while (false)

/// A folder of its own for each test, removed after it.
class Lint : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("fatc_lint_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }
  /// A state file where the spindle is empty, every pocket full and every
  /// tool in `measured` has a length.
  std::string state_with_lengths(std::initializer_list<int> measured) const {
    Config config = *io::load_config_file(kConfig).config;
    ToolState tools = ToolState::fresh(config);
    for (const int tool : measured) tools.lengths[tool] = 20.0 + tool;
    io::save_state_file(path("tools.state"), tools, io::kCommandLineWait);
    return path("tools.state");
  }
  /// The sample config with one key changed.
  std::string config_with(const std::string& key, const nlohmann::json& value) const {
    nlohmann::json config = nlohmann::json::parse(std::ifstream(kConfig));
    config[key] = value;
    return write("config.json", config.dump());
  }
  /// The state path of a first start: no file there.
  std::string no_state() const { return path("none.state"); }

  LintRun lint(const std::string& program, std::vector<std::string> more = {}) const {
    std::vector<std::string> args = {"--lint", program, "--config", kConfig};
    if (std::find(more.begin(), more.end(), "--state") == more.end()) {
      more.insert(more.end(), {"--state", no_state()});
    }
    args.insert(args.end(), more.begin(), more.end());
    return run(args);
  }

  fs::path dir_;
};

bool has(const std::string& text, const std::string& line) {
  return text.find(line) != std::string::npos;
}

/// The output of a lint must hold `line`; on failure the whole output shows.
#define EXPECT_LINE(run, line) EXPECT_TRUE(has((run).out, line)) << (run).out << (run).err
#define EXPECT_NO_LINE(run, line) EXPECT_FALSE(has((run).out, line)) << (run).out

std::string program(const std::string& name) { return kPrograms + "/" + name; }

// ---- the tool changes and where the tools are ----

TEST_F(Lint, shouldListEveryChangeInTheOrderLinuxCncRunsThem) {
  const LintRun r = lint(program("changes.ngc"), {"--state", state_with_lengths({1, 2, 3, 4, 5})});
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_LINE(r, "tools in the order of the changes: T1 T3 T2 T4 T5 T0\n");
  EXPECT_LINE(r, "  1  4         M6 T1         pocket 1 ");
  EXPECT_LINE(r, "  2  5         M6 T3         pocket 3 ");
  EXPECT_LINE(r, "  3  6         M6 T2         pocket 2 ");
  // M6 alone on line 8: the change is shown on its T word's line.
  EXPECT_LINE(r, "  4  7         M6 T4         pocket 4 ");
  EXPECT_LINE(r,
              "  5  9         M61 Q4        LinuxCNC is told T4 is in the spindle; nothing moves");
  EXPECT_LINE(r, "  6  10        M6 T5         pocket 5 ");
  EXPECT_LINE(r, "  7  11        M6 T0         empties the spindle ");
  EXPECT_LINE(r, "changes.ngc: 6 tool changes (M6), 1 M61, 0 problems, 0 not known\n");
  EXPECT_NO_LINE(r, "T6");  // after the closing %
}

TEST_F(Lint, shouldSayWhatTheSpindleHoldsAtTheStart) {
  EXPECT_LINE(lint(program("manual.ngc")),
              "manual.ngc: at the start the spindle holds nothing (no state file yet at " +
                  no_state() + ": each pocket holds its first-start tool)\n");
  const LintRun r = lint(program("manual.ngc"), {"--state", kPrograms + "/measured.state"});
  EXPECT_LINE(r, "manual.ngc: at the start the spindle holds T2 (state file " + kPrograms +
                     "/measured.state)\n");
}

TEST_F(Lint, shouldReportAnM6WithoutAT) {
  const LintRun r = lint(program("no_t.ngc"), {"--state", state_with_lengths({2})});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r, "no_t.ngc: line 3: M6 without a T word since the start\n");
  EXPECT_LINE(r, "  1  3         M6            not known ");
  EXPECT_LINE(r, "tools in the order of the changes: T? T2\n");
  EXPECT_LINE(r, "no_t.ngc: 2 tool changes (M6), 0 M61, 1 problem, 0 not known\n");
}

TEST_F(Lint, shouldCallAToolWithoutPocketManual) {
  const LintRun r = lint(program("manual.ngc"), {"--state", state_with_lengths({1, 42})});
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_LINE(r, "  1  1         M6 T42        manual: handed over at loading ");
  EXPECT_LINE(r, "and the operator at 2 prompts not counted)");  // insert T42, remove it
}

TEST_F(Lint, shouldReportAChangeTheChangerRefuses) {
  const LintRun refused =
      run({"--lint", program("manual.ngc"), "--config", config_with("manual_tools", false),
           "--state", state_with_lengths({1, 42})});
  EXPECT_EQ(refused.code, 1);
  EXPECT_LINE(refused,
              "manual.ngc: line 1: M6 T42 refused: tool 42 is in no pocket of the "
              "rack (and manual_tools is off)\n");
  EXPECT_LINE(refused, "  1  1         M6 T42        refused: manual: handed over at loading ");
  // The changer would stop the program; the lint reads on with the spindle as it was.
  EXPECT_LINE(refused, "  2  2         M6 T1         pocket 1 ");
}

TEST_F(Lint, shouldFollowTheRackThroughTheStateFile) {
  // measured.state: T2 in the spindle, pocket 3 empty (tool 3 unloaded).
  const std::string text = "T1 M6\nT3 M6\nT2 M6\nM2\n";
  const LintRun r = lint(write("rack.ngc", text), {"--state", kPrograms + "/measured.state"});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r, "  1  1         M6 T1         pocket 1 ");
  EXPECT_LINE(r, "  2  2         M6 T3         out of the rack (pocket 3 empty) ");
  // T2 went home at the first change: it is in pocket 2 now.
  EXPECT_LINE(r, "  3  3         M6 T2         pocket 2 ");
  EXPECT_LINE(r, "rack.ngc: line 2: M6 T3: the state file " + kPrograms +
                     "/measured.state has pocket 3 empty (T3 is not in it): the changer "
                     "refuses the change; load it first\n");
}

TEST_F(Lint, shouldSayAChangeToTheToolInTheSpindleMovesNothing) {
  const LintRun r =
      lint(write("same.ngc", "T1 M6\nT1 M6\nM2\n"), {"--state", state_with_lengths({1})});
  EXPECT_EQ(r.code, 0);
  EXPECT_LINE(r, "  2  2         M6 T1         in the spindle already ");
  EXPECT_LINE(r, "for 1 change,");
}

TEST_F(Lint, shouldReportAnM61ThatDisagreesWithTheChanger) {
  const LintRun r =
      lint(write("m61.ngc", "T1 M6\nM61 Q3\nM2\n"), {"--state", state_with_lengths({1, 3})});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              "m61.ngc: line 2: M61 Q3: tells LinuxCNC the spindle holds T3 while the changer "
              "has T1 in it: the next G43 would apply the wrong length\n");
}

// ---- lengths ----

TEST_F(Lint, shouldReportAToolNeverMeasuredOncePerTool) {
  const LintRun r = lint(write("unmeasured.ngc", "T1 M6\nT2 M6\nT1 M6\nM2\n"),
                         {"--state", state_with_lengths({2})});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r, "unmeasured.ngc: line 1: T1 was never measured: no length in the state file " +
                     path("tools.state") +
                     ", and M6 measures nothing (probe_after_change is \"off\")\n");
  EXPECT_NO_LINE(r, "unmeasured.ngc: line 3: T1 was never measured");
  EXPECT_LINE(r,
              "  2  2         M6 T2         pocket 2                              not measured at "
              "M6                    22.0000 mm (state file)");
}

TEST_F(Lint, shouldReportAStateFileThatRecordsACutOffSequence) {
  ToolState tools = ToolState::fresh(*io::load_config_file(kConfig).config);
  tools.uncertain = true;
  tools.lengths = {{1, 21.0}, {2, 22.0}};
  io::save_state_file(path("cut_off.state"), tools, io::kCommandLineWait);
  const LintRun r =
      lint(write("after_fault.ngc", "T1 M6\nT2 M6\nM2\n"), {"--state", path("cut_off.state")});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r, "after_fault.ngc: line 1: the state file " + path("cut_off.state") +
                     " records a sequence that was cut off: the changer refuses M6 until the "
                     "fault is cleared (panel, or --confirm)\n");
  EXPECT_LINE(r, "after_fault.ngc: 2 tool changes (M6), 0 M61, 1 problem, 0 not known\n");
}

TEST_F(Lint, shouldNameTheChangeWhereTheRackDatumCheckFallsDue) {
  const std::string config = config_with(
      "rack_touch", {{"feature", "bore"}, {"stylus_radius", 1.0}, {"bore_diameter", 30.0},
                     {"top", {{"x", 25.0}, {"y", 0.0}}}, {"pocket_above_top", 20.0},
                     {"depth", 5.0}, {"datum", {{"pocket", 1}}}, {"check_every_changes", 3}});
  const auto loaded = io::load_config_file(config);
  ASSERT_TRUE(loaded.config) << loaded.errors.front();
  ToolState tools = ToolState::fresh(*loaded.config);
  tools.lengths = {{1, 21.0}, {2, 22.0}, {3, 23.0}};
  tools.datum.changes = 1;
  io::save_state_file(path("due.state"), tools, io::kCommandLineWait);
  const LintRun r = run({"--lint", write("due.ngc", "T1 M6\nT2 M6\nT3 M6\nT1 M6\nM2\n"),
                         "--config", config, "--state", path("due.state")});
  EXPECT_EQ(r.code, 1) << r.out << r.err;
  EXPECT_LINE(r, "due.ngc: line 3: M6 T3: the rack datum check falls due here, 3 changes after "
                 "the last (1 in the state file, rack_touch.check_every_changes 3): the changer "
                 "refuses it; run check-datum before the program\n");
  EXPECT_LINE(r, "1 problem");

  tools.datum.changes = 0;
  tools.datum.drift = "the rack datum is 0.62 mm off in X (tolerance 0.10): re-teach or check the rack";
  io::save_state_file(path("drift.state"), tools, io::kCommandLineWait);
  const LintRun moved = run({"--lint", write("moved.ngc", "T1 M6\nM2\n"), "--config", config,
                             "--state", path("drift.state")});
  EXPECT_LINE(moved, "moved.ngc: line 1: M6 T1: the state file " + path("drift.state") +
                         " says the rack datum is 0.62 mm off in X (tolerance 0.10): re-teach or "
                         "check the rack: the changer refuses M6 until teach-datum or "
                         "clear-datum-drift\n");
}

TEST_F(Lint, shouldAcceptAnUnmeasuredToolWhenTheChangeMeasuresIt) {
  const LintRun r = run({"--lint", write("measure.ngc", "T1 M6\nM2\n"), "--config",
                         config_with("probe_after_change", "measure"), "--state", no_state()});
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_LINE(r,
              "  1  1         M6 T1         pocket 1                              measured        "
              "                      measured at the change ");
}

TEST_F(Lint, shouldNameALineThatStartsTheSpindleWithAProbeInIt) {
  const nlohmann::json tools = {{"2", {{"kind", "probe"}, {"measure", "new"}}},
                                {"3", {{"measure", "check"}, {"check_tolerance", 0.05}}}};
  const LintRun r = run({"--lint", write("probe.ngc", "T2 M6\nS1000 M3\nM5\nT3 M6\nM4 S500\nM2\n"),
                         "--config", config_with("tools", tools), "--state",
                         state_with_lengths({2, 3})});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              "probe.ngc: line 2: the spindle turns here (M3 in force, S1000) with T2 in it, a "
              "probe (tools.2.kind): fatc-spindle-guard holds the spindle and the changer aborts "
              "the program here\n");
  EXPECT_NO_LINE(r, "probe.ngc: line 5:");
  EXPECT_LINE(r, "M6 T2         pocket 2                              probe, spindle held, measured "
                 "if new  22.0000 mm (state file)");
  EXPECT_LINE(r, "M6 T3         pocket 3                              checked ±0.05" +
                     std::string(25, ' ') + "checked at the change, stored 23.0000 mm (state file) ");
}

TEST_F(Lint, shouldNameOnlyTheFirstSpindleStartThatTurnsTheProbeAndAnOrient) {
  const nlohmann::json tools = {{"2", {{"kind", "probe"}}}};
  const LintRun r = run({"--lint", write("starts.ngc", "T2 M6\nS0 M3\nS900 M3\nM4\nM19 R90\nM2\n"),
                         "--config", config_with("tools", tools), "--state",
                         state_with_lengths({2})});
  EXPECT_EQ(r.code, 1);
  EXPECT_NO_LINE(r, "starts.ngc: line 2:");
  EXPECT_LINE(r, "starts.ngc: line 3: the spindle turns here (M3 in force, S900) with T2 in it, a probe");
  EXPECT_NO_LINE(r, "starts.ngc: line 4:");
  EXPECT_LINE(r, "starts.ngc: line 5: M19 orients the spindle with T2 in it, a probe");
}

TEST_F(Lint, shouldTakeANewToolAsMeasuredAfterItsFirstChange) {
  const LintRun r = run({"--lint", write("new.ngc", "T1 M6\nT2 M6\nT1 M6\nT1 M6\nM2\n"),
                         "--config", config_with("probe_after_change", "new"), "--state",
                         no_state()});
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_LINE(r, "  1  1         M6 T1         pocket 1");
  EXPECT_LINE(r, "measured if new                       measured at the change");
  EXPECT_LINE(r, "measured if new                       measured at an earlier change");
  EXPECT_NO_LINE(r, "never measured");
}

TEST_F(Lint, shouldReadTheLengthsFromTheToolTable) {
  const std::string table = kPrograms + "/tools.tbl";
  const LintRun r =
      lint(write("table.ngc", "T1 M6\nT2 M6\nT3 M6\nT4 M6\nM2\n"), {"--tool-table", table});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              "  1  1         M6 T1         pocket 1                              not measured at "
              "M6                    Z30.0000 (tool table)");
  EXPECT_LINE(r, "table.ngc: line 2: T2 was never measured: Z0 in the tool table " + table +
                     " (line 3), and M6 measures nothing (probe_after_change is \"off\")\n");
  EXPECT_LINE(r, "table.ngc: line 3: T3 was never measured: no Z in the tool table " + table +
                     " (line 4), and M6 measures nothing (probe_after_change is \"off\")\n");
  // LinuxCNC skips the line of tool 4: its interpreter refuses T4.
  EXPECT_LINE(r,
              "table.ngc: line 4: LinuxCNC stops the program here: Requested tool 4 not found "
              "in the tool table\n");
  EXPECT_LINE(r, table + ": line 5: LinuxCNC skips this line: \"Zabc\" is not a number after Z\n");
  EXPECT_LINE(r, table + ": line 6: tool 1 again (first on line 2)\n");
  EXPECT_LINE(r, "tools in the order of the changes: T1 T2 T3\n");
}

TEST(ToolTable, shouldReadTheFieldsAsLinuxCncDoes) {
  const ToolTable table =
      parse_tool_table("T1 P1 Z30.0 D6.0 ;end mill\n;comment\n\nt2 p2 z-1.5\nT3 K4\nT5\tZ9\n");
  ASSERT_EQ(table.tools.size(), 3u);
  EXPECT_DOUBLE_EQ(*table.tools.at(1).z, 30.0);
  EXPECT_DOUBLE_EQ(*table.tools.at(2).z, -1.5);
  // A tab is no separator to LinuxCNC: "T5\tZ9" reads as T5, and the Z is lost.
  EXPECT_FALSE(table.tools.at(5).z);
  ASSERT_EQ(table.problems.size(), 1u);
  EXPECT_EQ(table.problems[0].line, 5);
  EXPECT_EQ(table.problems[0].text,
            "LinuxCNC skips this line: \"K4\" is no tool table field (T P D X Y Z A B C U V W I "
            "J Q)");
}

// ---- what LinuxCNC's interpreter says of the program ----

TEST_F(Lint, shouldReportEveryLineLinuxCncRefuses) {
  const LintRun r = lint(program("bad_words.ngc"));
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              "bad_words.ngc: line 2: LinuxCNC stops the program here: Non integer value for "
              "integer\n");
  EXPECT_LINE(r,
              "bad_words.ngc: line 3: LinuxCNC stops the program here: Negative tool id (tool "
              "not found)\n");
  EXPECT_LINE(r,
              "bad_words.ngc: line 4: LinuxCNC stops the program here: Multiple t words on one "
              "line\n");
  EXPECT_LINE(r,
              "bad_words.ngc: line 5: LinuxCNC stops the program here: Need non-negative Q-word "
              "to specify tool number with M61\n");
  EXPECT_LINE(r, "bad_words.ngc: line 7: LinuxCNC stops the program here: Bad character '\\\\173' "
                 "used\n")
      << "the interpreter's words escaped as any file's text: its backslash doubled";
  EXPECT_LINE(r, "bad_words.ngc: 0 tool changes (M6), 0 M61, 6 problems, 0 not known\n");
}

TEST_F(Lint, shouldReportAnUnterminatedComment) {
  const LintRun r = lint(program("unterminated.ngc"));
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              "unterminated.ngc: line 3: LinuxCNC stops the program here: Unclosed comment "
              "found\n");
  EXPECT_LINE(r,
              "unterminated.ngc: line 5: LinuxCNC stops the program here: Nested comment found\n");
  EXPECT_LINE(r, "tools in the order of the changes: T1 T2\n");
}

TEST_F(Lint, shouldFollowSubroutinesDefinedBeforeTheCallAndInTheSubroutinePath) {
  const LintRun r = lint(program("calls.ngc"), {"--subroutine-path", "/nonexistent:" + kPrograms});
  EXPECT_LINE(r, "tools in the order of the changes: T1 T2 T3\n");
  EXPECT_LINE(r, "  2  3         M6 T2         pocket 2 ");
  // In a subroutine file: no line of the program.
  EXPECT_LINE(r, "  3  -         M6 T3         pocket 3 ");
  // On the call's line, as LinuxCNC says it (rs274 alone says it on the last line).
  EXPECT_LINE(r, "calls.ngc: line 8: LinuxCNC stops the program here: EOF in file:" +
                     program("calls.ngc") + " seeking o-word: o<missingsub> from line: 8\n");
}

TEST_F(Lint, shouldFindNoSubroutineBesideTheProgramAsLinuxCnc) {
  const LintRun r = lint(program("calls.ngc"));
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r, "tools in the order of the changes: T1 T2\n");
  EXPECT_LINE(r, "seeking o-word: o<sub_change> from line: 7\n");
}

TEST_F(Lint, shouldRunLoopsAndTakeOnlyTheBranchTheProgramTakes) {
  // while: 3 times; if/else: the if; do-while: no change; repeat 2: a subroutine's.
  const LintRun r = lint(program("flow.ngc"),
                         {"--subroutine-path", kPrograms, "--state", state_with_lengths({1, 2, 3})});
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_LINE(r, "tools in the order of the changes: T1 T1 T1 T2 T3 T3\n");
  EXPECT_LINE(r, "  2  4         M6 T1         in the spindle already ");
  EXPECT_NO_LINE(r, "  10        M6 T3");  // the else branch
}

TEST_F(Lint, shouldFollowARecursiveSubroutineAsItRuns) {
  const LintRun r = lint(program("recursive.ngc"), {"--state", state_with_lengths({1})});
  EXPECT_LINE(r, "tools in the order of the changes: T1 T1 T1 T1\n");
  EXPECT_LINE(r, "recursive.ngc: 4 tool changes (M6), 0 M61, 0 problems, 0 not known\n");
}

TEST_F(Lint, shouldComputeToolNumbersFromParametersAndExpressions) {
  const LintRun r = lint(program("computed.ngc"), {"--state", state_with_lengths({2, 3, 4})});
  EXPECT_EQ(r.code, 1) << r.out;  // M61 Q3 while the changer holds T4
  EXPECT_LINE(r, "tools in the order of the changes: T3 T4 T2\n");
  EXPECT_LINE(r, "  3  4         M61 Q3 ");
  // A parameter set two lines before the T word.
  const LintRun later = lint(write("later.ngc", "#<t> = 3\nG0 X1\nT#<t> M6\nM2\n"));
  EXPECT_LINE(later, "tools in the order of the changes: T3\n");
  EXPECT_LINE(later, "  1  3         M6 T3 ");
}

TEST_F(Lint, shouldListTZeroAndRepeatsInTheOrderOfTheChanges) {
  const LintRun r = lint(write("zero.ngc", "T1 M6\nT3 M6\nT1 M6\nM61 Q3\nT0 M6\nM2\n"),
                         {"--state", state_with_lengths({1, 3})});
  EXPECT_LINE(r, "tools in the order of the changes: T1 T3 T1 T0\n");
  EXPECT_LINE(r, "  4  4         M61 Q3 ");
}

TEST_F(Lint, shouldRunTheMachinesRemapsAndUserCodes) {
  const LintRun r = lint(program("codes.ngc"), {"--state", state_with_lengths({1, 2}), "--ini",
                                                kPrograms + "/remap.ini"});
  EXPECT_EQ(r.code, 1) << r.out;
  // REMAP = M400 ... ngc=m400: m400.ngc in the INI's subroutine folder changes to T2.
  EXPECT_LINE(r, "tools in the order of the changes: T1 T2\n");
  EXPECT_LINE(r, "codes.ngc: line 2: LinuxCNC stops the program here: Unknown m code used: M101\n");
  EXPECT_LINE(r, "codes.ngc: line 4: LinuxCNC stops the program here: Unknown g code used\n");
  // No [AXIS_*] limits in it: the estimate's are assumed, and it says why.
  EXPECT_LINE(r, "the moves at 3000 mm/min and 500 mm/s², assumed (" + kPrograms +
                     "/remap.ini has no usable MAX_VELOCITY and MAX_ACCELERATION of [AXIS_X], "
                     "[AXIS_Y] and [AXIS_Z]: --plan --ini says why)");
}

TEST_F(Lint, shouldReportAnIniWithoutTheM6Remap) {
  const LintRun r = lint(program("manual.ngc"), {"--state", state_with_lengths({1, 42}), "--ini",
                                                 kPrograms + "/no_m6_remap.ini"});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              "manual.ngc: line 1: the INI remaps no M6: LinuxCNC's own M6 would run here, "
              "not fixed_atc_probe_m6\n");
  EXPECT_LINE(r, "/no_m6_remap.ini has no usable MAX_VELOCITY and MAX_ACCELERATION of ");
}

// ---- with the sample machine's INI: the M6 remap, HAL pins, its tool table ----

TEST_F(Lint, shouldReadLinuxCncsSampleWithCutterCompensation) {
  // sim.tbl's diameters are mm: as inches (rs274 reads them so) the entry
  // moves of the cutter compensation would be refused.
  const LintRun r = lint(program("linuxcnc/gmoccapy_2_tools_with_cutter_radius_compensation.ngc"),
                         {"--ini", kSimIni, "--tool-table", kSimTable});
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_LINE(r, "tools in the order of the changes: T3 T1\n");
  EXPECT_LINE(r, "  1  17        M6 T3         pocket 3 ");
  EXPECT_LINE(r, "  2  53        M6 T1         pocket 1 ");
  EXPECT_NO_LINE(r, "cutter compensation entry");
}

TEST_F(Lint, shouldReadLinuxCncsSkeletonProgram) {
  const LintRun r =
      lint(program("linuxcnc/skeleton.ngc"), {"--ini", kSimIni, "--tool-table", kSimTable});
  EXPECT_LINE(r, "tools in the order of the changes: T1 T0\n");
  EXPECT_LINE(r, "  1  10        M6 T1         pocket 1 ");
  EXPECT_LINE(r, "  2  18        M6 T0         empties the spindle ");
}

TEST_F(Lint, shouldSayAToolFromAHalPinIsNotKnown) {
  const LintRun r =
      lint(write("operator.ngc", "T1 M6\nT[#<_hal[fixed_atc_probe.number]>] M6\nT2 M6\nM2\n"),
           {"--ini", kSimIni, "--tool-table", kSimTable, "--state", state_with_lengths({1, 2})});
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_LINE(r, "tools in the order of the changes: T1 T? T2\n");
  EXPECT_LINE(r, "  2  2         M6            not known ");
  EXPECT_LINE(r,
              "operator.ngc: line 2: Named parameter #<_hal[fixed_atc_probe.number]> not "
              "defined: a HAL pin, read only when the program runs on the machine: what the line "
              "does is not known\n");
  EXPECT_LINE(r, "operator.ngc: 3 tool changes (M6), 0 M61, 0 problems, 1 not known\n");
}

TEST_F(Lint, shouldSayAToolFromAnM66InputIsNotKnown) {
  const LintRun r = lint(write("input.ngc", "M66 P0 L0\nT#5399 M6\nM2\n"));
  EXPECT_LINE(r, "tools in the order of the changes: T?\n");
  EXPECT_LINE(r,
              "input.ngc: line 2: the tool number reads #5399, the input M66 waited for: known "
              "only when the program runs on the machine (rs274 reads 0)\n");
}

// ---- the estimate (its model: tests/unit/dry_run/timing_test.cpp) ----

TEST_F(Lint, shouldEstimateTheChangeTimeFromThePlannedSteps) {
  const LintRun r =
      lint(write("two.ngc", "T1 M6\nT2 M6\nM2\n"), {"--state", state_with_lengths({1, 2})});
  EXPECT_LINE(r, "\nestimated tool-change time: ");
  EXPECT_LINE(r,
              " for 2 changes, from safe to safe (the way between the work and safe not "
              "counted)\n  from the steps --plan prints for each: the moves at 3000 mm/min "
              "and 500 mm/s², assumed (--ini gives the machine's [AXIS_*] and [TRAJ] limits), "
              "each an exact stop (G61.1) at the axes' full acceleration as LinuxCNC plans it, "
              "plus the dwells, 17 ms a step (the executor's handshake) and 0.53 s a change (4.5 of "
              "iocontrol's 0.1 s cycles for T and M6, 75 ms for the remap)\n");
}

// ---- usage and unreadable input: exit 2 ----

TEST_F(Lint, shouldExitTwoOnUsageMistakes) {
  EXPECT_EQ(run({"--lint"}).err, "--lint needs a value");
  EXPECT_EQ(run({"--lint", "a.ngc"}).err, "--config FILE is required");
  EXPECT_EQ(run({"--lint", "a.ngc", "--config", kConfig, "--from", "1"}).err,
            "--from is not used by --lint");
  EXPECT_EQ(run({"--dot", "--tool-table", "t"}).err, "--tool-table is not used by --dot");
  EXPECT_EQ(run({"--lint", "a.ngc", "--lint", "b.ngc"}).err, "--lint given twice");
  EXPECT_EQ(run({"--lint", "", "--config", kConfig}).err,
            "--lint: expected a file path, got nothing");
}

TEST_F(Lint, shouldExitTwoWhenAnInputCannotBeRead) {
  const LintRun missing = lint(path("missing.ngc"));
  EXPECT_EQ(missing.code, 2);
  EXPECT_EQ(missing.err, path("missing.ngc") + ": cannot open (No such file or directory)\n");
  EXPECT_EQ(missing.out, "");
  const LintRun table = lint(program("manual.ngc"), {"--tool-table", path("none.tbl")});
  EXPECT_EQ(table.code, 2);
  EXPECT_EQ(table.err, path("none.tbl") + ": cannot open (No such file or directory)\n");
  const LintRun config = run({"--lint", program("manual.ngc"), "--config", path("none.json")});
  EXPECT_EQ(config.code, 2);
}

// ---- hostile programs: one clear line, non-zero, within a second ----

TEST_F(Lint, shouldRefuseADirectoryOrAFifoAtOnce) {
  const LintRun folder = lint(dir_.string());
  EXPECT_EQ(folder.code, 2);
  EXPECT_EQ(folder.err, dir_.string() + ": expected a regular file, got a directory\n");
  ASSERT_EQ(::mkfifo(path("fifo.ngc").c_str(), 0600), 0);
  const LintRun fifo = lint(path("fifo.ngc"));
  EXPECT_EQ(fifo.code, 2);
  EXPECT_EQ(fifo.err, path("fifo.ngc") + ": expected a regular file, got a FIFO\n");
  EXPECT_WITHIN_A_SECOND(fifo);
}

TEST_F(Lint, shouldRefuseABinaryFileInOneLine) {
  std::string binary =
      "\x7f"
      "ELF\x02\x01\x01";
  binary += std::string("\0\0\0\x03\n\x89PNG", 10);
  for (int i = 0; i < 100000; ++i) binary.push_back(static_cast<char>(i * 7919 % 256));
  const LintRun r = lint(write("binary.ngc", binary));
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r, "\nproblems:\n  " + path("binary.ngc") +
                     ": line 1: NUL byte at column 8: not a G-code text "
                     "file (LinuxCNC stops reading a line at a NUL); nothing of it read\n\n");
  EXPECT_WITHIN_A_SECOND(r);
}

TEST_F(Lint, shouldRefuseAFileWithANulByte) {
  const LintRun r = lint(write("nul.ngc", std::string("T1 M6\nG0 X1\nG0\0 X2\nM2\n", 22)));
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              "nul.ngc: line 3: NUL byte at column 3: not a G-code text file (LinuxCNC "
              "stops reading a line at a NUL); nothing of it read\n");
}

// ---- the interpreter's bounds ----

/// run_interpreter on `program` with the bounds given.
std::optional<program::InterpreterRun> interpret(const std::string& program, double seconds,
                                                 std::size_t max_output, std::string& error) {
  io::InterpreterInput input;
  input.rs274 = *io::find_rs274(error);
  input.program_path = program;
  input.seconds = seconds;
  input.max_output_bytes = max_output;
  return io::run_interpreter(input, error);
}

TEST_F(Lint, shouldStopAnInterpreterThatRunsWithoutEnd) {
  const std::string endless = write("endless.ngc", "T1 M6\no100 while [1]\n  G0 X1\n  G0 X2\no100 endwhile\nM2\n");
  std::string error;
  const auto start = Clock::now();
  const auto run = interpret(endless, 1.0, io::kMaxInterpreterOutput, error);
  ASSERT_TRUE(run) << error;
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 3.0);
  ASSERT_EQ(run->uses.size(), 1u);
  ASSERT_EQ(run->problems.size(), 1u);
  // Where it was, from the calls it printed: in the loop.
  EXPECT_TRUE(run->problems[0].text ==
                  "LinuxCNC's interpreter (rs274) still ran after 1 s, at line 3 of 6 (a loop "
                  "without end, or a program longer than it reads in that time): stopped; tool "
                  "changes after that are not known" ||
              run->problems[0].text ==
                  "LinuxCNC's interpreter (rs274) still ran after 1 s, at line 4 of 6 (a loop "
                  "without end, or a program longer than it reads in that time): stopped; tool "
                  "changes after that are not known")
      << run->problems[0].text;
}

TEST_F(Lint, shouldStopReadingAnInterpreterThatPrintsTooMuch) {
  const std::string endless = write("endless.ngc", "o100 while [1]\n  G0 X1\n  G0 X2\no100 endwhile\nM2\n");
  std::string error;
  const auto run = interpret(endless, 10.0, 100000, error);
  ASSERT_TRUE(run) << error;
  ASSERT_EQ(run->problems.size(), 1u);
  EXPECT_EQ(run->problems[0].text,
            "LinuxCNC's interpreter (rs274) printed over 100000 bytes: stopped; tool changes "
            "after that are not known");
}

TEST_F(Lint, shouldGiveTheInterpreterOnlyTheStartOfAHugeProgram) {
  std::string text = "T1 M6\n";
  while (text.size() < 100000) text += "G1 X1.000 Y2.000 F100\n";
  const std::string huge = write("huge.ngc", text + "T2 M6\nM2\n");
  io::InterpreterInput input;
  std::string error;
  input.rs274 = *io::find_rs274(error);
  input.program_path = huge;
  input.max_program_bytes = 50000;
  const auto run = io::run_interpreter(input, error);
  ASSERT_TRUE(run) << error;
  ASSERT_EQ(run->uses.size(), 1u);
  ASSERT_FALSE(run->problems.empty());
  EXPECT_EQ(run->problems[0].text.rfind("only the first 49990 of its " +
                                            std::to_string(fs::file_size(huge)) +
                                            " bytes read (the lint reads at most 50000 bytes of "
                                            "G-code): tool changes after line 2273 are not known",
                                        0),
            0u)
      << run->problems[0].text;
}

TEST_F(Lint, shouldSayInOneLineThatRs274IsMissing) {
  ::setenv("FATC_RS274", "/nonexistent/rs274", 1);
  const LintRun r = lint(program("manual.ngc"));
  ::unsetenv("FATC_RS274");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "/nonexistent/rs274 ($FATC_RS274): no such program: LinuxCNC's interpreter rs274 is "
            "needed to read the program\n");
  EXPECT_EQ(r.out, "");
}

TEST_F(Lint, shouldLeaveTheToolDataOfARunningLinuxCncAloneWhenTheInterpreterRuns) {
  // rs274 makes LinuxCNC's tool data anew in $HOME/.tool.mmap, where a
  // running LinuxCNC of the same user keeps its own.
  const std::string home = path("home");
  fs::create_directories(home);
  const char* was = std::getenv("HOME");
  const std::string saved = was ? was : "";
  ::setenv("HOME", home.c_str(), 1);
  const LintRun r = lint(program("changes.ngc"));
  ::setenv("HOME", saved.c_str(), 1);
  EXPECT_NE(r.out.find("tools in the order of the changes:"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(home + "/.tool.mmap"));
}

TEST_F(Lint, shouldReadAProgramWhoseNameHasSpacesAndQuotes) {
  const std::string name = write("it's a \"test\" $(x).ngc", "T2 M6\nM2\n");
  const LintRun r = lint(name);
  EXPECT_EQ(r.code, 1) << r.out << r.err;  // T2 never measured
  EXPECT_LINE(r, "tools in the order of the changes: T2\n");
}

TEST_F(Lint, shouldRefuseAVeryLongLine) {
  const LintRun r =
      lint(write("long.ngc", "T1 M6\nG0 X" + std::string(100'000, '1') + "\nT2 M6\nM2\n"));
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r, "long.ngc: line 2: LinuxCNC stops the program here: Command too long\n");
  EXPECT_LINE(r, "tools in the order of the changes: T1 T2\n");
  EXPECT_WITHIN_A_SECOND(r);
}

TEST_F(Lint, shouldNeverNameAnotherLineForALineNumberedByTheProgram) {
  // N words the size of the lint's own, naming line 3: on a line too long for
  // LinuxCNC, and on line 4 that fits only without the lint's number (a
  // comment fills it to LinuxCNC's longest, 252).
  const std::string fits = "N1000000003G1 X1 (" + std::string(252 - 19, 'a') + ")";
  ASSERT_EQ(fits.size(), 252u);
  const LintRun r = lint(write("numbered.ngc", "T1 M6\nN1000000003 G0 X" +
                                                   std::string(300, '1') + "\nT2 M6\n" + fits +
                                                   "\nM2\n"));
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r, "numbered.ngc: line 2: LinuxCNC stops the program here: Command too long\n");
  EXPECT_LINE(r, "numbered.ngc: LinuxCNC stops the program here: Cannot do g1 with zero feed "
                 "rate (at \"G1 X1 (aaa");
  EXPECT_EQ(r.out.find("line 3: LinuxCNC"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("line 4: LinuxCNC"), std::string::npos) << r.out;
  EXPECT_WITHIN_A_SECOND(r);
}

TEST_F(Lint, shouldKeepAThousandErrorsAndStopAtTheNext) {
  std::string text;
  for (int i = 0; i < 3000; ++i) text += "G0 X1 {\n";
  const LintRun r = lint(write("garbage.ngc", text + "T1 M6\nM2\n"));
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              "garbage.ngc: more than 1000 errors: LinuxCNC's interpreter (rs274) was stopped at "
              "line 1001; tool changes after that are not known\n");
  EXPECT_LINE(r, "garbage.ngc: 0 tool changes (M6), 0 M61, 1001 problems, 0 not known\n");
  EXPECT_WITHIN_A_SECOND(r);
}

TEST_F(Lint, shouldStopAtTheEndOfAProgramWithoutM2) {
  // rs274 -n 0 would repeat the error for ever.
  const LintRun r = lint(write("no_end.ngc", "T1 M6\nG0 X1\n"));
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              "no_end.ngc: line 2: LinuxCNC stops the program here: File ended with no percent "
              "sign or program end\n");
  // Not known: no tool table gives T1's length for the rack keep-out.
  EXPECT_LINE(r, "no_end.ngc: 1 tool change (M6), 0 M61, 2 problems, 1 not known\n");
  EXPECT_WITHIN_A_SECOND(r);
}

TEST_F(Lint, shouldStopCallsNestedDeeperThanLinuxCncAllows) {
  for (int level = 0; level < 12; ++level) {
    const std::string name = "level" + std::to_string(level);
    write(name + ".ngc", "o<" + name + "> sub\nT" + std::to_string(level + 1) + " M6\no<level" +
                             std::to_string(level + 1) + "> call\no<" + name + "> endsub\nM2\n");
  }
  const LintRun r = lint(write("deep.ngc", "o<level0> call\nM2\n"), {"--subroutine-path", dir_.string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r, "tools in the order of the changes: T1 T2 T3 T4 T5 T6 T7 T8 T9\n");
  EXPECT_LINE(r, "LinuxCNC stops the program here: ");
}

TEST_F(Lint, shouldStopCountingAfterTenThousandChanges) {
  std::string text;
  for (int i = 0; i < 6000; ++i) text += "T1 M6\nT2 M6\n";
  const LintRun r = lint(write("many.ngc", text + "M2\n"), {"--state", state_with_lengths({1, 2})});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_LINE(r,
              "many.ngc: more than 10000 tool changes and M61: the other 2000 are not counted\n");
  EXPECT_LINE(r, "  ... and 9800 more\n");
  EXPECT_LINE(r, "many.ngc: 10000 tool changes (M6), 0 M61, 0 problems, 1 not known\n");
}

// ---- hostile programs, second round: bounded, and refused as LinuxCNC refuses ----

/// Resident memory now and its peak since reset_peak(), in KiB (/proc/self/status).
long status_kib(const char* key) {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind(key, 0) == 0) return std::stol(line.substr(std::strlen(key)));
  }
  return -1;
}
/// Starts the peak (VmHWM) anew from what is resident now.
void reset_peak() { std::ofstream("/proc/self/clear_refs") << "5"; }

/// `lines` lines of `line` after `head`, then `end`, written in pieces.
std::string big_program(const std::string& path, const std::string& head, const std::string& line,
                        std::size_t lines, const std::string& end) {
  std::ofstream out(path, std::ios::binary);
  out << head;
  std::string block;
  for (int i = 0; i < 4096; ++i) block += line;
  for (std::size_t i = 0; i < lines / 4096; ++i) out << block;
  for (std::size_t i = 0; i < lines % 4096; ++i) out << line;
  out << end;
  return path;
}

TEST_F(Lint, shouldNumberA64MiBProgramInSmallMemory) {
  // 64 MiB of moves: neither the program nor its numbered copy is ever whole
  // in memory (it took 4 bytes for each byte read), nor rs274's output (read
  // as it comes). rs274 itself is stopped after half a second.
  const std::string huge = big_program(path("huge.ngc"), "T1 M6\n", "G1 X1.000 Y2.000 F100\n",
                                       (64u << 20) / 22 - 1, "T2 M6\nM2\n");
  ASSERT_LE(fs::file_size(huge), io::kMaxProgramBytes);
  reset_peak();
  const long before = status_kib("VmRSS:");
  std::string error;
  const auto run = interpret(huge, 0.5, io::kMaxInterpreterOutput, error);
  const long grown = status_kib("VmHWM:") - before;
  ASSERT_TRUE(run) << error;
  EXPECT_LT(grown, 16 * 1024) << "KiB more resident while reading 64 MiB";
  ASSERT_EQ(run->problems.size(), 1u);
  EXPECT_EQ(run->problems[0].text.rfind(
                "LinuxCNC's interpreter (rs274) still ran after 0.5 s, at line ", 0),
            0u)
      << run->problems[0].text;
  EXPECT_NE(run->problems[0].text.find(" of 3050404 (a loop without end, or a program longer than "
                                       "it reads in that time): stopped; tool changes after that "
                                       "are not known"),
            std::string::npos)
      << run->problems[0].text;
}

TEST_F(Lint, shouldSayInOneLineThatAProgramIsBeyondTheLimit) {
  const std::string huge = big_program(path("huge.ngc"), "T1 M6\n", "G1 X1.000 Y2.000 F100\n",
                                       (64u << 20) / 22 + 10, "T2 M6\nM2\n");
  std::string error;
  io::InterpreterInput input;
  input.rs274 = *io::find_rs274(error);
  input.program_path = huge;
  input.seconds = 0.5;
  const auto run = io::run_interpreter(input, error);
  ASSERT_TRUE(run) << error;
  ASSERT_FALSE(run->problems.empty());
  EXPECT_EQ(run->problems[0].text,
            "only the first 67108850 of its " + std::to_string(fs::file_size(huge)) +
                " bytes read (the lint reads at most 64 MiB of G-code): tool changes after line "
                "3050403 are not known");
}

TEST_F(Lint, shouldNumberLinesAcrossThePiecesTheFileIsReadIn) {
  // Lines of the program cut at every 64 KiB piece: each change on its own line.
  std::string text;
  int line = 0;
  while (text.size() < 300000) {
    text += (++line % 1000 == 0 ? "T" + std::to_string(line / 1000 % 6 + 1) + " M6\n"
                                : "G0 X1 (move " + std::to_string(line) + ")\n");
  }
  const LintRun r =
      lint(write("pieces.ngc", text + "M2\n"), {"--state", state_with_lengths({1, 2, 3, 4, 5, 6})});
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_LINE(r, "  1  1000      M6 T2 ");
  EXPECT_LINE(r, "  9  9000      M6 T4 ");
  EXPECT_LINE(r, " 16  16000     M6 T5 ");
}

TEST_F(Lint, shouldReadAnUnclosedWhileOfAHundredThousandLinesInLinearTime) {
  // LinuxCNC runs the loop's body once and ends at M2: nothing refused.
  const std::string program =
      big_program(path("while.ngc"), "T1 M6\no100 while [1]\n", "G0 X1\n", 100000, "M2\n");
  const LintRun r = lint(program, {"--state", state_with_lengths({1})});
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_LINE(r, "while.ngc: 1 tool change (M6), 0 M61, 0 problems, 1 not known\n");
  EXPECT_LINE(r, "while.ngc: line 3: no tool table (--tool-table, or the INI's "
                 "[EMCIO]TOOL_TABLE): the moves are checked against the rack with no tool "
                 "length\n");
  EXPECT_CPU_BELOW(r, 5.0);
}

TEST_F(Lint, shouldFindManyUndefinedSubroutinesInManyFoldersInLinearTime) {
  // rs274 alone reads the rest of the program for each undefined call: 20,000
  // calls took over 15 s. Each finds an empty file after the machine's folders.
  std::string folders;
  for (int i = 0; i < 9; ++i) {
    fs::create_directories(path("subs" + std::to_string(i)));
    folders += (i ? ":" : "") + path("subs" + std::to_string(i));
  }
  std::string text;
  for (int i = 0; i < 20000; ++i) text += "o<nosuch" + std::to_string(i) + "> call\n";
  const std::string program = write("undefined.ngc", text + "T1 M6\nM2\n");
  const LintRun r = lint(program, {"--subroutine-path", folders});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r, "undefined.ngc: line 1: LinuxCNC stops the program here: EOF in file:" + program +
                     " seeking o-word: o<nosuch0> from line: 1\n");
  EXPECT_LINE(r, "undefined.ngc: line 49: LinuxCNC stops the program here: EOF in file:" + program +
                     " seeking o-word: o<nosuch48> from line: 49\n");
  EXPECT_LINE(r,
              "undefined.ngc: more than 1000 errors: LinuxCNC's interpreter (rs274) was stopped "
              "at line 1001; tool changes after that are not known\n");
  EXPECT_CPU_BELOW(r, 5.0);
}

TEST_F(Lint, shouldRefuseASubroutineFolderLongerThanLinuxCncReads) {
  const std::string folder = "/" + std::string(260, 'd');
  const LintRun r = lint(program("calls.ngc"), {"--subroutine-path", folder});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "--subroutine-path: " + folder.substr(0, 200) +
                       "\u2026: over the 250 characters LinuxCNC reads of a folder in its INI\n");
}

TEST_F(Lint, shouldFindASubroutineOfTheFoldersBeforeAnyEmptyFile) {
  // A name the program does not define may be a file of the subroutine path: found there.
  write("subs/found_there.ngc", "");
  fs::create_directories(path("subs"));
  std::ofstream(path("subs/found_there.ngc"))
      << "o<found_there> sub\nT3 M6\no<found_there> endsub\nM2\n";
  const LintRun r = lint(write("found.ngc", "o<found_there> call\no<not_there> call\nM2\n"),
                         {"--subroutine-path", path("subs"), "--state", state_with_lengths({3})});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r, "tools in the order of the changes: T3\n");
  EXPECT_LINE(r, "found.ngc: line 2: LinuxCNC stops the program here: EOF in file:" +
                     path("found.ngc") + " seeking o-word: o<not_there> from line: 2\n");
}

TEST_F(Lint, shouldLintTenThousandChangesOnATwoHundredPocketRackInLinearTime) {
  nlohmann::json config = nlohmann::json::parse(std::ifstream(kConfig));
  config["pockets"] = nlohmann::json::object();
  for (int i = 0; i < 200; ++i) {
    config["pockets"][std::to_string(i + 1)] = {{"x", 10.0 + (i % 20) * 45.0},
                                                {"y", 20.0 + (i / 20) * 100.0}};
  }
  config["safe"] = {{"x", 450.0}, {"y", 1050.0}, {"z", -5.0}};
  // Ten rows 100 apart: more parts than the realtime guard's four boxes.
  config["rack_keepout_all_motion"] = false;
  config["loading"] = {{"x", 20.0}, {"y", 1100.0}, {"z", -10.0}};
  config["probe_limit"] = {{"x", 20.0}, {"y", 1100.0}, {"z", -90.0}};
  const std::string rack = write("rack200.json", config.dump());
  std::string text;
  unsigned seed = 1;
  for (int i = 0; i < 10000; ++i) {
    seed = seed * 1103515245u + 12345u;
    text += "T" + std::to_string(seed / 65536 % 200 + 1) + " M6\n";
  }
  const LintRun r =
      run({"--lint", write("changes.ngc", text + "M2\n"), "--config", rack, "--state", no_state()});
  EXPECT_EQ(r.code, 1) << r.err;  // never measured
  EXPECT_LINE(r, "changes.ngc: 10000 tool changes (M6), 0 M61, 200 problems, 0 not known\n");
  EXPECT_CPU_BELOW(r, 10.0);
}

TEST_F(Lint, shouldRefuseASubroutineDefinedTwice) {
  const std::string program =
      write("twice.ngc",
            "o<twice> sub\nG0 X1\no<twice> endsub\no<twice> sub\nG0 X2\no<twice> endsub\nM2\n");
  const LintRun r = lint(program);
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r, "twice.ngc: line 4: LinuxCNC stops the program here: File:" + program +
                     " line:4 redefining sub: o|twice| already defined in file:" + program + "\n");
}

TEST_F(Lint, shouldRefuseAnM61QBeyondTheToolRange) {
  // 20 digits: LinuxCNC's own verdict, never a tool of a wrapped number.
  const LintRun r =
      lint(write("m61.ngc", "M61 Q12345678901234567890\nM61 Q2147483648\nM61 Q5000\nM2\n"));
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              "m61.ngc: line 1: LinuxCNC stops the program here: Need non-negative Q-word to "
              "specify tool number with M61\n");
  EXPECT_LINE(r,
              "m61.ngc: line 2: LinuxCNC stops the program here: Need non-negative Q-word to "
              "specify tool number with M61\n");
  EXPECT_LINE(r,
              "m61.ngc: line 3: LinuxCNC stops the program here: Requested tool 5000 not found "
              "in the tool table\n");
  EXPECT_LINE(r, "m61.ngc: 0 tool changes (M6), 0 M61, 3 problems, 0 not known\n");
}

TEST_F(Lint, shouldRefuseATBeyondTheToolRange) {
  const LintRun r =
      lint(write("t.ngc", "T12345678901234567890 M6\nT2147483648 M6\nT1001 M6\nM2\n"));
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              "t.ngc: line 1: LinuxCNC stops the program here: Negative tool id (tool not "
              "found)\n");
  EXPECT_LINE(r,
              "t.ngc: line 2: LinuxCNC stops the program here: Negative tool id (tool not "
              "found)\n");
  EXPECT_LINE(r,
              "t.ngc: line 3: LinuxCNC stops the program here: Requested tool 1001 not found in "
              "the tool table\n");
  EXPECT_LINE(r, "t.ngc: 0 tool changes (M6), 0 M61, 3 problems, 0 not known\n");
}

/// A tool table line and the problem it must give.
struct BadTableLine {
  const char* line;
  const char* expected;
};

TEST(ToolTable, shouldLeaveOutEveryLineWhoseNumbersMeanNothing) {
  // clang-format off
  const BadTableLine kLines[] = {
    {"T2 P2 Znan", "\"Znan\" is no number a tool can have (NaN, infinite, or over 100000 either way), which LinuxCNC would read as it is; the line is left out of the table here"},
    {"T2 P2 ZNAN(0x7)", "\"ZNAN(0x7)\" is no number a tool can have (NaN, infinite, or over 100000 either way), which LinuxCNC would read as it is; the line is left out of the table here"},
    {"T2 P2 Zinf", "\"Zinf\" is no number a tool can have (NaN, infinite, or over 100000 either way), which LinuxCNC would read as it is; the line is left out of the table here"},
    {"T2 P2 Z-Infinity", "\"Z-Infinity\" is no number a tool can have (NaN, infinite, or over 100000 either way), which LinuxCNC would read as it is; the line is left out of the table here"},
    {"T2 P2 Z1e400", "\"Z1e400\" is no number a tool can have (NaN, infinite, or over 100000 either way), which LinuxCNC would read as it is; the line is left out of the table here"},
    {"T2 P2 D1e300", "\"D1e300\" is no number a tool can have (NaN, infinite, or over 100000 either way), which LinuxCNC would read as it is; the line is left out of the table here"},
    {"T2 P2 X-100000.5", "\"X-100000.5\" is no number a tool can have (NaN, infinite, or over 100000 either way), which LinuxCNC would read as it is; the line is left out of the table here"},
    {"T99999999999 P2", "\"T99999999999\" is beyond the largest whole number LinuxCNC reads (2147483647): it would read another number; the line is left out of the table here"},
    {"T2 P12345678901234567890", "\"P12345678901234567890\" is beyond the largest whole number LinuxCNC reads (2147483647): it would read another number; the line is left out of the table here"},
    {"T2 P2 Q-3000000000", "\"Q-3000000000\" is beyond the largest whole number LinuxCNC reads (2147483647): it would read another number; the line is left out of the table here"},
  };
  // clang-format on
  for (const BadTableLine& bad : kLines) {
    const ToolTable table =
        parse_tool_table(std::string("T1 P1 Z30\n") + bad.line + "\nT3 P3 Z100000\n");
    EXPECT_EQ(table.tools.size(), 2u) << bad.line;
    EXPECT_EQ(table.tools.count(2), 0u) << bad.line;
    ASSERT_EQ(table.problems.size(), 1u) << bad.line;
    EXPECT_EQ(table.problems[0].line, 2);
    EXPECT_EQ(table.problems[0].text, bad.expected);
  }
}

TEST_F(Lint, shouldReportTheProblemsOfTheIniToolTable) {
  // Not only of --tool-table: the table rs274 is given is the INI's.
  const std::string ini =
      write("machine.ini", "[EMCIO]\nTOOL_TABLE = tools.tbl\n[TRAJ]\nLINEAR_UNITS = mm\n");
  write("tools.tbl", "T1 P1 Z30\nT2 P2 Znan\n");
  const LintRun r = lint(write("p.ngc", "T1 M6\nT2 M6\nM2\n"), {"--ini", ini});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              path("tools.tbl") +
                  ": line 2: \"Znan\" is no number a tool can have (NaN, "
                  "infinite, or over 100000 either way), which LinuxCNC would read as it is; the "
                  "line is left out of the table here\n");
  EXPECT_LINE(r,
              "p.ngc: line 2: LinuxCNC stops the program here: Requested tool 2 not found in "
              "the tool table\n");
}

// ---- the rack keep-out: config.json's rack (pockets along X at Y20, Z-80,
// margin 20), up to Z-55 with an empty spindle; sim.tbl's lengths ----

TEST_F(Lint, shouldNameTheLineThatTakesTheToolDownIntoThePocketsColumn) {
  const std::string text =
      "T1 M6\nG43\nG0 X150 Y60 Z-40\nG0 Z-100 (beside the rack, low)\nG0 Z-40\nG0 Y20\n"
      "G0 Z-60\nM2\n";
  const LintRun r = lint(write("keepout.ngc", text),
                         {"--ini", kSimIni, "--state", state_with_lengths({1})});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              "keepout.ngc: line 7: G0 would enter the rack at pocket 3 with T1 (length "
              "30.0000 mm), the nose at machine X150.000 Y20.000 Z-25.000\n");
  EXPECT_NO_LINE(r, "line 4:");
  EXPECT_LINE(r, "keepout.ngc: 1 tool change (M6), 0 M61, 1 problem, 0 not known\n");
}

TEST_F(Lint, shouldNameTheLineOfTheKeepoutScenarioProgram) {
  // The integration scenario's program, T1 in the spindle: where the machine
  // stands before its G53 moves is not known, where line 3 ends is.
  Config config = *io::load_config_file(kConfig).config;
  ToolState tools = ToolState::fresh(config);
  tools.put_in_spindle(1);
  io::save_state_file(path("t1.state"), tools, io::kCommandLineWait);
  const LintRun r = lint(FATC_SOURCE_DIR "/tests/integration/keepout/keepout_program.ngc",
                         {"--ini", kSimIni, "--state", path("t1.state")});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              "keepout_program.ngc: line 3: G1 would enter the rack at pocket 4 with T1 (length "
              "30.0000 mm), the nose at machine X200.000 Y20.000 Z-80.000\n");
}

TEST_F(Lint, shouldRaiseTheRackByTheLengthOfTheToolInTheSpindle) {
  // G49: the nose at Z-28; T4's tip (25 long) at Z-53 passes, T6's (50) at Z-78 does not.
  const auto with = [&](int tool) {
    return lint(write("long.ngc", "T" + std::to_string(tool) +
                                      " M6\nG49\nG0 X150 Y20 Z-2\nG0 Z-28\nM2\n"),
                {"--ini", kSimIni, "--state", state_with_lengths({4, 6})});
  };
  EXPECT_EQ(with(4).code, 0) << with(4).out;
  EXPECT_LINE(with(6),
              "long.ngc: line 4: G0 would enter the rack at pocket 3 with T6 (length 50.0000 "
              "mm), the nose at machine X150.000 Y20.000 Z-5.000\n");
}

TEST_F(Lint, shouldNameAnArcThatSweepsThroughTheRack) {
  // About X150 Y60 from X100 to X200: counterclockwise it dips to Y10.
  const LintRun r = lint(write("arc.ngc", "G0 X100 Y60 Z-70\nG3 X200 Y60 I50 J0 F500\nM2\n"));
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              "arc.ngc: line 2: G3 would enter the rack at pocket 2 with an empty spindle, the "
              "nose at machine X104.17");
  EXPECT_EQ(lint(write("arc.ngc", "G0 X100 Y60 Z-70\nG2 X200 Y60 I50 J0 F500\nM2\n")).code, 0);
}

TEST_F(Lint, shouldNameASubroutinesMoveWithTheLineThatCallsIt) {
  fs::create_directories(path("subs"));
  write("subs/dip.ngc", "o<dip> sub\nG0 Z-70\no<dip> endsub\nM2\n");
  const LintRun r = lint(write("calls_dip.ngc", "G0 X150 Y20 Z-5\n#1 = 2\no<dip> call\nM2\n"),
                         {"--subroutine-path", path("subs")});
  EXPECT_LINE(r,
              "calls_dip.ngc: line 3: G0 would enter the rack at pocket 3 with an empty spindle, "
              "the nose at machine X150.000 Y20.000 Z-55.000 (in a subroutine this line calls)\n");
  // A subroutine of the program's own file: its own line.
  const LintRun own = lint(write(
      "own_dip.ngc", "o<low> sub\nG0 Z-70\no<low> endsub\nG0 X150 Y20 Z-5\no<low> call\nM2\n"));
  EXPECT_LINE(own,
              "own_dip.ngc: line 2: G0 would enter the rack at pocket 3 with an empty spindle, "
              "the nose at machine X150.000 Y20.000 Z-55.000\n");
}

TEST_F(Lint, shouldTakeAnInchProgramOnAMmMachine) {
  const LintRun r =
      lint(write("inch.ngc", "G20\nG0 X5.9055 Y0.7874 Z-0.1969\nG0 Z-2.7559\nM2\n"));
  EXPECT_LINE(r,
              "inch.ngc: line 3: G0 would enter the rack at pocket 3 with an empty spindle, the "
              "nose at machine X150.000 Y20.000 Z-55.000\n");
}

TEST_F(Lint, shouldFindTheNoseUnderEveryOffsetAsLinuxCncDoes) {
  // G54 from the machine's parameter file (in its units, mm), G92, a
  // rotated coordinate system and G43: G53 down over pocket 4 ends there.
  const std::string ini = write(
      "offsets.ini",
      "[RS274NGC]\nPARAMETER_FILE = offsets.var\nSUBROUTINE_PATH = " FATC_SOURCE_DIR
      "/nc_files\nREMAP = M6 modalgroup=6 ngc=fixed_atc_probe_m6\n[EMCIO]\nTOOL_TABLE = " +
          kSimTable + "\n[TRAJ]\nLINEAR_UNITS = mm\n");
  write("offsets.var", "5220\t1\n5221\t12.5\n5222\t-7.25\n5223\t-3\n");
  const std::string text =
      "T1 M6\nG54 G92 X5 Y5 Z5\nG10 L2 P1 R30\nG43\nG53 G0 X200 Y20 Z-5\nG53 G0 Z-70\nM2\n";
  const LintRun r =
      lint(write("offsets.ngc", text), {"--ini", ini, "--state", state_with_lengths({1})});
  EXPECT_LINE(r,
              "offsets.ngc: line 6: G0 would enter the rack at pocket 4 with T1 (length 30.0000 "
              "mm), the nose at machine X200.000 Y20.000 Z-25.000\n");
}

// ---- what the program does to its own tools and machine (issue 32, class 2) ----

TEST_F(Lint, shouldPutTheNoseAtAG53PositionWhateverTheOffsetOfTheM6) {
  // T2 (35 mm) M6 ends in G43 on the machine; G53 takes the nose to Z-30
  // all the same, its tip at Z-65: into pocket 3's column, not 35 mm above.
  const auto with = [&](const std::string& moves) {
    return lint(write("park.ngc", "T2 M6\n" + moves + "M2\n"),
                {"--ini", kSimIni, "--state", state_with_lengths({2})});
  };
  const LintRun park = with("G53 G0 X150 Y60 Z-30\nG53 G1 Y20 F1000\n");
  EXPECT_EQ(park.code, 1);
  EXPECT_LINE(park,
              "park.ngc: line 3: G1 would enter the rack at pocket 3 with T2 (length 35.0000 "
              "mm), the nose at machine X150.000 Y40.000 Z-30.000\n");
  // In program coordinates the M6's G43 counts: Z-30 is the tip, the nose at Z5.
  EXPECT_EQ(with("G0 X150 Y60 Z-30\nG1 Y20 F1000\n").code, 0);
  // The same without G53 and without the program's own G43: the tip at Z-60.
  EXPECT_LINE(with("G0 X150 Y60 Z-40\nG0 Y20\nG0 Z-60\n"),
              "park.ngc: line 4: G0 would enter the rack at pocket 3 with T2 (length 35.0000 "
              "mm), the nose at machine X150.000 Y20.000 Z-20.000\n");
}

TEST_F(Lint, shouldPutTheNoseWhereLinuxCncDoesUnderInchesARotatedG55AndTheM6sG43) {
  // tests/integration/keepout/offsets_after_m6.ngc to its last move, where the real
  // LinuxCNC stood at X101.6 Y76.2 Z-28.5 (integration_keepout_offsets_after_m6);
  // from there, program X-1.2126 is machine Y20, over pocket 2.
  std::ifstream file(FATC_SOURCE_DIR "/tests/integration/keepout/offsets_after_m6.ngc");
  std::string program, line;
  while (std::getline(file, line) && line != "G0 Z-2.5") program += line + "\n";
  const LintRun r = lint(write("offsets.ngc", program + "G0 Z-2.5\nG0 X-1.2126\nM2\n"),
                         {"--ini", kSimIni, "--state", state_with_lengths({2})});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r,
              "offsets.ngc: line 13: G0 would enter the rack at pocket 2 with T2 (length 35.0000 "
              "mm), the nose at machine X101.600 Y40.000 Z-28.500\n");
}

TEST_F(Lint, shouldCountAToolLengthTheProgramSetsFromThatLineOn) {
  // T1 is 30 mm in sim.tbl: the nose at Z-10 over pocket 3 passes; at 80 mm
  // (G10 L1, L10 or L11) its tip is 35 mm into the column.
  const auto with = [&](const std::string& set) {
    return lint(write("g10.ngc", "T1 M6\nG53 G0 X150 Y60 Z-10\n" + set + "G53 G0 Y20\nM2\n"),
                {"--ini", kSimIni, "--state", state_with_lengths({1})});
  };
  EXPECT_EQ(with("").code, 0) << with("").out;
  // L10: the length that makes the nose's Z (program Z-40) read Z-70: 60 mm.
  EXPECT_LINE(with("G10 L10 P1 Z-70\n"),
              "g10.ngc: line 4: G0 would enter the rack at pocket 3 with T1 (length 60.0000 mm)");
  EXPECT_LINE(with("G20\nG10 L1 P1 Z3.1496\nG21\n"),
              "g10.ngc: line 6: G0 would enter the rack at pocket 3 with T1 (length 79.9998 mm)");
  EXPECT_LINE(with("G10 L1 P1 Z80\n"),
              "g10.ngc: line 4: G0 would enter the rack at pocket 3 with T1 (length 80.0000 mm), "
              "the nose at machine X150.000 Y40.000 Z-10.000\n");
}

TEST_F(Lint, shouldCheckTheConfigAgainstTheSoftLimitsOfTheIni) {
  const LintRun r = lint(write("plain.ngc", "G0 X0\nM2\n"),
                         {"--ini", FATC_BAD_CONFIGS "/narrow_limits.ini"});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r, "is outside the soft limits");
  EXPECT_LINE(r, "  " + kConfig + ": ");
}

TEST_F(Lint, shouldTakeTheUserMCodesOfTheIniWithoutRunningThem) {
  fs::create_directories(path("mcodes"));
  const std::string ran = path("ran");
  write("mcodes/M101", "#!/bin/sh\ntouch " + ran + "\n");
  fs::permissions(path("mcodes/M101"), fs::perms::owner_all);
  write("mcodes/M102", "#!/bin/sh\n");  // not executable: LinuxCNC does not take it
  const std::string ini = write("user_m.ini", "[RS274NGC]\nUSER_M_PATH = mcodes\n[TRAJ]\n"
                                              "LINEAR_UNITS = mm\n");
  const LintRun r = lint(write("m101.ngc", "M101 P1 Q2\nG0 X0\nM102\nM2\n"), {"--ini", ini});
  EXPECT_NO_LINE(r, "M101");
  EXPECT_NO_LINE(r, "m101.ngc: line 1:");  // not "P word with no ... user M code to use it"
  EXPECT_LINE(r, "m101.ngc: line 3: LinuxCNC stops the program here: Unknown m code used: M102\n");
  EXPECT_FALSE(fs::exists(ran));
}

TEST_F(Lint, shouldNameAChuckReleaseTheChangerWouldRefuse) {
  const auto with = [&](const std::string& text) {
    return lint(write("release.ngc", text + "M311\nM2\n"),
                {"--ini", kSimIni, "--state", state_with_lengths({1})});
  };
  EXPECT_LINE(with("M3 S1000\nM310\n"),
              "release.ngc: line 2: the chuck release would be refused: the spindle is on: M5 "
              "first\n");
  EXPECT_LINE(with("T1 M6\nG53 G0 X100 Y100 Z-10\no<fixed_atc_probe_chuck_release> call\n"),
              "release.ngc: line 3: the chuck release would be refused: T1 is in the spindle and "
              "would drop: release it only at loading (machine X20.000 Y150.000 Z-10.000) or "
              "with the spindle empty\n");
  // At loading, or with the spindle empty and stopped: the changer opens it.
  const LintRun at_loading = with("T1 M6\nG53 G0 X20 Y150 Z-10\nM310\n");
  EXPECT_EQ(at_loading.code, 0) << at_loading.out;
  EXPECT_EQ(with("M3 S1000\nM5\nM310\n").code, 0);
}

// ---- the changer's own moves with the tools they carry (issue 32, class 1 in the preflight) ----

TEST_F(Lint, shouldNameAChangeWhoseOwnMovesWouldCarryAToolsTipIntoAHolder) {
  const auto with = [&](const std::string& table, const std::string& program) {
    return run({"--lint", write("carry.ngc", program), "--config",
                write("top.json", test::kTopRack),
                "--state", no_state(), "--tool-table", write("tools.tbl", table)});
  };
  // T1 80 mm in the table: fetched from pocket 1, carried to safe over pocket 2's holder.
  const LintRun long_tool = with("T1 P1 Z80\nT2 P2 Z30\n", "T1 M6\nM2\n");
  EXPECT_EQ(long_tool.code, 1) << long_tool.out;
  EXPECT_LINE(long_tool, "carry.ngc: line 1: M6 T1 from empty, step ");
  EXPECT_LINE(long_tool, "): carries T1 (length 80.0000 mm) with its tip ");
  EXPECT_LINE(long_tool, "below the top of the holder at pocket ");
  // 30 mm clears; a Z of 0 or below counts as the longest the config allows (40 mm).
  EXPECT_EQ(with("T1 P1 Z30\nT2 P2 Z-12\n", "T1 M6\nT2 M6\nM2\n").code, 0);
  EXPECT_EQ(with("T1 P1 Z30\n", "G10 L1 P1 Z0\nT1 M6\nM2\n").code, 0);
  // A length the program sets counts for the changes after it: T1 taken
  // at 30 mm, lengthened to 80 and carried back by the next change.
  const LintRun set = with("T1 P1 Z30\nT2 P2 Z30\n", "T1 M6\nG10 L1 P1 Z80\nT2 M6\nM2\n");
  EXPECT_EQ(set.code, 1) << set.out;
  EXPECT_NO_LINE(set, "carry.ngc: line 1: M6");
  EXPECT_LINE(set, "carry.ngc: line 3: M6 T2 from T1, step ");
  EXPECT_LINE(set, "): carries T1 (length 80.0000 mm)");
}

// ---- lint round 4 (issue 42): each class, not the case ----

TEST_F(Lint, shouldNameEveryWayTheSpindleStartsTurningOnceEachTimeAProbeIsInIt) {
  const nlohmann::json tools = {{"2", {{"kind", "probe"}}}};
  const auto with = [&](const std::string& text) {
    return run({"--lint", write("turn.ngc", text), "--config", config_with("tools", tools),
                "--state", state_with_lengths({2, 3})});
  };
  // M3 at S0 turns nothing; the S word later does, on a line of its own or in a G1.
  const LintRun s_word =
      with("T2 M6\nM3 S0\nG1 X10 F100\nS1000\nS2000\nM5\nT3 M6\nM3 S0\nT2 M6\nM3 S0\nG1 X20 S500\nM2\n");
  EXPECT_EQ(s_word.code, 1);
  EXPECT_NO_LINE(s_word, "turn.ngc: line 2:");
  EXPECT_LINE(s_word, "turn.ngc: line 4: the spindle turns here (M3 in force, S1000) with T2 in it, "
                      "a probe (tools.2.kind): fatc-spindle-guard holds the spindle and the "
                      "changer aborts the program here\n");
  EXPECT_NO_LINE(s_word, "turn.ngc: line 5:");
  EXPECT_NO_LINE(s_word, "turn.ngc: line 8:");  // T3, a cutter
  EXPECT_LINE(s_word, "turn.ngc: line 11: the spindle turns here (M3 in force, S500) with T2 in it");
  // G96 with D turns the spindle at D whatever S (canon gives motion D; no surface speed then).
  EXPECT_LINE(with("T2 M6\nG96 D1500 S0 M4\nM2\n"),
              "turn.ngc: line 2: the spindle turns here (M4 in force, G96 up to D1500) with T2");
  EXPECT_LINE(with("T2 M6\nM3 S0\nG96 D900 S0\nM2\n"),
              "turn.ngc: line 3: the spindle turns here (M3 in force, G96 up to D900) with T2");
  // M4 after M5 at the S still in force.
  EXPECT_LINE(with("T2 M6\nS700\nM5\nM4\nM2\n"),
              "turn.ngc: line 4: the spindle turns here (M4 in force, S700) with T2");
  // The S of the program's own subroutine is named on its own line.
  EXPECT_LINE(with("o<s> sub\nS800\no<s> endsub\nT2 M6\nM3 S0\no<s> call\nM2\n"),
              "turn.ngc: line 2: the spindle turns here (M3 in force, S800) with T2");
}

TEST_F(Lint, shouldTakeTheSpindleAsTheRemapLeavesItAfterAChange) {
  // The changer's M6 stops the spindle whatever TOOL_CHANGE_WITH_SPINDLE_ON:
  // the M3 after the change starts it again, with the probe in it.
  const nlohmann::json tools = {{"2", {{"kind", "probe"}}}};
  const std::string ini = write(
      "on.ini", "[RS274NGC]\nSUBROUTINE_PATH = " FATC_SOURCE_DIR
                "/nc_files\nREMAP = M6 modalgroup=6 ngc=fixed_atc_probe_m6\n[EMCIO]\n"
                "TOOL_CHANGE_WITH_SPINDLE_ON = 1\n[TRAJ]\nLINEAR_UNITS = mm\n");
  const LintRun r = run({"--lint", write("on.ngc", "M3 S1000\nT2 M6\nM3\nM2\n"), "--config",
                         config_with("tools", tools), "--state", state_with_lengths({2}),
                         "--ini", ini});
  EXPECT_LINE(r, "on.ngc: line 3: the spindle turns here (M3 in force, S1000) with T2 in it");
  EXPECT_NO_LINE(r, "TOOL_CHANGE_WITH_SPINDLE_ON");
}

TEST_F(Lint, shouldSayTheSpindleIsUncertainAfterACutOffSequenceAsTheGuardTakesIt) {
  const nlohmann::json tools = {{"2", {{"kind", "probe"}}}};
  const std::string config_path = config_with("tools", tools);
  const Config config = *io::load_config_file(config_path).config;
  ToolState cut = ToolState::fresh(config);
  cut.lengths[2] = 22.0;
  cut.uncertain = true;
  cut.in_progress = InProgress{"M6 T2", "fetching tool 2 from pocket 2", 2};
  io::save_state_file(path("cut.state"), cut, io::kCommandLineWait);
  const LintRun r = run({"--lint", write("cut.ngc", "M3 S1000\nM5\nT2 M6\nM2\n"), "--config",
                         config_path, "--state", path("cut.state")});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r, "cut.ngc: at the start the spindle is uncertain (the state file's M6 T2 was "
                 "cut off; last known: nothing): it may hold T2, a probe (tools.2.kind): "
                 "fatc-spindle-guard holds the spindle until the fault is cleared (panel, or "
                 "--confirm)\n");
  EXPECT_NO_LINE(r, "the spindle holds nothing");
  EXPECT_LINE(r, "cut.ngc: line 1: the spindle turns here (M3 in force, S1000) while it may hold "
                 "T2, a probe, as the cut-off sequence of the state file left it (tools.2.kind): "
                 "fatc-spindle-guard holds the spindle and the changer aborts the program here\n");
  // Cut off at pocket 1 with the probe in its own pocket: the spindle holds no probe.
  cut.in_progress = InProgress{"M6 T1", "fetching tool 1 from pocket 1", 1};
  io::save_state_file(path("cut.state"), cut, io::kCommandLineWait);
  const LintRun cutter = run({"--lint", write("cut.ngc", "M3 S1000\nM5\nT2 M6\nM2\n"), "--config",
                              config_path, "--state", path("cut.state")});
  EXPECT_LINE(cutter, "(the state file's M6 T1 was cut off; last known: nothing): the changer "
                      "refuses M6 until the fault is cleared (panel, or --confirm)\n");
  EXPECT_NO_LINE(cutter, "cut.ngc: line 1:");
}

TEST_F(Lint, shouldNameTheIniKeysThatMoveLinuxCncsOwnM6AfterTheChange) {
  const std::string ini = write(
      "moves.ini", "[RS274NGC]\nSUBROUTINE_PATH = " FATC_SOURCE_DIR
                   "/nc_files\nREMAP = M6 modalgroup=6 ngc=fixed_atc_probe_m6\n[EMCIO]\n"
                   "TOOL_CHANGE_POSITION = 0 0 -5\nTOOL_CHANGE_QUILL_UP = 1\n"
                   "TOOL_CHANGE_AT_G30 = 0\nTOOL_CHANGE_WITH_SPINDLE_ON = 1\n[TRAJ]\n"
                   "LINEAR_UNITS = mm\n");
  const LintRun r = lint(write("moves.ngc", "T1 M6\nM2\n"), {"--ini", ini});
  EXPECT_EQ(r.code, 1);
  EXPECT_LINE(r, "  " + ini +
                     ": [EMCIO]TOOL_CHANGE_POSITION (line 5): LinuxCNC's own M6, which "
                     "fixed_atc_probe_m6 calls once the change is done, would rapid to \"0 0 -5\" "
                     "after every change, from safe; remove it: the changer ends its change at "
                     "safe\n");
  EXPECT_LINE(r, "  " + ini +
                     ": [EMCIO]TOOL_CHANGE_QUILL_UP (line 6): LinuxCNC's own M6, which "
                     "fixed_atc_probe_m6 calls once the change is done, would rapid Z up to "
                     "machine zero (G53 Z0) after every change, from safe; remove it");
  EXPECT_NO_LINE(r, "TOOL_CHANGE_AT_G30");  // 0: it moves nothing
  EXPECT_NO_LINE(r, "TOOL_CHANGE_WITH_SPINDLE_ON");
  // --check names them the same, one line each.
  const LintRun check = run({"--check", "--config", kConfig, "--state", no_state(), "--ini", ini});
  EXPECT_EQ(check.code, 1);
  EXPECT_TRUE(has(check.err, ini + ": [EMCIO]TOOL_CHANGE_POSITION (line 5): LinuxCNC's own M6"))
      << check.err;
  EXPECT_TRUE(has(check.err, ini + ": [EMCIO]TOOL_CHANGE_QUILL_UP (line 6): LinuxCNC's own M6"))
      << check.err;
  const std::string g30 = write("g30.ini", "[EMCIO]\nTOOL_CHANGE_AT_G30 = true\n");
  EXPECT_LINE(lint(write("g30.ngc", "M2\n"), {"--ini", g30}),
              ": [EMCIO]TOOL_CHANGE_AT_G30 (line 2): LinuxCNC's own M6, which fixed_atc_probe_m6 "
              "calls once the change is done, would rapid to the G30 position after every "
              "change");
}

TEST(ToolTable, shouldReadALineOverLinuxCncsBufferAsItsFgetsDoes) {
  // 255 characters at a time, each a line: T3 from the start, its comment cut.
  const std::string comment(300, 'x');
  ToolTable table = parse_tool_table("T3 P3 Z40.5 ;" + comment + "\nT4 P4 Z20\n");
  ASSERT_EQ(table.tools.count(3), 1u);
  EXPECT_DOUBLE_EQ(*table.tools.at(3).z, 40.5);
  EXPECT_EQ(table.tools.count(4), 1u);
  ASSERT_EQ(table.problems.size(), 1u);
  EXPECT_EQ(table.problems[0].line, 1);
  EXPECT_EQ(table.problems[0].text,
            "313 characters, over the 255 LinuxCNC reads as one line: it reads tool 3 from the "
            "first 255, its comment cut there; characters 256 on as a line of their own, which it "
            "skips");
  // A field cut by the 255th character: LinuxCNC reads the number short.
  const std::string pad(245, ' ');  // Z40.125 from the 251st character
  table = parse_tool_table("T5 P5" + pad + "Z40.125 D6\n");
  ASSERT_EQ(table.tools.count(5), 1u);
  EXPECT_DOUBLE_EQ(*table.tools.at(5).z, 40.1);
  ASSERT_EQ(table.problems.size(), 1u);
  EXPECT_EQ(table.problems[0].text,
            "260 characters, over the 255 LinuxCNC reads as one line: it reads tool 5 from the "
            "first 255, its field \"Z40.125\" read as \"Z40.1\", without what follows; characters "
            "256 on as a line of their own, which it skips");
  // The rest may read as a tool of its own, as LinuxCNC would take it.
  table = parse_tool_table("T6 P6 Z10 " + std::string(245, ' ') + "T7 P7 Z11\n");
  EXPECT_EQ(table.tools.count(6), 1u);
  ASSERT_EQ(table.tools.count(7), 1u);
  EXPECT_DOUBLE_EQ(*table.tools.at(7).z, 11.0);
  ASSERT_EQ(table.problems.size(), 1u);
  EXPECT_EQ(table.problems[0].text,
            "264 characters, over the 255 LinuxCNC reads as one line: it reads tool 6 from the "
            "first 255, without what follows; characters 256 on as a line of their own, read as "
            "tool 7");
  // A megabyte on one line: read piece by piece, said in one short line.
  std::string many = "T4 P4 Z1 ;";
  for (int i = 0; i < 4000; ++i) many += std::string(250, ' ') + "T" + std::to_string(100 + i % 3) + " Z9";
  table = parse_tool_table(many + "\n");
  ASSERT_FALSE(table.problems.empty());
  EXPECT_LT(table.problems[0].text.size(), 300u) << table.problems[0].text;
  EXPECT_NE(table.problems[0].text.find(" lines of their own: "), std::string::npos);
  // 255 characters are read whole: nothing to say.
  table = parse_tool_table("T8 P8 Z12 ;" + std::string(244, 'c') + "\n");
  EXPECT_TRUE(table.problems.empty());
  EXPECT_EQ(table.tools.count(8), 1u);
}

TEST_F(Lint, shouldKeepTheLengthOfAToolOnALongTableLine) {
  write("long.tbl", "T1 P1 Z30 ;" + std::string(400, 'c') + "\n");
  const LintRun r = lint(write("long.ngc", "T1 M6\nM2\n"),
                         {"--tool-table", path("long.tbl"), "--state", state_with_lengths({})});
  EXPECT_LINE(r, "M6 T1         pocket 1");
  EXPECT_LINE(r, "Z30.0000 (tool table)");
  EXPECT_NO_LINE(r, "not in the tool table");
  EXPECT_LINE(r, path("long.tbl") + ": line 1: 411 characters, over the 255 LinuxCNC reads as one "
                                    "line: it reads tool 1 from the first 255, its comment cut "
                                    "there; characters 256 on as a line of their own, which "
                                    "it skips\n");
}

TEST_F(Lint, shouldReadTheIniAsTheLinuxcncScriptExpandsItsIncludes) {
  fs::create_directories(path("machine/parts"));
  write("machine/parts/axes.inc",
        "[AXIS_X]\nMIN_LIMIT = -10\nMAX_LIMIT = 400\n[AXIS_Y]\nMIN_LIMIT = -10\nMAX_LIMIT = 300\n"
        "[AXIS_Z]\nMIN_LIMIT = -120\nMAX_LIMIT = 0\n");
  write("machine/parts/remap.inc", "[RS274NGC]\nSUBROUTINE_PATH = " FATC_SOURCE_DIR
                                   "/nc_files\nREMAP = M6 modalgroup=6 ngc=fixed_atc_probe_m6\n");
  // Relative to the INI's folder, wherever the command runs.
  const std::string ini = write("machine/m.ini", "[TRAJ]\nLINEAR_UNITS = mm\n#INCLUDE parts/axes.inc\n"
                                                 "#INCLUDE parts/remap.inc\n");
  const LintRun check = run({"--check", "--config", kConfig, "--state", no_state(), "--ini", ini});
  EXPECT_EQ(check.code, 0) << check.out << check.err;
  const LintRun r =
      lint(write("inc.ngc", "T1 M6\nM2\n"), {"--ini", ini, "--state", state_with_lengths({1})});
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NO_LINE(r, "remaps no M6");
  EXPECT_NO_LINE(r, "soft limits");
  // Included again and again past 1 MiB: refused in one line, at once.
  write("machine/parts/big.inc", "; " + std::string(600 * 1024, 'x') + "\n");
  write("machine/big.ini", "#INCLUDE parts/big.inc\n#INCLUDE parts/big.inc\n");
  const LintRun big =
      run({"--check", "--config", kConfig, "--state", no_state(), "--ini", path("machine/big.ini")});
  EXPECT_EQ(big.code, 1);
  EXPECT_TRUE(has(big.err, path("machine/big.ini") +
                               ": over 1 MiB with the files its #INCLUDE lines name\n"))
      << big.err;
  EXPECT_LT(big.seconds, 5.0);
  // One line for an include that cannot be read; a key's line in its own file.
  write("machine/broken.ini", "[TRAJ]\nLINEAR_UNITS = mm\n#INCLUDE parts/gone.inc\n"
                              "#INCLUDE parts/axes.inc\n#INCLUDE\n[EMCIO]\nTOOL_CHANGE_QUILL_UP = 1\n");
  write("machine/parts/axes.inc", "[AXIS_X]\nMIN_LIMIT = -10\nMAX_LIMIT = nan\n");
  const LintRun broken =
      run({"--check", "--config", kConfig, "--state", no_state(), "--ini", path("machine/broken.ini")});
  EXPECT_EQ(broken.code, 1);
  EXPECT_TRUE(has(broken.err, path("machine/broken.ini") +
                                  ": line 3: #INCLUDE " + path("machine") +
                                  "/parts/gone.inc: cannot open (No such file or directory): "
                                  "none of its keys are read\n"))
      << broken.err;
  EXPECT_TRUE(has(broken.err, path("machine/broken.ini") + ": line 5: #INCLUDE names no file\n"))
      << broken.err;
  EXPECT_TRUE(has(broken.err, "[AXIS_X]MAX_LIMIT (line 3 of parts/axes.inc): expected a finite "
                              "number from -1e99 to 1e99, got \"nan\"\n"))
      << broken.err;
  EXPECT_TRUE(has(broken.err, "[EMCIO]TOOL_CHANGE_QUILL_UP (line 7): LinuxCNC's own M6"))
      << broken.err;
}

TEST_F(Lint, shouldTakeTheUserMCodesOfAnIncludedOrHomeRelativePath) {
  fs::create_directories(path("machine/mcodes"));
  write("machine/mcodes/M101", "#!/bin/sh\n");
  fs::permissions(path("machine/mcodes/M101"), fs::perms::owner_all);
  write("machine/paths.inc", "[RS274NGC]\nUSER_M_PATH = nothing:mcodes\n");
  const std::string ini =
      write("machine/m.ini", "[TRAJ]\nLINEAR_UNITS = mm\n#INCLUDE paths.inc\n");
  const LintRun r = lint(write("m101.ngc", "M101 P1 Q2\nM101\nM2\n"), {"--ini", ini});
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NO_LINE(r, "m101.ngc: line");
}

TEST_F(Lint, shouldFindTheIniFoldersUnderTheUsersHomeThoughRs274RunsWithAnotherHome) {
  // rs274 runs with a scratch HOME; `~/` in the INI is the user's, as LinuxCNC takes it.
  fs::create_directories(path("home/subs"));
  fs::create_directories(path("home/mc"));
  fs::create_directories(path("home/prefix"));
  write("home/subs/lift.ngc", "o<lift> sub\nG0 Z0\no<lift> endsub\nM2\n");
  write("home/prefix/park.ngc", "o<park> sub\nG0 X0\no<park> endsub\nM2\n");
  write("home/mc/M150", "#!/bin/sh\n");
  fs::permissions(path("home/mc/M150"), fs::perms::owner_all);
  const std::string ini = write("home.ini", "[DISPLAY]\nPROGRAM_PREFIX = ~/prefix\n[RS274NGC]\n"
                                            "SUBROUTINE_PATH = ~/subs\nUSER_M_PATH = ~/mc\n"
                                            "[TRAJ]\nLINEAR_UNITS = mm\n");
  const char* home = std::getenv("HOME");
  const std::string saved = home ? home : "";
  ::setenv("HOME", path("home").c_str(), 1);
  const LintRun r =
      lint(write("home.ngc", "o<lift> call\no<park> call\nM150 P2\nM2\n"), {"--ini", ini});
  home ? ::setenv("HOME", saved.c_str(), 1) : ::unsetenv("HOME");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NO_LINE(r, "home.ngc: line");
}

}  // namespace
}  // namespace fatc
