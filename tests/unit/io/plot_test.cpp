// --plot: the rack from above as SVG, from the config and the tool state, and
// the path of one change.
#include "io/plot.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "cli_run.hpp"
#include "core/config/quote.hpp"
#include "core/dry_run/simulator.hpp"
#include "temp_folder.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::valid_config;

long count(const std::string& text, const std::string& part) {
  long n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST(Plot, shouldDrawEveryPocketWithItsToolKeepOutAndApproach) {
  const Config config = valid_config();
  const std::string svg = io::rack_svg(config, ToolState::fresh(config), nullptr, "the rack");
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  for (int n = 1; n <= 6; ++n) {
    EXPECT_NE(svg.find(">pocket " + std::to_string(n) + "</text>"), std::string::npos) << n;
    EXPECT_NE(svg.find(">T" + std::to_string(n) + "</text>"), std::string::npos) << n;
  }
  EXPECT_EQ(count(svg, "stroke-dasharray=\"4 3\""), 6) << "one keep-out square a pocket";
  EXPECT_EQ(count(svg, "marker-end=\"url(#arrow)\""), 6) << "one side approach a pocket";
  for (const char* station : {">safe</text>", ">loading</text>", ">touch-off sensor</text>"}) {
    EXPECT_NE(svg.find(station), std::string::npos) << station;
  }
}

TEST(Plot, shouldShowWhereEachToolIsAndTopPockets) {
  const std::string side = R"("pocket_default": {"y": 20.0, "z": -80.0})";
  std::string text = test::kValidConfig;
  text.replace(text.find(side), side.size(),
               R"("pocket_default": {"y": 20.0, "z": -80.0, "approach": "top"})");
  const Config config = parse_config(text).config.value();
  ToolState tools = ToolState::fresh(config);
  tools.put_in_spindle(2);
  const std::string svg = io::rack_svg(config, tools, nullptr, "A & <B>");
  EXPECT_NE(svg.find(">T2 (spindle), top</text>"), std::string::npos) << svg;
  EXPECT_NE(svg.find(">T1, top</text>"), std::string::npos);
  EXPECT_EQ(count(svg, "marker-end"), 0) << "no side approach to draw";
  EXPECT_NE(svg.find(">A &amp; &lt;B&gt;</text>"), std::string::npos) << "the title escaped";
}

TEST(Plot, shouldDrawTheChangesMovesInXYSlowOnesApart) {
  const Config config = valid_config();
  const Simulator change = plan_change(config, 1, 2, -70.0);
  const std::string svg = io::rack_svg(config, ToolState::fresh(config), &change, "M6 T2");
  // Six approach arrows, and the change's moves in XY: two slow ones (into
  // pocket 1, out of pocket 2), the rest rapids.
  EXPECT_EQ(count(svg, "stroke=\"#c00\""), 2) << svg;
  EXPECT_GE(count(svg, "stroke=\"#36c\""), 4);
  EXPECT_NE(svg.find("The change: blue dashed rapids, red solid slow moves"), std::string::npos);
}

TEST(Plot, shouldWriteTheFileAndSayWhatItDrew) {
  const std::string path = ::testing::TempDir() + "fatc_rack.svg";
  const auto r = test::run_cli({"--plot", path, "--config", FATC_SOURCE_DIR "/config/config.json",
                                "--from", "2", "--to", "5"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find(": 6 pockets, and the path of the change\n"), std::string::npos) << r.out;
  std::ostringstream written;
  written << std::ifstream(path).rdbuf();
  std::remove(path.c_str());
  EXPECT_NE(written.str().find("M6 T5 with T2 in the spindle, the direct path"),
            std::string::npos);
}

TEST(Plot, shouldRefuseWhatItCannotDrawInOneLine) {
  const std::string config = FATC_SOURCE_DIR "/config/config.json";
  auto r = test::run_cli({"--plot", "x.svg", "--config", config, "--from", "2"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "--plot: --from A and --to B go together (the change to draw)");
  r = test::run_cli({"--plot", "/nonexistent/dir/x.svg", "--config", config});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "/nonexistent/dir/x.svg: cannot create a temporary file in /nonexistent/dir (No such "
            "file or directory): not written\n");
  r = test::run_cli({"--plot", "x.svg", "--config", config, "--ini", "sim.ini"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--ini is not used by --plot"), std::string::npos) << r.err;
}

/// A folder with a config and a state file, where --plot draws.
class PlotFiles : public test::TempFolder {
 protected:
  void SetUp() override {
    TempFolder::SetUp();
    config_ = folder_ + "/config.json";
    state_ = folder_ + "/state.svg";  // named like a drawing: the mistake to catch
    std::ofstream(config_) << test::kValidConfig;
    std::ofstream(state_) << to_json(ToolState::fresh(valid_config()));
  }
  static std::string text(const std::string& path) { return test::text_of(path); }
  test::CliRun plot(const std::string& svg) {
    return test::run_cli({"--plot", svg, "--config", config_, "--state", state_});
  }
  std::string config_, state_;
};

TEST_F(PlotFiles, shouldRefuseToDrawOverItsOwnStateFile) {
  const std::string before = text(state_);
  const auto r = plot(state_);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "--plot \"" + state_ + "\" is the file given as --state: nothing written\n");
  EXPECT_EQ(text(state_), before);
}

TEST_F(PlotFiles, shouldRefuseToDrawOverItsConfigThroughALinkOrASecondName) {
  const std::string before = text(config_);
  std::filesystem::create_symlink(config_, folder_ + "/soft.svg");
  ASSERT_EQ(::link(config_.c_str(), (folder_ + "/hard.svg").c_str()), 0);
  for (const char* name : {"/soft.svg", "/hard.svg"}) {
    const auto r = plot(folder_ + name);
    EXPECT_EQ(r.code, 2) << name;
    EXPECT_EQ(r.err,
              "--plot \"" + folder_ + name + "\" is the file given as --config: nothing written\n");
  }
  EXPECT_EQ(text(config_), before);
}

TEST_F(PlotFiles, shouldNotFollowALinkToTheConfigPlantedAtTheOldTemporaryName) {
  const std::string before = text(config_);
  std::filesystem::create_symlink(config_, folder_ + "/rack.svg.tmp");
  const auto r = plot(folder_ + "/rack.svg");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(text(config_), before);
  EXPECT_EQ(text(folder_ + "/rack.svg").rfind("<?xml", 0), 0u);
}

TEST_F(PlotFiles, shouldRefuseAFifoAtTheDrawingsNameWithoutWaiting) {
  ASSERT_EQ(::mkfifo((folder_ + "/rack.svg").c_str(), 0600), 0);
  const auto r = plot(folder_ + "/rack.svg");  // a blocked open would hang the test here
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, folder_ + "/rack.svg: expected a regular file, got a FIFO: not written\n");
}

TEST_F(PlotFiles, shouldRefuseADrawingLinkedElsewhere) {
  const std::string elsewhere = folder_ + "/elsewhere.txt";
  std::ofstream(elsewhere) << "someone else's";
  std::filesystem::create_symlink(elsewhere, folder_ + "/rack.svg");
  const auto r = plot(folder_ + "/rack.svg");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, folder_ + "/rack.svg: a symbolic link (to " + elsewhere +
                       "): not written, the link would become a file of its own; give the file it "
                       "points to\n");
  EXPECT_EQ(text(elsewhere), "someone else's");
}

/// Whether xmllint reads `path` as well-formed XML; what it said otherwise.
std::string not_well_formed(const std::string& path) {
  const std::string command = "xmllint --noout '" + path + "' 2>&1";
  std::FILE* pipe = ::popen(command.c_str(), "r");
  std::string said;
  char buffer[512];
  while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) said.append(buffer, n);
  const int status = ::pclose(pipe);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? "" : said + " (xmllint)";
}

