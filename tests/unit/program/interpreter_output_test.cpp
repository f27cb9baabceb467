// What rs274 prints, read into tool uses, problems and what is not known:
// each test feeds text captured from rs274 (LinuxCNC 2.9) over a program
// numbered by number_lines.
#include "core/program/interpreter_output.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "core/program/interpreter_inputs.hpp"
#include "core/program/numbered_program.hpp"

namespace fatc::program {
namespace {

/// Rows 1-7 hold tools 1-7, as config/sim/sim.tbl.
std::vector<int> sim_rows() { return {0, 1, 2, 3, 4, 5, 6, 7}; }

InterpreterRun read(const std::string& out, const std::string& err,
                    std::vector<int> input_lines = {}, std::vector<int> rows = sim_rows()) {
  InterpreterOutput output("p.ngc", "/tmp/x/program.ngc", std::move(rows), std::move(input_lines),
                           1000000);
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
  InterpreterOutput output("p.ngc", "", sim_rows(), {}, 1000);
  for (int i = 0; i < 10005; ++i) output.canonical_call("  1 N1000000001 CHANGE_TOOL_NUMBER(1)");
  const auto run = output.finish();
  EXPECT_EQ(run.uses.size(), kMaxToolUses);
  EXPECT_EQ(run.uses_not_kept, 5u);
}

TEST(InterpreterOutput, shouldCountErrorsBeyondAThousand) {
  InterpreterOutput output("p.ngc", "", sim_rows(), {}, 1000);
  for (int i = 0; i < 1500; ++i) {
    output.error_line("Bad character '{' used");
    output.error_line("N1000000001 {");
  }
  const auto run = output.finish();
  ASSERT_EQ(run.problems.size(), kMaxErrors + 1);
  EXPECT_EQ(run.problems.back().text, "500 more errors of the interpreter, not listed");
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

TEST(NumberLines, shouldStartEachLineOfCodeWithItsNumber) {
  const auto numbered = number_lines(
      "%\n(comment)\n\n  N10 T1 M6\r\n/T2 M6\n n 2 0 . 5 M61 Q4\nT#5399 M6\n#<t> = # 5399.5\n%\n");
  EXPECT_EQ(numbered.text,
            "%\nN1000000002 (comment)\n\n  N1000000004 T1 M6\r\n/N1000000005 T2 M6\n"
            " N1000000006 M61 Q4\nN1000000007 T#5399 M6\nN1000000008 #<t> = # 5399.5\n%\n"
            "N1000000010 M2\n");
  EXPECT_EQ(numbered.input_lines, std::vector<int>{7});
  EXPECT_TRUE(numbered.problems.empty());
  EXPECT_EQ(line_of("/N1000000005 T2 M6"), 5);
  EXPECT_EQ(line_of("N0080 T1 M6"), 0);
  EXPECT_EQ(line_of("G0 X1"), 0);
}

TEST(NumberLines, shouldLeaveALineTooLongToNumberAsItWas) {
  const std::string longest(kMaxLineLength - 12, 'X');
  const std::string too_long(kMaxLineLength - 11, 'X');
  EXPECT_EQ(number_lines(longest).text, "N1000000001 " + longest + "\nN1000000002 M2\n");
  EXPECT_EQ(number_lines(too_long).text, too_long + "\nN1000000002 M2\n");
}

TEST(NumberLines, shouldRefuseATextWithANulByte) {
  const auto numbered = number_lines(std::string("T1 M6\nG0\0 X2\n", 13));
  EXPECT_EQ(numbered.text, "");
  ASSERT_EQ(numbered.problems.size(), 1u);
  EXPECT_EQ(numbered.problems[0].line, 2);
  EXPECT_EQ(numbered.problems[0].text,
            "NUL byte at column 3: not a G-code text file (LinuxCNC stops reading a line at a "
            "NUL); nothing of it read");
}

TEST(InterpreterTable, shouldListEachToolOnceWithItsDiameterInInches) {
  const ToolTable table = parse_tool_table(
      "T7 P2 Z20 D2.54 ;c\nT1 P5 Z30.0 D25.4\nT0 P0\nT4 P4 Zabc\nT1 P6 Z31\n");
  const auto given = interpreter_table(table, 1.0 / 25.4);
  EXPECT_EQ(given.text, "T1 P5 Z30.0 D1\nT7 P2 Z20 D0.1\n");
  EXPECT_EQ(given.tool_of_row, (std::vector<int>{0, 1, 7}));
  const auto any = any_tool_table();
  EXPECT_EQ(any.tool_of_row.size(), static_cast<std::size_t>(kToolsWithoutTable + 1));
  EXPECT_EQ(any.tool_of_row[42], 42);
}

TEST(InterpreterIni, shouldPutHalPinsOffAndTheSubroutineFoldersFirstInTheSection) {
  EXPECT_EQ(ini_for_preflight("[EMC]\nA = 1\n[RS274NGC]\nHAL_PIN_VARS = 1\nSUBROUTINE_PATH = b\n",
                              "/a:b"),
            "[EMC]\nA = 1\n[RS274NGC]\nHAL_PIN_VARS = 0\nSUBROUTINE_PATH = /a:b\nHAL_PIN_VARS = "
            "1\nSUBROUTINE_PATH = b\n");
  EXPECT_EQ(ini_for_preflight("[EMC]\nA = 1", "/a"),
            "[EMC]\nA = 1\n[RS274NGC]\nHAL_PIN_VARS = 0\nSUBROUTINE_PATH = /a\n");
  EXPECT_EQ(ini_for_preflight("[RS274NGC]\n", ""), "[RS274NGC]\nHAL_PIN_VARS = 0\n");
}

}  // namespace
}  // namespace fatc::program
