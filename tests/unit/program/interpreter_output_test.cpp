// What rs274 prints, read into tool uses, problems and what is not known:
// each test feeds text captured from rs274 (LinuxCNC 2.9) over a program
// numbered by LineNumberer; and the numbering itself, piece by piece.
#include "core/program/interpreter_output.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "core/program/interpreter_inputs.hpp"
#include "core/program/numbered_program.hpp"

namespace fatc::program {
namespace {

/// Rows 1-7 hold tools 1-7, as config/sim/sim.tbl.
std::vector<int> sim_rows() { return {0, 1, 2, 3, 4, 5, 6, 7}; }

/// p.ngc of `lines` lines, numbered into /tmp/x/program.ngc; `input_lines` read #5399.
ProgramGiven given(std::vector<int> input_lines = {}, int lines = 1000000) {
  ProgramGiven program;
  program.name = "p.ngc";
  program.numbered_path = "/tmp/x/program.ngc";
  program.stub_folder = "/tmp/x/undefined";
  for (const int line : input_lines) program.input_lines.insert(line);
  program.lines = lines;
  return program;
}

InterpreterRun read(const std::string& out, const std::string& err,
                    std::vector<int> input_lines = {}, std::vector<int> rows = sim_rows()) {
  InterpreterOutput output(given(std::move(input_lines)), std::move(rows));
  std::istringstream calls(out), errors(err);
  for (std::string line; std::getline(calls, line);) output.canonical_call(line);
  for (std::string line; std::getline(errors, line);) output.error_line(line);
  return output.finish();
}

std::string uses_of(const InterpreterRun& run) {
  std::string text;
  for (const ToolUse& use : run.uses) {
    text += (use.kind == ToolUse::Kind::change ? "M6 T" : "M61 Q") +
            (use.tool ? std::to_string(*use.tool) : "?") + "@" + std::to_string(use.where.line) +
            " ";
  }
  return text;
}

TEST(InterpreterOutput, shouldTakeEachChangeOnItsTWordsLineThroughTheRemap) {
  // T3 on line 3, M6 on line 5 (remapped: its calls have no N word).
  const auto run = read(
      "    7 N1000000002 STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
      "    8 N1000000003 SELECT_TOOL(3)\n"
      "    9 N..... COMMENT(\"REMAP=M6 modalgroup=6 ngc=fixed_atc_probe_m6\")\n"
      "   12 N..... START_CHANGE()\n"
      "   14 N..... CHANGE_TOOL(3)\n"
      "   15 N1000000007 CHANGE_TOOL_NUMBER(2)\n"
      "   16 N1000000008 SELECT_TOOL(0)\n"
      "   17 N1000000008 CHANGE_TOOL(0)\n",
      "executing\n");
  EXPECT_EQ(uses_of(run), "M6 T3@3 M61 Q2@7 M6 T0@8 ");
  EXPECT_TRUE(run.problems.empty());
  EXPECT_TRUE(run.unknowns.empty());
}

TEST(InterpreterOutput, shouldKeepEachSpindleStartWithTheToolUsesBeforeIt) {
  const auto run = read(
      "    1 N1000000001 START_SPINDLE_CLOCKWISE(0)\n"
      "    2 N1000000002 SELECT_TOOL(3)\n"
      "    3 N1000000002 CHANGE_TOOL(3)\n"
      "    4 N1000000003 SET_SPINDLE_SPEED(0, 500.0000)\n"
      "    5 N1000000003 START_SPINDLE_COUNTERCLOCKWISE(0)\n"
      "    6 N1000000004 START_SPINDLE_CLOCKWISE(1)\n"
      "    7 N1000000005 ORIENT_SPINDLE(0, 90.0000, 0)\n",
      "executing\n");
  // M3 at S0 turns nothing; S500 with M3 in force does (M4 on the same line then changes nothing).
  ASSERT_EQ(run.spindle_starts.size(), 2u) << "spindle 1 is another spindle";
  EXPECT_EQ(run.spindle_starts[0].where.line, 3);
  EXPECT_EQ(run.spindle_starts[0].before_use, 1u);
  EXPECT_TRUE(run.spindle_starts[0].clockwise);
  EXPECT_DOUBLE_EQ(run.spindle_starts[0].speed, 500.0);
  EXPECT_TRUE(run.spindle_starts[1].orients);
  EXPECT_EQ(run.spindle_starts[1].where.line, 5);
}

/// Where the spindle starts turning: "line:M3|M4:S[:Dmax]" each.
std::string turns_of(const InterpreterRun& run) {
  std::string text;
  for (const SpindleStart& start : run.spindle_starts) {
    char one[96];
    std::snprintf(one, sizeof one, "%d:%s:%g%s ", start.where.line,
                  start.orients ? "M19" : start.clockwise ? "M3" : "M4", start.speed,
                  start.css_maximum != 0.0 ? (":D" + std::to_string(static_cast<int>(start.css_maximum))).c_str() : "");
    text += one;
  }
  return text;
}

TEST(InterpreterOutput, shouldFindEveryWayTheCommandedSpindleSpeedBecomesNonZero) {
  // Captured from rs274 (2.9) of: M3 S0 / G1 X1 F100 / S1000 / G1 X2 S2000 /
  // M5 / S500 / G96 D1000 S100 M3 / G97 / S0 / G96 D1200 S0 / M4 / M5 / M4 S0 / G97 / S300.
  const auto run = read(
      "    7 N1000000001 SET_SPINDLE_SPEED(0, 0.0000)\n"
      "    8 N1000000001 START_SPINDLE_CLOCKWISE(0)\n"
      "    9 N1000000002 STRAIGHT_FEED(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
      "   11 N1000000003 SET_SPINDLE_SPEED(0, 1000.0000)\n"
      "   12 N1000000004 SET_SPINDLE_SPEED(0, 2000.0000)\n"
      "   14 N1000000005 STOP_SPINDLE_TURNING(0)\n"
      "   15 N1000000006 SET_SPINDLE_SPEED(0, 500.0000)\n"
      "   16 N1000000007 SET_SPINDLE_MODE(0 1000.0000)\n"
      "   17 N1000000007 SET_SPINDLE_SPEED(0, 100.0000)\n"
      "   18 N1000000007 START_SPINDLE_CLOCKWISE(0)\n"
      "   19 N1000000008 SET_SPINDLE_MODE(0 0.0000)\n"
      "   20 N1000000009 SET_SPINDLE_SPEED(0, 0.0000)\n"
      "   21 N1000000010 SET_SPINDLE_MODE(0 1200.0000)\n"
      "   22 N1000000010 SET_SPINDLE_SPEED(0, 0.0000)\n"
      "   23 N1000000011 START_SPINDLE_COUNTERCLOCKWISE(0)\n"
      "   24 N1000000012 STOP_SPINDLE_TURNING(0)\n"
      "   25 N1000000013 SET_SPINDLE_SPEED(0, 0.0000)\n"
      "   26 N1000000013 START_SPINDLE_COUNTERCLOCKWISE(0)\n"
      "   27 N1000000014 SET_SPINDLE_MODE(0, 0.0000)\n"
      "   28 N1000000015 SET_SPINDLE_SPEED(0, 300.0000)\n",
      "executing\n");
  // S1000 under M3 S0; S2000 while it turns is no new start; S500 after M5
  // turns nothing; G96 D1000 S100 M3; G97 and S0 stop it; G96 D1200 S0
  // turns it again under the M3 in force, at D (motion runs at D without a
  // surface speed), M4 then is no new start; after M5, M4 S0 under G96 D1200
  // too; G97 (2.10's comma) and S300 keep it turning.
  EXPECT_EQ(turns_of(run), "3:M3:1000 7:M3:100:D1000 10:M3:0:D1200 13:M4:0:D1200 ");
}

TEST(InterpreterOutput, shouldTakeAChangeWithoutItsToolAsLinuxCnc210PrintsIt) {
  // LinuxCNC 2.10's rs274 prints CHANGE_TOOL() with no number: the tool is
  // the one SELECT_TOOL chose (2.9 printed CHANGE_TOOL(7)).
  const auto run = read(
      "   11 N1000000005 SELECT_TOOL(2)\n"
      "   16 N..... CHANGE_TOOL()\n"
      "   17 N1000000006 SELECT_TOOL(7)\n"
      "   22 N..... CHANGE_TOOL()\n",
      "");
  EXPECT_EQ(uses_of(run), "M6 T2@5 M6 T7@6 ");
  EXPECT_TRUE(run.problems.empty());
}

TEST(InterpreterOutput, shouldReadTheToolNumberOfAnM61FromItsRow) {
  // The table's rows: tool 12 is on row 3; rs274 names the row.
  const auto run = read("  7 N1000000001 CHANGE_TOOL_NUMBER(3)\n", "", {}, {0, 1, 7, 12});
  EXPECT_EQ(uses_of(run), "M61 Q12@1 ");
}

TEST(InterpreterOutput, shouldReadLineNumbersOfSixDigitsAndMore) {
  const auto run = read("   11 N1000123456SELECT_TOOL(2)\n   14 N1000123456CHANGE_TOOL(2)\n", "");
  EXPECT_EQ(uses_of(run), "M6 T2@123456 ");
}

TEST(InterpreterOutput, shouldShowAChangeInASubroutineFileWithoutALine) {
  // A subroutine file's own N words are no line numbers of the program.
  const auto run = read("  7 N0080  SELECT_TOOL(1)\n  8 N..... CHANGE_TOOL(1)\n", "");
  EXPECT_EQ(uses_of(run), "M6 T1@0 ");
}

TEST(InterpreterOutput, shouldReportAnErrorOnItsLine) {
  const auto run = read("",
                        "executing\n"
                        "Requested tool 99 not found in the tool table\n"
                        "N1000000005 T99 M6\n"
                        "Bad character '\\173' used\n"
                        "/N1000000007 G0 X1 {\n");
  ASSERT_EQ(run.problems.size(), 2u);
  EXPECT_EQ(run.problems[0].where.line, 5);
  EXPECT_EQ(run.problems[0].text,
            "LinuxCNC stops the program here: Requested tool 99 not found in the tool table");
  EXPECT_EQ(run.problems[1].where.line, 7);
}

TEST(InterpreterOutput, shouldNameTheProgramWhereAMessageNamesTheCopy) {
  const auto run = read("",
                        "EOF in file:/tmp/x/program.ngc seeking o-word: o<s> from line: 13\n"
                        "N1000000017 M2\n");
  ASSERT_EQ(run.problems.size(), 1u);
  EXPECT_EQ(run.problems[0].text,
            "LinuxCNC stops the program here: EOF in file:p.ngc seeking o-word: o<s> from line: "
            "13");
}

TEST(InterpreterOutput, shouldQuoteTheLineOfAnErrorInASubroutineFile) {
  const auto run = read("", "Unknown m code used\nM123\n");
  ASSERT_EQ(run.problems.size(), 1u);
  EXPECT_EQ(run.problems[0].where.line, 0);
  EXPECT_EQ(run.problems[0].text,
            "LinuxCNC stops the program here: Unknown m code used (at \"M123\")");
}

TEST(InterpreterOutput, shouldReportAProgramWithoutAnEndOnItsLastLine) {
  // p.ngc has 1000000 lines: line 1000001 is the M2 number_lines added.
  const auto run = read("  7 N1000000003 SELECT_TOOL(1)\n  8 N1001000001 PROGRAM_END()\n", "");
  ASSERT_EQ(run.problems.size(), 1u);
  EXPECT_EQ(run.problems[0].where.line, 1000000);
  EXPECT_EQ(run.problems[0].text,
            "LinuxCNC stops the program here: File ended with no percent sign or program end");
}

TEST(InterpreterOutput, shouldReportAnM6WithoutAnyT) {
  const auto run = read("  9 N1000000003 CHANGE_TOOL(0)\n", "");
  EXPECT_EQ(uses_of(run), "M6 T?@3 ");
  ASSERT_EQ(run.problems.size(), 1u);
  EXPECT_EQ(run.problems[0].text, "M6 without a T word since the start");
}

TEST(InterpreterOutput, shouldSayAHalPinIsNotKnownAndKeepItsChange) {
  const auto run = read(
      "  7 N1000000001 SELECT_TOOL(1)\n  8 N1000000001 CHANGE_TOOL(1)\n"
      "  9 N1000000004 SELECT_TOOL(2)\n 10 N1000000004 CHANGE_TOOL(2)\n",
      "Named parameter #<_hal[fixed_atc_probe.number]> not defined\n"
      "N1000000002 T[#<_hal[fixed_atc_probe.number]>] M6 (the operator's choice)\n");
  EXPECT_EQ(uses_of(run), "M6 T1@1 M6 T?@2 M6 T2@4 ");
  EXPECT_TRUE(run.problems.empty());
  ASSERT_EQ(run.unknowns.size(), 1u);
  EXPECT_EQ(run.unknowns[0].where.line, 2);
  EXPECT_EQ(run.unknowns[0].text,
            "Named parameter #<_hal[fixed_atc_probe.number]> not defined: a HAL pin, read only "
            "when the program runs on the machine: what the line does is not known");
}

TEST(InterpreterOutput, shouldSayAToolReadFromAnM66InputIsNotKnown) {
  const auto run = read("  8 N1000000002 SELECT_TOOL(0)\n  9 N..... CHANGE_TOOL(0)\n", "", {2});
  EXPECT_EQ(uses_of(run), "M6 T?@2 ");
  ASSERT_EQ(run.unknowns.size(), 1u);
  EXPECT_EQ(run.unknowns[0].text,
            "the tool number reads #5399, the input M66 waited for: known only when the program "
            "runs on the machine (rs274 reads 0)");
}

TEST(InterpreterOutput, shouldKeepAtMostTheFirstTenThousandUses) {
  InterpreterOutput output(given({}, 1000), sim_rows());
  for (int i = 0; i < 10005; ++i) output.canonical_call("  1 N1000000001 CHANGE_TOOL_NUMBER(1)");
  const auto run = output.finish();
  EXPECT_EQ(run.uses.size(), kMaxToolUses);
  EXPECT_EQ(run.uses_not_kept, 5u);
}

TEST(InterpreterOutput, shouldStopAtTheErrorAfterAThousand) {
  InterpreterOutput output(given({}, 1000), sim_rows());
  for (int i = 0; i < 1500; ++i) {
    output.error_line("Bad character '{' used");
    output.error_line("N" + std::to_string(1000000001 + i) + " {");
  }
  EXPECT_TRUE(output.done());
  const auto run = output.finish();
  ASSERT_EQ(run.problems.size(), kMaxErrors + 1);
  EXPECT_EQ(run.problems.back().where.line, 0);
  EXPECT_EQ(run.problems.back().text,
            "more than 1000 errors: LinuxCNC's interpreter (rs274) was stopped at line 1000; "
            "tool changes after that are not known");
}

TEST(InterpreterOutput, shouldSayAnUndefinedSubroutineAsLinuxCncSaysItOfTheProgram) {
  // The call found its empty file in the stub folder: rs274 stopped at once, on the call's line.
  const auto run = read("",
                        "EOF in file:/tmp/x/undefined/nosuch.ngc seeking o-word: o<nosuch> from "
                        "line: 0\n"
                        "N1000000012 o<nosuch> call [1]\n"
                        "EOF in file:/tmp/x/undefined/deeper.ngc seeking o-word: o<deeper> from "
                        "line: 0\n"
                        "o<deeper> call\n");
  ASSERT_EQ(run.problems.size(), 2u);
  EXPECT_EQ(run.problems[0].where.line, 12);
  EXPECT_EQ(run.problems[0].text,
            "LinuxCNC stops the program here: EOF in file:p.ngc seeking o-word: o<nosuch> from "
            "line: 12");
  // In a subroutine file of the program's: no line of the program.
  EXPECT_EQ(run.problems[1].text,
            "LinuxCNC stops the program here: EOF seeking o-word: o<deeper> (at \"o<deeper> "
            "call\")");
}

TEST(InterpreterOutput, shouldKeepAtMostTenThousandUsesWithTheChangesOfLinesNotRun) {
  InterpreterOutput output(given({}, 100000), sim_rows());
  for (int i = 1; i <= 6000; ++i) {
    const std::string n = std::to_string(1000000000 + 2 * i);
    output.canonical_call("  1 N" + n + " SELECT_TOOL(1)");
    output.canonical_call("  2 N" + n + " CHANGE_TOOL(1)");
    output.error_line("Named parameter #<_hal[x]> not defined");
    output.error_line("N" + std::to_string(1000000000 + 2 * i + 1) + " T#<_hal[x]> M6");
  }
  const auto run = output.finish();
  ASSERT_EQ(run.uses.size(), kMaxToolUses);
  EXPECT_EQ(run.uses_not_kept, 2000u);
  // Each change of a line not run between the uses before and after it.
  for (std::size_t i = 1; i < run.uses.size(); ++i) {
    ASSERT_LE(run.uses[i - 1].where.line, run.uses[i].where.line) << i;
  }
  EXPECT_FALSE(run.uses[1].tool);
  EXPECT_EQ(run.uses[1].where.line, 3);
}

TEST(InterpreterOutput, shouldSayAnInputLineOnceWhateverTheLoopsAndKeepAThousand) {
  std::vector<int> input_lines;
  for (int line = 1; line <= 2000; ++line) input_lines.push_back(line);
  InterpreterOutput output(given(input_lines, 2000), sim_rows());
  for (int pass = 0; pass < 3; ++pass) {
    for (int line = 1; line <= 2000; ++line) {
      output.canonical_call("  1 N" + std::to_string(1000000000 + line) + " SELECT_TOOL(0)");
    }
  }
  const auto run = output.finish();
  EXPECT_EQ(run.unknowns.size(), kMaxErrors);
  EXPECT_EQ(run.unknowns.back().where.line, 1000);
}

TEST(HoldsM6, shouldFindAnM6WordOutsideCommentsAndNames) {
  EXPECT_TRUE(holds_m6("T[#<_hal[x]>] M6"));
  EXPECT_TRUE(holds_m6("t#<t> m 0 6 g43"));
  EXPECT_TRUE(holds_m6("M6"));
  EXPECT_FALSE(holds_m6("M61 Q#<_hal[x]>"));
  EXPECT_FALSE(holds_m6("G0 X1 (M6 later)"));
  EXPECT_FALSE(holds_m6("#<m6> = #<_hal[x]> ; M6"));
  EXPECT_FALSE(holds_m6("M6.5"));
}

/// What a LineNumberer makes of `text` fed in pieces of `piece` bytes.
struct Numbered {
  std::string text;
  LineNumberer numberer;
};
Numbered number(std::string_view text, std::size_t piece = 1000000, bool cut = false) {
  Numbered numbered;
  for (std::size_t at = 0; at < text.size(); at += piece) {
    numbered.numberer.add(text.substr(at, piece));
    numbered.text += numbered.numberer.take_text();
  }
  numbered.numberer.finish(cut);
  numbered.text += numbered.numberer.take_text();
  return numbered;
}

TEST(LineNumberer, shouldStartEachLineOfCodeWithItsNumber) {
  const std::string program =
      "%\n(comment)\n\n  N10 T1 M6\r\n/T2 M6\n n 2 0 . 5 M61 Q4\nT#5399 M6\n#<t> = # 5399.5\n%\n";
  // The same whatever the pieces the file is read in.
  for (const std::size_t piece : {std::size_t{1}, std::size_t{7}, program.size()}) {
    const auto numbered = number(program, piece);
    EXPECT_EQ(numbered.text,
              "%\nN1000000002 (comment)\n\n  N1000000004 T1 M6\r\n/N1000000005 T2 M6\n"
              " N1000000006 M61 Q4\nN1000000007 T#5399 M6\nN1000000008 #<t> = # 5399.5\n%\n"
              "N1000000010 M2\n")
        << piece;
    EXPECT_TRUE(numbered.numberer.input_lines().contains(7));
    EXPECT_FALSE(numbered.numberer.input_lines().contains(8));
    EXPECT_EQ(numbered.numberer.lines(), 9);
    EXPECT_EQ(numbered.numberer.bytes(), program.size());
    EXPECT_FALSE(numbered.numberer.nul());
  }
  EXPECT_EQ(line_of("/N1000000005 T2 M6"), 5);
  EXPECT_EQ(line_of("N0080 T1 M6"), 0);
  EXPECT_EQ(line_of("G0 X1"), 0);
}

TEST(LineNumberer, shouldLeaveALineTooLongToNumberAsItWas) {
  const std::string longest(kMaxLineLength - 12, 'X');
  const std::string too_long(kMaxLineLength - 11, 'X');
  EXPECT_EQ(number(longest).text, "N1000000001 " + longest + "\nN1000000002 M2\n");
  EXPECT_EQ(number(too_long).text, too_long + "\nN1000000002 M2\n");
}

TEST(LineNumberer, shouldPassOnAHugeLineWithoutKeepingIt) {
  LineNumberer numberer;
  numberer.add("T1 M6\nG0 X");
  std::size_t passed = numberer.take_text().size();
  for (int i = 0; i < 1000; ++i) {
    numberer.add(std::string(1000, '1'));
    EXPECT_LE(numberer.text_size(), 1000u + kMaxLineLength);
    passed += numberer.take_text().size();
  }
  numberer.add("\nM2\n");
  numberer.finish(false);
  EXPECT_EQ(numberer.take_text(), "\nN1000000003 M2\nN1000000004 M2\n");
  // Numbered all the same: LinuxCNC refuses it and prints its start, which names the line.
  EXPECT_EQ(passed, std::string("N1000000001 T1 M6\nN1000000002 G0 X").size() + 1000000);
  EXPECT_EQ(numberer.lines(), 3);
}

TEST(LineNumberer, shouldDropTheLastLineOfACutFile) {
  const auto numbered = number("T1 M6\nT2 M6\nT3", 4, true);
  EXPECT_EQ(numbered.text, "N1000000001 T1 M6\nN1000000002 T2 M6\nN1000000003 M2\n");
  EXPECT_EQ(numbered.numberer.bytes(), 12u);
  EXPECT_EQ(numbered.numberer.lines(), 2);
}

TEST(LineNumberer, shouldRefuseATextWithANulByteInAnyPiece) {
  for (const std::size_t piece : {std::size_t{1}, std::size_t{8}, std::size_t{100}}) {
    const auto numbered = number(std::string("T1 M6\nG0\0 X2\n", 13), piece);
    ASSERT_TRUE(numbered.numberer.nul()) << piece;
    EXPECT_EQ(numbered.numberer.nul()->line, 2);
    EXPECT_EQ(numbered.numberer.nul()->text,
              "NUL byte at column 3: not a G-code text file (LinuxCNC stops reading a line at a "
              "NUL); nothing of it read");
  }
}

TEST(LineNumberer, shouldListTheSubroutinesTheProgramCallsAndNeverDefines) {
  const auto numbered = number(
      "o<Defined> sub\no<defined> endsub\n"
      "o<defined> call\nO< No Such > CALL [1]\n(o<in_comment> call)\n/N20 o<two> call\n"
      "o100 call\no200 sub\no200 endsub\no200 call\n"
      "o<../../etc/passwd> call\no<$(reboot)> call\no<.hidden> call\no<later> call\n"
      "o<later> sub\no<later> endsub\nM2\n");
  EXPECT_EQ(numbered.numberer.undefined_calls(),
            (std::vector<std::string>{"100", "nosuch", "two"}));
}

TEST(LineNumberer, shouldNoteBeforeALineThatMayRunASubroutineThatItDoes) {
  // An o-call and an M-code an INI may remap; not LinuxCNC's own M-codes,
  // nor a parameter named like one. The note goes under block delete with its line.
  const std::string note = "(" + std::string(kRunsSubroutine) + ")\n";
  EXPECT_EQ(number("M3 S1000\nM310\no<x> call\n/M101 P1\n#<_m310> = 1\nM5 M9\nM2\n").text,
            "N1000000001 M3 S1000\nN1000000002 " + note + "N1000000002 M310\nN1000000003 " + note +
                "N1000000003 o<x> call\n/N1000000004 " + note +
                "/N1000000004 M101 P1\nN1000000005 #<_m310> = 1\nN1000000006 M5 M9\n"
                "N1000000007 M2\nN1000000008 M2\n");
}

TEST(InterpreterOutput, shouldShowASubroutinesCallsOnTheLineThatRunsIt) {
  // M3 on line 1, M310 on line 2 runs the remap's subroutine: its calls are line 2's.
  struct Heard : CallListener {
    std::vector<std::pair<int, std::string>> calls;
    void call(int line, bool, std::string_view call) override { calls.emplace_back(line, call); }
    void tool_use(const ToolUse&) override {}
  } heard;
  ProgramGiven given;
  given.name = "p.ngc";
  given.lines = 3;
  InterpreterOutput output(given, {0});
  output.listen(&heard);
  output.canonical_call("  7 N1000000001 START_SPINDLE_CLOCKWISE(0)");
  output.canonical_call("  8 N1000000002 COMMENT(\"" + std::string(kRunsSubroutine) + "\")");
  output.canonical_call("  9 N..... COMMENT(\"Releases\")");
  EXPECT_EQ(heard.calls, (std::vector<std::pair<int, std::string>>{
                             {1, "START_SPINDLE_CLOCKWISE(0)"}, {2, "COMMENT(\"Releases\")"}}));
}

TEST(LineSet, shouldHoldTheLinesInsertedOnly) {
  LineSet lines;
  lines.insert(5);
  lines.insert(1000000);
  lines.insert(-1);
  EXPECT_TRUE(lines.contains(5));
  EXPECT_TRUE(lines.contains(1000000));
  EXPECT_FALSE(lines.contains(6));
  EXPECT_FALSE(lines.contains(-1));
  EXPECT_FALSE(lines.contains(2000000));
}

TEST(InterpreterTable, shouldListEachToolOnceWithItsLengthsAndDiameterInInches) {
  const ToolTable table = parse_tool_table(
      "T7 P2 Z20.32 D2.54 ;c\nT1 P5 X2.54 Z25.4 D25.4 A90\nT0 P0\nT4 P4 Zabc\nT1 P6 Z31\n");
  const auto given = interpreter_table(table, 1.0 / 25.4);
  EXPECT_EQ(given.text, "T1 P5 X0.1 Z1 D1 A90\nT7 P2 Z0.8 D0.1\n");
  EXPECT_EQ(given.tool_of_row, (std::vector<int>{0, 1, 7}));
  const auto any = any_tool_table();
  EXPECT_EQ(any.tool_of_row.size(), static_cast<std::size_t>(kToolsWithoutTable + 1));
  EXPECT_EQ(any.tool_of_row[42], 42);
}

TEST(InterpreterIni, shouldPutHalPinsOffAndTheSubroutineFoldersFirstInTheSectionOneALine) {
  EXPECT_EQ(
      ini_for_preflight("[EMC]\nA = 1\n[RS274NGC]\nHAL_PIN_VARS = 1\nSUBROUTINE_PATH = b\n",
                        "/a:b"),
      "[EMC]\nA = 1\n[RS274NGC]\nHAL_PIN_VARS = 0\nSUBROUTINE_PATH = /a:\\\nb\nHAL_PIN_VARS = "
      "1\nSUBROUTINE_PATH = b\n");
  EXPECT_EQ(ini_for_preflight("[EMC]\nA = 1", "/a"),
            "[EMC]\nA = 1\n[RS274NGC]\nHAL_PIN_VARS = 0\nSUBROUTINE_PATH = /a\n");
  EXPECT_EQ(ini_for_preflight("[RS274NGC]\n", ""), "[RS274NGC]\nHAL_PIN_VARS = 0\n");
}

TEST(InterpreterIni, shouldPutTheUserMCodesModuleFirstInThePythonSection) {
  EXPECT_EQ(ini_for_preflight("[PYTHON]\nTOPLEVEL = mine.py\n[RS274NGC]\n", "", "/s/user_m.py"),
            "[PYTHON]\nTOPLEVEL = /s/user_m.py\nTOPLEVEL = mine.py\n[RS274NGC]\nHAL_PIN_VARS = 0\n");
  EXPECT_EQ(ini_for_preflight("[EMC]\n", "", "/s/user_m.py"),
            "[EMC]\n[RS274NGC]\nHAL_PIN_VARS = 0\n[PYTHON]\nTOPLEVEL = /s/user_m.py\n");
  const std::string module = user_m_code_module({101, 150}, std::string("py/top'.py"));
  EXPECT_NE(module.find("for _fatc_code in (101, 150, ):"), std::string::npos) << module;
  // The INI's own TOPLEVEL runs after, its path whatever bytes it has.
  EXPECT_NE(module.find("_fatc_own = b'\\x70\\x79\\x2f\\x74\\x6f\\x70\\x27\\x2e\\x70\\x79'"),
            std::string::npos)
      << module;
  EXPECT_EQ(user_m_code_module({101}, std::nullopt).find("_fatc_own"), std::string::npos);
}

}  // namespace
}  // namespace fatc::program