TEST(Plot, shouldEscapeWhatXmlForbidsInEveryTextItWrites) {
  const Config config = valid_config();
  // Markup, both quotes, C0 controls, DEL, U+FFFE and U+FFFF, a lone
  // continuation byte, a cut sequence, an overlong '<', a UTF-16 surrogate.
  const std::string nasty = std::string("a&b<c>d\"e'f\x01g\x1b[31mh\x7fi\xef\xbf\xbej\xef\xbf\xbfk") +
                            "\x80l\xe2\x82m\xc0\xbcn\xed\xa0\x80o \xc3\xa9 \xe2\x86\x92 \xf0\x9f\x94\xa7";
  const std::string svg = io::rack_svg(config, ToolState::fresh(config), nullptr, nasty);
  EXPECT_NE(svg.find(">a&amp;b&lt;c&gt;d&quot;e&apos;f\\x01g\\x1b[31mh\\x7fi\\u{fffe}j\\u{ffff}k"
                     "\\x80l\\xe2\\x82m\\xc0\\xbcn\\xed\\xa0\\x80o \xc3\xa9 \xe2\x86\x92 "
                     "\xf0\x9f\x94\xa7</text>"),
            std::string::npos)
      << svg.substr(0, 1200);
  const std::string path = ::testing::TempDir() + "fatc_nasty_title.svg";
  std::ofstream(path) << svg;
  EXPECT_EQ(not_well_formed(path), "");
  std::remove(path.c_str());
}

TEST_F(PlotFiles, shouldWriteWellFormedXmlWhateverTheConfigsPathHolds) {
  // Every byte a Linux file name may hold but '/' and NUL, a few at a time.
  std::vector<std::string> names = {"a&b<c>d\"e'f",        "\x01\x02\t\n\r\x1b\x7f",
                                    "\xef\xbf\xbe\xef\xbf\xbf", "\x80\xfe\xff\xc0\xbc",
                                    "\xed\xa0\x80\xe2\x82",     "]]>&amp;<!--"};
  for (int byte = 1; byte < 256; byte += 17) {
    if (byte != '/') names.push_back(std::string("z") + static_cast<char>(byte));
  }
  for (const std::string& name : names) {
    const std::string folder = folder_ + "/" + name;
    std::filesystem::create_directories(folder);
    const std::string config = folder + "/config.json";
    std::ofstream(config) << test::kValidConfig;
    const std::string svg = folder_ + "/rack.svg";
    const auto r = test::run_cli({"--plot", svg, "--config", config, "--from", "1", "--to", "2"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(not_well_formed(svg), "") << escape(name);
  }
}

}  // namespace
}  // namespace fatc
