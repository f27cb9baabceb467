// The rack map in the tool table's P column (issue 34): with_rack_pockets on
// tables as LinuxCNC writes them and as operators type them, on a rack of
// five pockets where tools and pockets differ (T12 in 1, T7 in 2, 3 free,
// T3 in 4 and in the spindle, T20 from outside loaded into 5).
#include "core/program/tool_table.hpp"

#include <gtest/gtest.h>

namespace fatc {
namespace {

ToolState rack() {
  ToolState tools;
  tools.pockets = {
      {1, {12, true}}, {2, {7, true}}, {3, {0, false}}, {4, {3, false}}, {5, {20, true}}};
  tools.spindle = 3;
  return tools;
}

// LinuxCNC's tooldata_save: "T%-3d P%-3d", signed lengths, " ;comment".
const char* const kSaved =
    "T3   P3   D+10.000000 Z+40.000000 ;10mm face mill\n"
    "T7   P7   D+2.000000 Z+20.000000 ;2mm end mill\n"
    "T12  P12  D+6.000000 Z+30.000000 ;6mm end mill\n"
    "T20  P20  D+4.000000 Z+41.250000 ;4mm end mill\n";

TEST(RackPockets, shouldWriteEachRackToolsPocketAndKeepEverythingElseWhenLinuxCncSavedTheTable) {
  const PocketRewrite rewrite = with_rack_pockets(kSaved, rack());
  EXPECT_EQ(rewrite.text,
            "T3   P4   D+10.000000 Z+40.000000 ;10mm face mill\n"
            "T7   P2   D+2.000000 Z+20.000000 ;2mm end mill\n"
            "T12  P1  D+6.000000 Z+30.000000 ;6mm end mill\n"
            "T20  P5  D+4.000000 Z+41.250000 ;4mm end mill\n");
  const std::vector<PocketChange> expected = {{3, 3, 4}, {7, 7, 2}, {12, 12, 1}, {20, 20, 5}};
  EXPECT_EQ(rewrite.changes, expected);
}

TEST(RackPockets, shouldChangeNothingWhenEveryPMatchesTheRack) {
  const std::string text = with_rack_pockets(kSaved, rack()).text;
  const PocketRewrite again = with_rack_pockets(text, rack());
  EXPECT_EQ(again.text, text);
  EXPECT_TRUE(again.changes.empty());
}

TEST(RackPockets, shouldGiveTheToolInTheSpindleItsOwnPocketWhenItBelongsInOne) {
  ToolState tools = rack();
  tools.put_in_spindle(12);
  EXPECT_EQ(with_rack_pockets("T12 P12 Z30\n", tools).text, "T12 P1 Z30\n");
}

TEST(RackPockets, shouldAddPAfterTheToolWhenTheLineHasNone) {
  const PocketRewrite rewrite = with_rack_pockets("t7 z20.0 ; no pocket\n", rack());
  EXPECT_EQ(rewrite.text, "t7 P2 z20.0 ; no pocket\n");
  ASSERT_EQ(rewrite.changes.size(), 1u);
  EXPECT_FALSE(rewrite.changes[0].was);
}

TEST(RackPockets, shouldSetPZeroWhenAToolOutsideTheRackNamesOneOfItsPockets) {
  // T9 (manual) says pocket 2, where T7 belongs; T30's P30 is no pocket of the rack.
  const PocketRewrite rewrite = with_rack_pockets("T9 P2 Z15\nT30 P30 Z12\nT31 Z11\n", rack());
  EXPECT_EQ(rewrite.text, "T9 P0 Z15\nT30 P30 Z12\nT31 Z11\n");
  const std::vector<PocketChange> expected = {{9, 2, 0}};
  EXPECT_EQ(rewrite.changes, expected);
  const std::map<int, std::optional<int>> p_of = {{9, 0}, {30, 30}, {31, std::nullopt}};
  EXPECT_EQ(rewrite.p_of, p_of);
}

TEST(RackPockets, shouldAddNoLineWhenARackToolIsNotInTheTable) {
  const PocketRewrite rewrite = with_rack_pockets("T3 P3 Z40\n", rack());
  EXPECT_EQ(rewrite.text, "T3 P4 Z40\n");
  EXPECT_EQ(rewrite.changes.size(), 1u);
}

TEST(RackPockets, shouldKeepCommentsBlankLinesOrderAndLinesLinuxCncSkipsByteForByte) {
  const std::string text =
      ";rack tools first\r\n"
      "\n"
      "T20 P3 Z41 ;P5 in the comment stays\r\n"
      "T7 P2 K9\n"    // LinuxCNC skips the line: no K field
      "T12 PX Z30\n"  // P is no number: skipped
      "T3 Z40 P3";    // P last, no newline at the end
  EXPECT_EQ(with_rack_pockets(text, rack()).text,
            ";rack tools first\r\n"
            "\n"
            "T20 P5 Z41 ;P5 in the comment stays\r\n"
            "T7 P2 K9\n"
            "T12 PX Z30\n"
            "T3 Z40 P4");
}

TEST(RackPockets, shouldMendEveryLineOfAToolListedTwice) {
  EXPECT_EQ(with_rack_pockets("T7 P7 Z20\nT7 P8 Z21\n", rack()).text, "T7 P2 Z20\nT7 P2 Z21\n");
}

TEST(RackPockets, shouldNameToolWhatTheTableSaidAndHowToMoveAToolWhenTheyDisagree) {
  const std::string words =
      pocket_disagreement_words({{3, 7, 4}, {9, 2, 0}, {12, std::nullopt, 1}});
  EXPECT_NE(words.find("tool 3 is in pocket 4 (the table said P7)"), std::string::npos) << words;
  EXPECT_NE(words.find("tool 9 is in no pocket of the rack (the table said P2)"),
            std::string::npos);
  EXPECT_NE(words.find("tool 12 is in pocket 1 (the table said no P)"), std::string::npos);
  EXPECT_NE(words.find("unload it, then load it with the Pocket box"), std::string::npos);
}

}  // namespace
}  // namespace fatc
