// What the command line prints passes through CappedLines: no line longer
// than 400 characters and none that acts on the terminal, whatever a file
// held; a list of a file's problems is capped and the rest counted.
#include "io/capped_lines.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

namespace fatc::io {
namespace {

TEST(TerminalSafe, shouldShowEveryControlCharacterButTabAndNewline) {
  EXPECT_EQ(terminal_safe("a\tb\n"), "a\tb\n");
  EXPECT_EQ(terminal_safe("\x1b[2J\x1b]0;title\x07"), "\\x1b[2J\\x1b]0;title\\x07");
  EXPECT_EQ(terminal_safe("over\rwritten\b\x7f"), "over\\rwritten\\x08\\x7f");
  EXPECT_EQ(terminal_safe(std::string("nul\0byte", 8)), "nul\\x00byte");
}

TEST(TerminalSafe, shouldShowC1ControlsAndBytesThatAreNotUtf8) {
  // U+009B is CSI on a terminal that reads C1 controls; a lone 0x9B is CSI on an 8-bit one.
  EXPECT_EQ(terminal_safe(std::string("\xc2\x9b") + "31m"), "\\u{009b}31m");
  EXPECT_EQ(terminal_safe("\xc2\x85next"), "\\u{0085}next");
  EXPECT_EQ(terminal_safe(std::string("\x9b") + "31m \xff"), "\\x9b31m \\xff");
  EXPECT_EQ(terminal_safe("\xe2\x80\xa6 \xc3\xa9 \xc2\xa0 \xf0\x9f\x94\xa7"),
            "\xe2\x80\xa6 \xc3\xa9 \xc2\xa0 \xf0\x9f\x94\xa7")
      << "letters and symbols beyond ASCII are left as they are";
}

TEST(CappedLines, shouldMakeEachLineTerminalSafeBeforeCuttingIt) {
  std::ostringstream printed;
  {
    CappedLines lines(printed);
    std::ostream out(&lines);
    out << "config.json: units: got \"\x1b[31mmm\"\n" << std::string(500, '\x01') << "\n";
  }
  const std::string text = printed.str();
  EXPECT_EQ(text.substr(0, text.find('\n') + 1), "config.json: units: got \"\\x1b[31mmm\"\n");
  EXPECT_EQ(text.find('\x01'), std::string::npos);
  const std::string second = text.substr(text.find('\n') + 1);
  EXPECT_EQ(second.rfind("\\x01\\x01", 0), 0u);
  EXPECT_EQ(second.size(), 399u + std::string("\u2026\n").size()) << "cut after it was made visible";
}

TEST(PrintCapped, shouldListTheFirstFiftyAndCountTheRest) {
  std::vector<std::string> lines;
  for (int i = 1; i <= 100000; ++i) lines.push_back("line " + std::to_string(i) + ": tool 1 again");
  std::ostringstream out;
  print_capped(out, lines);
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 51);
  EXPECT_EQ(text.substr(0, 23), "  line 1: tool 1 again\n");
  EXPECT_NE(text.find("  line 50: tool 1 again\n  ... and 99950 more\n"), std::string::npos);
}

TEST(PrintCapped, shouldListAShortListWhole) {
  std::ostringstream out;
  print_capped(out, {"one", "two"});
  EXPECT_EQ(out.str(), "  one\n  two\n");
  std::ostringstream none;
  print_capped(none, {});
  EXPECT_EQ(none.str(), "");
}

}  // namespace
}  // namespace fatc::io
