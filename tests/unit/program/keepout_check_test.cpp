// The static rack keep-out: canonical calls as rs274 prints them (numbered
// by LineNumberer), read through InterpreterOutput into KeepoutCheck, on
// the valid config's rack (six pockets along X at Y20, 50 apart, margin 20:
// X30-320, Y0-40, up to Z-55) with sim.tbl's lengths.
#include "core/program/keepout_check.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "test_config.hpp"

namespace fatc {
namespace {

const Config& config() {
  static const Config valid = test::valid_config();
  return valid;
}

KeepoutCheckInput input(bool return_to_xy = false) {
  KeepoutCheckInput in;
  in.config = &config();
  in.program = "p.ngc";
  in.tools = ToolState::fresh(config());
  in.lengths = std::map<int, double>{{1, 30.0}, {2, 35.0}, {3, 40.0}, {4, 25.0},
                                     {5, 45.0}, {6, 50.0}, {7, 20.0}};
  in.table_name = "sim.tbl";
  in.longest = [] { return 40.0; };
  in.return_to_xy = return_to_xy;
  return in;
}

/// A call on program line `line` (0: a line of a subroutine file).
std::string on(int line, const std::string& call) {
  return (line > 0 ? "    7 N" + std::to_string(1000000000 + line) : std::string("    7 N.....")) +
         " " + call + "\n";
}
std::string traverse(int line, double x, double y, double z) {
  std::ostringstream call;
  call.setf(std::ios::fixed);
  call.precision(4);
  call << "STRAIGHT_TRAVERSE(" << x << ", " << y << ", " << z << ", 0.0000, 0.0000, 0.0000)";
  return on(line, call.str());
}
std::string tool_offset(int line, double z) {
  std::ostringstream call;
  call.setf(std::ios::fixed);
  call.precision(4);
  call << "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 " << z
       << ", 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)";
  return on(line, call.str());
}
/// M6 T`tool` on `line`, through the preflight's stand-in for the remap: M6
/// and G43 with the table's `length`.
std::string change(int line, int tool, double length = 0.0) {
  return on(line, "SELECT_TOOL(" + std::to_string(tool) + ")") + on(0, "START_CHANGE()") +
         on(0, "CHANGE_TOOL(" + std::to_string(tool) + ")") + tool_offset(0, length);
}

struct Checked {
  std::vector<program::Finding> problems;
  std::vector<program::Finding> unknowns;
  std::string text() const {
    std::string all;
    for (const auto& found : problems) {
      all += "line " + std::to_string(found.where.line) + ": " + found.text + "\n";
    }
    return all;
  }
};

/// LineNumberer's note, as rs274 prints it, that `line` runs a subroutine.
std::string runs_subroutine(int line) {
  return on(line, "COMMENT(\"" + std::string(program::kRunsSubroutine) + "\")");
}

/// `calls` through InterpreterOutput.
Checked checked(const std::string& calls, KeepoutCheckInput in = input()) {
  KeepoutCheck keepout(std::move(in));
  program::ProgramGiven given;
  given.name = "p.ngc";
  given.lines = 1000;
  program::InterpreterOutput output(given, {0, 1, 2, 3, 4, 5, 6, 7, 9});
  output.listen(&keepout);
  std::istringstream lines(calls);
  for (std::string line; std::getline(lines, line);) output.canonical_call(line);
  output.finish();
  return {keepout.problems(), keepout.unknowns()};
}

TEST(KeepoutCheck, shouldNameAMoveDownOverAPocketAndNotOneBesideTheRack) {
  const Checked run = checked(traverse(1, 150, 20, -5) + traverse(2, 150, 20, -70) +
                              traverse(3, 150, 60, -70) + traverse(4, 150, 60, -100) +
                              on(5, "STRAIGHT_FEED(300.0000, 60.0000, -100.0000, 0, 0, 0)"));
  EXPECT_EQ(run.text(),
            "line 2: G0 would enter the rack at pocket 3 with an empty spindle, the nose at "
            "machine X150.000 Y20.000 Z-55.000\n");
}

TEST(KeepoutCheck, shouldRaiseTheRackByTheLengthOfTheToolInTheSpindle) {
  // G49, then from safe (X120 Y80 Z-5), where the change ends, over pocket 3 at Z-25.
  const std::string moves = on(2, "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 0.0000, 0.0000 0.0000 "
                                  "0.0000, 0.0000 0.0000 0.0000)") +
                            traverse(3, 150, 20, -25);
  EXPECT_EQ(checked(change(1, 4) + moves).text(), "");  // T4, 25 long: its tip at Z-50
  EXPECT_EQ(checked(change(1, 6) + moves).text(),
            "line 3: G0 would enter the rack at pocket 3 with T6 (length 50.0000 mm), the nose "
            "at machine X140.000 Y40.000 Z-18.333\n");
}

TEST(KeepoutCheck, shouldTakeTheProgramsZAsTheTipOfTheNewToolAfterM6) {
  // The stand-in ends in G43 as the remap does: T1's 30 mm in force.
  const Checked run =
      checked(change(1, 1, 30) + traverse(2, 150, 20, -50) + traverse(3, 150, 20, -60));
  EXPECT_EQ(run.text(),
            "line 3: G0 would enter the rack at pocket 3 with T1 (length 30.0000 mm), the nose "
            "at machine X150.000 Y20.000 Z-25.000\n");
}

TEST(KeepoutCheck, shouldCheckAnArcAlongItsWayNotOnlyItsEnds) {
  const std::string start = traverse(1, 100, 60, -70);
  // Counterclockwise from X100 to X200 about X150 Y60 dips to Y10, into the rack.
  const Checked down = checked(start + on(2, "ARC_FEED(200.0000, 60.0000, 150.0000, 60.0000, 1, "
                                             "-70.0000, 0.0000, 0.0000, 0.0000)"));
  ASSERT_EQ(down.problems.size(), 1u) << down.text();
  const std::string expected =
      "line 2: G3 would enter the rack at pocket 2 with an empty spindle, the nose at machine "
      "X104.17";  // the circle meets Y40 at X104.174, the chords within 0.001 of it
  EXPECT_EQ(down.text().substr(0, expected.size()), expected);
  // Clockwise it rises to Y110, away from it.
  EXPECT_EQ(checked(start + on(2, "ARC_FEED(200.0000, 60.0000, 150.0000, 60.0000, -1, "
                                  "-70.0000, 0.0000, 0.0000, 0.0000)"))
                .text(),
            "");
}

TEST(KeepoutCheck, shouldCheckOnlyWhereTheFirstMoveEndsAndAxesOnceTheProgramSetsThem) {
  // Where the machine stands at the start is not known: X and Y set, Z not yet.
  EXPECT_EQ(checked(traverse(1, 150, 20, 0) + traverse(2, 150, 20, -70)).text(),
            "line 2: G0 would enter the rack at pocket 3 with an empty spindle, the nose at "
            "machine X150.000 Y20.000 Z-70.000\n");
  EXPECT_EQ(checked(traverse(1, 150, 20, -70)).text(),
            "line 1: G0 would enter the rack at pocket 3 with an empty spindle, the nose at "
            "machine X150.000 Y20.000 Z-70.000\n");
}

TEST(KeepoutCheck, shouldGoOnFromWhereTheChangeEnds) {
  // Over pocket 3 before M6; the change ends at safe, and Z-70 there is clear of the rack.
  const std::string program = traverse(1, 150, 20, -5) + change(2, 1, 30) + traverse(3, 150, 20, -70);
  EXPECT_EQ(checked(program).text(), "");
  // With RETURN_TO_XY the change ends back over pocket 3.
  EXPECT_EQ(checked(program, input(true)).text(),
            "line 3: G0 would enter the rack at pocket 3 with T1 (length 30.0000 mm), the nose "
            "at machine X150.000 Y20.000 Z-25.000\n");
}

TEST(KeepoutCheck, shouldNameAMoveOfASubroutineFileWithTheLineThatCallsIt) {
  // Line 2 sets a parameter (nothing printed), line 3 calls dip.ngc.
  const Checked run =
      checked(traverse(1, 150, 20, -5) + runs_subroutine(3) + traverse(0, 150, 20, -70));
  EXPECT_EQ(run.text(),
            "line 3: G0 would enter the rack at pocket 3 with an empty spindle, the nose at "
            "machine X150.000 Y20.000 Z-55.000 (in a subroutine this line calls)\n");
}

TEST(KeepoutCheck, shouldTakeAnInchProgramOnAMmConfig) {
  const Checked run = checked(on(1, "USE_LENGTH_UNITS(CANON_UNITS_INCHES)") +
                              traverse(2, 5.9055, 0.7874, -0.1969) +
                              traverse(3, 5.9055, 0.7874, -2.7559));
  EXPECT_EQ(run.text(),
            "line 3: G0 would enter the rack at pocket 3 with an empty spindle, the nose at "
            "machine X150.000 Y20.000 Z-55.000\n");
}

TEST(KeepoutCheck, shouldCountAToolOfNoLengthAsTheGuardDoesAndSaySoOnce) {
  // T9 is not in the table: the longest the config allows (40 mm here), as
  // the guard counts it, never 0: its tip reaches the holders' tops from Z-15.
  const Checked run =
      checked(change(1, 9) + traverse(2, 150, 20, -10) + traverse(3, 150, 20, -20));
  EXPECT_EQ(run.text(),
            "line 3: G0 would enter the rack at pocket 3 with T9 (length 40.0000 mm), the nose "
            "at machine X150.000 Y20.000 Z-15.000\n");
  ASSERT_EQ(run.unknowns.size(), 1u);
  EXPECT_EQ(run.unknowns[0].where.line, 2);
  EXPECT_EQ(run.unknowns[0].text,
            "T9: LinuxCNC's tool table gives no length; the rack keep-out counts it as 40.0000 mm "
            "(the longest tool the config allows) (tool table sim.tbl)");
  // A Z of 0 or below, in the table or set by G10, is no length either; the
  // changer's measured length counts before the longest.
  KeepoutCheckInput measured = input();
  (*measured.lengths)[4] = -12.0;
  measured.tools.lengths[4] = 33.0;
  EXPECT_EQ(checked(change(1, 4) + traverse(2, 150, 20, -10) + traverse(3, 150, 20, -30),
                    std::move(measured))
                .text(),
            "line 3: G0 would enter the rack at pocket 3 with T4 (length 33.0000 mm), the nose "
            "at machine X150.000 Y20.000 Z-22.000\n");
  const std::string set_below =
      on(2, "SET_TOOL_TABLE_ENTRY(1, 1, 0.0000 0.0000 -3.1496 0.0000 0.0000 0.0000 0.0000 0.0000 "
            "0.0000, 0.0000, 0.0000, 0)");
  EXPECT_EQ(checked(change(1, 1, 30) + tool_offset(2, 0) + set_below + traverse(3, 150, 20, -10) +
                    traverse(4, 150, 20, -20))
                .text(),
            "line 4: G0 would enter the rack at pocket 3 with T1 (length 40.0000 mm), the nose "
            "at machine X150.000 Y20.000 Z-15.000\n");
}

TEST(KeepoutCheck, shouldTakeALengthTheProgramSetsFromThatLineOn) {
  // G10 L1 P1 Z80, as rs274 prints it (inches) for the tool's row and the spindle's.
  const std::string set =
      on(3, "SET_TOOL_TABLE_ENTRY(1, 1, 0.0000 0.0000 3.1496 0.0000 0.0000 0.0000 0.0000 0.0000 "
            "0.0000, 0.0000, 0.0000, 0)") +
      on(3, "SET_TOOL_TABLE_ENTRY(0, 1, 0.0000 0.0000 3.1496 0.0000 0.0000 0.0000 0.0000 0.0000 "
            "0.0000, 0.0000, 0.0000, 0)");
  const std::string over = change(1, 1, 30) + tool_offset(2, 0) + traverse(2, 150, 60, -10);
  EXPECT_EQ(checked(over + traverse(4, 150, 20, -10)).text(), "");
  EXPECT_EQ(checked(over + set + traverse(4, 150, 20, -10)).text(),
            "line 4: G0 would enter the rack at pocket 3 with T1 (length 80.0000 mm), the nose "
            "at machine X150.000 Y40.000 Z-10.000\n");
  // Written in inches, 3.1496 is what the line wrote: not rounded to 80 mm.
  const std::string inch_set =
      on(3, "USE_LENGTH_UNITS(CANON_UNITS_INCHES)") +
      on(3, "SET_TOOL_TABLE_ENTRY(1, 1, 0.0000 0.0000 3.1496 0.0000 0.0000 0.0000 0.0000 0.0000 "
            "0.0000, 0.0000, 0.0000, 0)") +
      on(3, "USE_LENGTH_UNITS(CANON_UNITS_MM)");
  EXPECT_EQ(checked(over + inch_set + traverse(4, 150, 20, -10)).text(),
            "line 4: G0 would enter the rack at pocket 3 with T1 (length 79.9998 mm), the nose "
            "at machine X150.000 Y40.000 Z-10.000\n");
}

TEST(KeepoutCheck, shouldNameAChuckReleaseWhileTheSpindleTurnsOrAToolHangsAwayFromLoading) {
  const std::string release =
      "COMMENT(\"Releases - opens - the chuck through fixed_atc_probe, and leaves it open.\")";
  EXPECT_EQ(checked(on(1, "START_SPINDLE_CLOCKWISE(0)") + runs_subroutine(2) + on(0, release)).text(),
            "line 2: the chuck release would be refused: the spindle is on: M5 first\n");
  EXPECT_EQ(checked(on(1, "START_SPINDLE_CLOCKWISE(0)") + on(2, "STOP_SPINDLE_TURNING(0)") +
                    on(0, release))
                .text(),
            "");
  const std::string t1 = change(1, 1, 30) + tool_offset(2, 0);
  EXPECT_EQ(checked(t1 + traverse(3, 20, 150, -10) + on(4, release)).text(), "");
  EXPECT_EQ(checked(t1 + traverse(3, 20, 150, -9) + on(4, release)).text(),
            "line 4: the chuck release would be refused: T1 is in the spindle and would drop: "
            "release it only at loading (machine X20.000 Y150.000 Z-10.000) or with the spindle "
            "empty\n");
}

}  // namespace
}  // namespace fatc
