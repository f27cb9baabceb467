// --plot: the rack from above as SVG, from the config and the tool state, and
// the path of one change.
#include "cli/plot.hpp"

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
  const std::string svg = io::rack_svg(config, ToolState::fresh(config), nullptr, nullptr, "the rack");
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
  const std::string svg = io::rack_svg(config, tools, nullptr, nullptr, "A & <B>");
  EXPECT_NE(svg.find(">T2 (spindle), top</text>"), std::string::npos) << svg;
  EXPECT_NE(svg.find(">T1, top</text>"), std::string::npos);
  EXPECT_EQ(count(svg, "marker-end"), 0) << "no side approach to draw";
  EXPECT_NE(svg.find(">A &amp; &lt;B&gt;</text>"), std::string::npos) << "the title escaped";
}

TEST(Plot, shouldDrawTheChangesMovesInXYSlowOnesApart) {
  const Config config = valid_config();
  const Simulator change = plan_change(config, 1, 2, -70.0);
  const std::string svg = io::rack_svg(config, ToolState::fresh(config), &change, nullptr, "M6 T2");
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
  EXPECT_NE(r.out.find(": 6 pockets, and the path of the change, the rack as at first start\n"),
            std::string::npos)
      << r.out;
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
  r = test::run_cli({"--plot", "x.svg", "--config", config, "--ini", "/nonexistent/sim.ini"});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(count(r.err, "\n"), 1) << r.err;
  EXPECT_EQ(r.err.rfind("/nonexistent/sim.ini: ", 0), 0u) << r.err;
}

TEST(Plot, shouldOutlineTheMachinesTravelWithItsLimits) {
  const Config config = valid_config();
  const SoftLimits travel{{-10.0, 400.0}, {-20.0, 300.0}, {-120.0, 0.0}};
  const std::string svg =
      io::rack_svg(config, ToolState::fresh(config), nullptr, &travel, "the machine");
  EXPECT_EQ(count(svg, "<rect class=\"travel\""), 1) << svg;
  EXPECT_NE(svg.find(">travel X -10 to 400, Y -20 to 300</text>"), std::string::npos);
  EXPECT_NE(svg.find("Grey outline: the machine's travel"), std::string::npos);
  // Its corners where the rack's coordinates put them: pocket 1 (x 20, y 20)
  // drawn as far from the outline's left edge as 30 mm are from 50 mm.
  const auto attribute = [&](const std::string& from, const std::string& name) {
    const auto at = svg.find(name + "=\"", svg.find(from)) + name.size() + 2;
    return std::stod(svg.substr(at, svg.find('"', at) - at));
  };
  const double left = attribute("<rect class=\"travel\"", "x");
  const double width = attribute("<rect class=\"travel\"", "width");
  const double safe_x = attribute("<circle class=\"safe\"", "cx");
  EXPECT_NEAR((safe_x - left) / width, (config.safe.x + 10.0) / 410.0, 0.002);
  const std::string without = io::rack_svg(config, ToolState::fresh(config), nullptr, nullptr, "");
  EXPECT_EQ(count(without, "travel"), 0);
}

TEST(Plot, shouldKeepLoadingVisibleOnTheSensorAndSafeOnBoth) {
  Config config = valid_config();
  ASSERT_EQ(config.loading.x, config.probe_limit.x);  // the sample's: one place in XY
  ASSERT_EQ(config.loading.y, config.probe_limit.y);
  config.safe = config.loading;
  const std::string svg = io::rack_svg(config, ToolState::fresh(config), nullptr, nullptr, "");
  // The sensor a ring, drawn first; loading a smaller dot inside it; safe the smallest, last.
  const auto sensor = svg.find("<circle class=\"sensor\"");
  const auto loading = svg.find("<circle class=\"loading\"");
  const auto safe = svg.find("<circle class=\"safe\"");
  ASSERT_NE(sensor, std::string::npos);
  ASSERT_NE(loading, std::string::npos);
  ASSERT_NE(safe, std::string::npos);
  EXPECT_LT(sensor, loading);
  EXPECT_LT(loading, safe);
  const auto line = [&](std::size_t at) { return svg.substr(at, svg.find('\n', at) - at); };
  EXPECT_NE(line(sensor).find("r=\"11.0\" fill=\"none\""), std::string::npos) << line(sensor);
  EXPECT_NE(line(loading).find("r=\"7.0\" fill=\"#26c\""), std::string::npos) << line(loading);
  EXPECT_NE(line(safe).find("r=\"4.0\" fill=\"#2a2\""), std::string::npos) << line(safe);
  // Three labels, each on a line of its own.
  std::vector<std::string> label_y;
  for (const std::string label : {">touch-off sensor<", ">loading<", ">safe<"}) {
    const auto text = svg.rfind("<text", svg.find(label));
    const auto y = svg.find(" y=\"", text) + 4;
    label_y.push_back(svg.substr(y, svg.find('"', y) - y));
  }
  EXPECT_NE(label_y[0], label_y[1]);
  EXPECT_NE(label_y[1], label_y[2]);
  EXPECT_NE(label_y[0], label_y[2]);
}

TEST(Plot, shouldWriteTheTravelOfHugeSoftLimitsInFull) {
  // LinuxCNC takes soft limits up to 1e99: a label cut by a buffer would name another machine.
  const Config config = valid_config();
  const SoftLimits travel{{-1e99, 1e99}, {-2.5e50, 123456789012.5}, {-120.0, 0.0}};
  const std::string svg =
      io::rack_svg(config, ToolState::fresh(config), nullptr, &travel, "the machine");
  char x_min[128], y_min[128];
  std::snprintf(x_min, sizeof x_min, "%.0f", -1e99);
  std::snprintf(y_min, sizeof y_min, "%.0f", -2.5e50);
  EXPECT_NE(svg.find(std::string(">travel X ") + x_min + " to " + (x_min + 1) + ", Y " + y_min +
                     " to 123456789012.5</text>"),
            std::string::npos)
      << svg.substr(0, 3000);
}

TEST(Plot, shouldWriteLengthsInTheConfigsUnitsToTheirPrecision) {
  // A 0.75 inch keep-out margin is 0.75, not 0.8; 0.03125 inch keeps its five decimals.
  Config config = test::valid_config();
  config.units = Units::inch;
  config.rack_keepout_margin = 0.75;
  const SoftLimits travel{{-0.03125, 16.0}, {-0.5, 12.0}, {-5.0, 0.0}};
  const std::string svg =
      io::rack_svg(config, ToolState::fresh(config), nullptr, &travel, "the machine");
  EXPECT_NE(svg.find("each pocket's keep-out (0.75 around it)"), std::string::npos);
  EXPECT_NE(svg.find(">travel X -0.03125 to 16, Y -0.5 to 12</text>"), std::string::npos);
}

TEST(Plot, shouldDrawTheTravelOfTheIniItIsGiven) {
  const std::string path = ::testing::TempDir() + "fatc_travel.svg";
  const auto r = test::run_cli({"--plot", path, "--config", FATC_SOURCE_DIR "/config/config.json",
                                "--ini", FATC_SOURCE_DIR "/config/sim/fixed_atc_sim.ini"});
  EXPECT_EQ(r.code, 0) << r.err;
  const std::string written = test::text_of(path);
  std::remove(path.c_str());
  EXPECT_NE(written.find(">travel X -10 to 400, Y -10 to 300</text>"), std::string::npos);
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
  const std::string svg = io::rack_svg(config, ToolState::fresh(config), nullptr, nullptr, nasty);
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
