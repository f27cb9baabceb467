#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/config/config.hpp"
#include "io/files.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using Json = nlohmann::json;

TEST(Config, shouldReadEveryPrototypeKeyWithItsMeaning) {
  const ConfigResult result = parse_config(test::kValidConfig);
  ASSERT_TRUE(result.config) << (result.errors.empty() ? "" : result.errors.front());
  const Config& c = *result.config;
  EXPECT_EQ(c.probe_length_compensation_offset, -95.0);
  EXPECT_EQ(c.probe_retract_offset_z, 5.0);
  EXPECT_EQ(c.pocket_side_offset.x, 0.0);
  EXPECT_EQ(c.pocket_side_offset.y, 40.0);
  EXPECT_EQ(c.pocket_above_chuck_offset_z, 20.0);
  EXPECT_EQ(c.pocket_above_clearance_offset_z, 60.0);
  EXPECT_EQ(c.chuck_seconds, 0.5);
  EXPECT_EQ(c.loading.y, 150.0);
  EXPECT_EQ(c.probe_limit.z, -90.0);
  EXPECT_EQ(c.safe.x, 120.0);
  ASSERT_EQ(c.pockets.size(), 6u);
}

TEST(Config, shouldMergePocketDefaultUnderEachPocket) {
  const Config c = test::valid_config();
  EXPECT_EQ(c.pockets.at(2).at.x, 100.0);
  EXPECT_EQ(c.pockets.at(2).at.y, 20.0);
  EXPECT_EQ(c.pockets.at(2).at.z, -80.0);
  EXPECT_EQ(c.pockets.at(6).at.z, -82.5) << "a pocket's own value wins over pocket_default";
}

TEST(Config, shouldApplyDocumentedDefaultsToNewKeys) {
  const Config c = test::valid_config();
  EXPECT_EQ(c.units, Units::mm);
  EXPECT_EQ(c.pocket_feed, 500.0);
  EXPECT_EQ(c.probe_seek_feed, 300.0);
  EXPECT_EQ(c.probe_latch_feed, 25.0);
  EXPECT_EQ(c.probe_backoff, 2.0);
  EXPECT_EQ(c.flush.pulses, 1);
  EXPECT_EQ(c.flush.pulse_seconds, 0.2);
  EXPECT_EQ(c.flush.pause_seconds, 0.2);
  EXPECT_EQ(c.spindle_stop_timeout_seconds, 10.0);
  EXPECT_FALSE(c.rack_keepout_margin);
  EXPECT_EQ(c.keepout_margin(), 20.0) << "half the side offset";
  EXPECT_EQ(c.probe_after_change, MeasureRule::off);
  EXPECT_EQ(c.check_tolerance(), 0.1);
  EXPECT_TRUE(c.manual_tools);
}

TEST(Config, shouldLetASmallProbeWindowStandWhenNoToolUsesTheDefaultTolerance) {
  Json j = Json::parse(test::kValidConfig);
  j["probe_window"] = 0.05;
  j["tools"] = {{"3", {{"measure", "check"}, {"check_tolerance", 0.02}}}};
  EXPECT_TRUE(parse_config(j.dump()).config.has_value());
  j["tools"]["4"] = {{"measure", "check"}};  // checked against probe_check_tolerance's 0.1
  const auto refused = parse_config(j.dump());
  ASSERT_FALSE(refused.errors.empty());
  EXPECT_EQ(refused.errors.front().rfind("probe_window: must be larger than probe_check_tolerance", 0), 0u);
}

TEST(Config, shouldReadEveryNewKey) {
  Json j = Json::parse(test::kValidConfig);
  j["units"] = "inch";
  j["pocket_feed"] = 20;
  j["probe_seek_feed"] = 12;
  j["probe_latch_feed"] = 1;
  j["probe_backoff"] = 0.08;
  j["flush"] = {{"pulses", 3}, {"pulse_seconds", 0.1}, {"pause_seconds", 0.3}};
  j["spindle_stop_timeout_seconds"] = 4;
  j["rack_keepout_margin"] = 0.5;
  j["probe_after_change"] = "check";
  j["probe_check_tolerance"] = 0.002;
  j["manual_tools"] = false;
  const auto result = parse_config(j.dump());
  ASSERT_TRUE(result.config) << result.errors.front();
  const Config& c = *result.config;
  EXPECT_EQ(c.units, Units::inch);
  EXPECT_EQ(c.pocket_feed, 20.0);
  EXPECT_EQ(c.probe_seek_feed, 12.0);
  EXPECT_EQ(c.probe_latch_feed, 1.0);
  EXPECT_EQ(c.probe_backoff, 0.08);
  EXPECT_EQ(c.flush.pulses, 3);
  EXPECT_EQ(c.flush.pulse_seconds, 0.1);
  EXPECT_EQ(c.flush.pause_seconds, 0.3);
  EXPECT_EQ(c.spindle_stop_timeout_seconds, 4.0);
  EXPECT_EQ(c.keepout_margin(), 0.5);
  EXPECT_EQ(c.probe_after_change, MeasureRule::check);
  EXPECT_EQ(c.check_tolerance(), 0.002);
  EXPECT_FALSE(c.manual_tools);
}

TEST(Config, shouldDefaultTheCheckToleranceInInches) {
  Json j = Json::parse(test::kValidConfig);
  j["units"] = "inch";
  EXPECT_EQ(parse_config(j.dump()).config->check_tolerance(), 0.004);
}

TEST(Config, shouldDefaultEveryFeedAndLengthToTheSameAmountInInches) {
  Json j = Json::parse(test::kValidConfig);
  const Config mm = *parse_config(j.dump()).config;
  j["units"] = "inch";
  const Config inch = *parse_config(j.dump()).config;
  // Each inch default is its mm one over 25: within 1.6 % of the same speed or length.
  const std::pair<double, double> same[] = {
      {mm.pocket_feed, inch.pocket_feed},           {mm.probe_seek_feed, inch.probe_seek_feed},
      {mm.probe_latch_feed, inch.probe_latch_feed}, {mm.probe_backoff, inch.probe_backoff},
      {mm.dry_run_feed(), inch.dry_run_feed()},     {mm.check_tolerance(), inch.check_tolerance()},
      {mm.window(), inch.window()},                  {mm.keepout_above(), inch.keepout_above()}};
  for (const auto& [in_mm, in_inch] : same) {
    EXPECT_NEAR(in_inch * 25.4 / in_mm, 1.016, 1e-9) << in_mm << " mm against " << in_inch << " inch";
  }
  EXPECT_EQ(inch.pocket_feed, 20.0);
  EXPECT_EQ(inch.probe_seek_feed, 12.0);
  EXPECT_EQ(inch.probe_latch_feed, 1.0);
  EXPECT_EQ(inch.probe_backoff, 0.08);
}

TEST(Config, shouldNameEachDefaultTakenInTheConfigsUnits) {
  Json j = Json::parse(test::kValidConfig);
  j["units"] = "inch";
  j["pocket_side_offset"] = {{"x", 0.0}, {"y", 1.5}};
  j["probe_seek_feed"] = 30;
  j["rack_keepout_all_motion"] = false;  // the mm rack read as inches: pockets 50 inches apart
  const auto parsed = parse_config(j.dump());
  ASSERT_TRUE(parsed.config) << parsed.errors.front();
  const Config& inch = *parsed.config;
  EXPECT_EQ(defaulted_words(inch),
            (std::vector<std::string>{
                "pocket_feed 20 in/min (default; 500 mm/min in a mm config)",
                "probe_latch_feed 1 in/min (default; 25 mm/min in a mm config)",
                "probe_backoff 0.08 inch (default; 2 mm in a mm config)",
                "probe_check_tolerance 0.004 inch (default; 0.1 mm in a mm config)",
                "probe_window 0.4 inch (default; 10 mm in a mm config)",
                "rack_keepout_above 0.2 inch (default; 5 mm in a mm config)",
                "verify_feed 20 in/min (default: pocket_feed)",
                "rack_keepout_margin 0.75 inch (default: half the side offset's length)"}));
  j["units"] = "mm";
  j["pocket_side_offset"] = {{"x", 0.0}, {"y", 40.0}};
  const auto mm = parse_config(j.dump());
  ASSERT_TRUE(mm.config) << mm.errors.front();
  EXPECT_EQ(defaulted_words(*mm.config).front(),
            "pocket_feed 500 mm/min (default; 20 in/min in an inch config)");
  for (const char* key : {"pocket_feed", "probe_latch_feed", "probe_backoff", "verify_feed",
                          "probe_check_tolerance", "probe_window", "rack_keepout_margin",
                          "rack_keepout_above"}) {
    j[key] = 0.5;
  }
  j["probe_window"] = 5;
  j["rack_keepout_margin"] = 10;
  j["rack_keepout_above"] = 3;
  const auto all = parse_config(j.dump());
  ASSERT_TRUE(all.config) << all.errors.front();
  EXPECT_TRUE(defaulted_words(*all.config).empty());
}

TEST(Config, shouldReadTheSampleConfigShipped) {
  const auto result = io::load_config_file(FATC_SOURCE_DIR "/config/config.json");
  EXPECT_TRUE(result.config) << (result.errors.empty() ? "" : result.errors.front());
}

/// A bad config: how to spoil the valid one, and what the message must say.
struct BadConfig {
  const char* name;
  std::function<void(Json&)> spoil;
  const char* expected;  ///< a part of the message, starting with the JSON path
};

std::ostream& operator<<(std::ostream& out, const BadConfig& bad) { return out << bad.name; }

class BadConfigs : public ::testing::TestWithParam<BadConfig> {};

TEST_P(BadConfigs, shouldNameTheJsonPathOfTheProblem) {
  Json j = Json::parse(test::kValidConfig);
  GetParam().spoil(j);
  const auto result = parse_config(j.dump());
  ASSERT_FALSE(result.config);
  ASSERT_FALSE(result.errors.empty());
  bool found = false;
  for (const auto& error : result.errors) found = found || error.find(GetParam().expected) == 0;
  EXPECT_TRUE(found) << "expected a message starting \"" << GetParam().expected << "\", got \""
                     << result.errors.front() << "\"";
}

// clang-format off
INSTANTIATE_TEST_SUITE_P(Each, BadConfigs, ::testing::Values(
  BadConfig{"missing_safe", [](Json& j) { j.erase("safe"); }, "safe: missing"},
  BadConfig{"missing_pockets", [](Json& j) { j.erase("pockets"); }, "pockets: missing"},
  BadConfig{"missing_chuck_seconds", [](Json& j) { j.erase("chuck_seconds"); }, "chuck_seconds: missing"},
  BadConfig{"missing_offset", [](Json& j) { j.erase("probe_length_compensation_offset"); }, "probe_length_compensation_offset: missing"},
  BadConfig{"missing_loading_z", [](Json& j) { j["loading"].erase("z"); }, "loading.z: missing"},
  BadConfig{"missing_side_y", [](Json& j) { j["pocket_side_offset"].erase("y"); }, "pocket_side_offset.y: missing"},
  BadConfig{"pocket_x_string", [](Json& j) { j["pockets"]["2"]["x"] = "abc"; }, "pockets.2.x: expected a number, got \"abc\""},
  BadConfig{"pocket_not_object", [](Json& j) { j["pockets"]["2"] = 5; }, "pockets.2: expected an object"},
  BadConfig{"pockets_array", [](Json& j) { j["pockets"] = Json::array(); }, "pockets: expected an object, got an array"},
  BadConfig{"pockets_empty", [](Json& j) { j["pockets"] = Json::object(); }, "pockets: no pockets defined"},
  BadConfig{"tool_zero", [](Json& j) { j["pockets"]["0"] = {{"x", 400}}; }, "pockets.0: the key must be a pocket number"},
  BadConfig{"tool_negative", [](Json& j) { j["pockets"]["-3"] = {{"x", 400}}; }, "pockets.-3: the key must be a pocket number"},
  BadConfig{"tool_fraction", [](Json& j) { j["pockets"]["1.5"] = {{"x", 400}}; }, "pockets.1.5: the key must be a pocket number"},
  BadConfig{"tool_name", [](Json& j) { j["pockets"]["endmill"] = {{"x", 400}}; }, "pockets.endmill: the key must be a pocket number"},
  BadConfig{"tool_leading_zero", [](Json& j) { j["pockets"]["07"] = {{"x", 400}}; }, "pockets.07: the key must be a pocket number"},
  BadConfig{"pocket_without_z", [](Json& j) { j["pocket_default"].erase("z"); j["pockets"]["6"].erase("z"); }, "pockets.1.z: missing, and pocket_default has no z"},
  BadConfig{"unknown_top_key", [](Json& j) { j["chuck_second"] = 1; }, "chuck_second: unknown key, did you mean \"chuck_seconds\"?"},
  BadConfig{"unknown_far_key", [](Json& j) { j["spindle_rpm"] = 1; }, "spindle_rpm: unknown key"},
  BadConfig{"unknown_axis", [](Json& j) { j["safe"]["w"] = 1; }, "safe.w: unknown key"},
  BadConfig{"unknown_pocket_key", [](Json& j) { j["pockets"]["3"]["diameter"] = 6; }, "pockets.3.diameter: unknown key"},
  BadConfig{"bool_number", [](Json& j) { j["chuck_seconds"] = true; }, "chuck_seconds: expected a number, got true"},
  BadConfig{"null_number", [](Json& j) { j["safe"]["z"] = nullptr; }, "safe.z: expected a number, got null"},
  BadConfig{"safe_not_object", [](Json& j) { j["safe"] = "home"; }, "safe: expected an object, got \"home\""},
  BadConfig{"chuck_zero", [](Json& j) { j["chuck_seconds"] = 0; }, "chuck_seconds: must be from 0.01 to 60 seconds, got 0"},
  BadConfig{"above_chuck_negative", [](Json& j) { j["pocket_above_chuck_offset_z"] = -1; }, "pocket_above_chuck_offset_z: must be from 0.001 to 1000 mm, got -1"},
  BadConfig{"clearance_below_chuck", [](Json& j) { j["pocket_above_clearance_offset_z"] = 10; }, "pocket_above_clearance_offset_z: must be above pocket_above_chuck_offset_z (20)"},
  BadConfig{"side_offset_zero", [](Json& j) { j["pocket_side_offset"] = {{"x", 0}, {"y", 0}}; }, "pocket_side_offset: must not be zero"},
  BadConfig{"pockets_too_close", [](Json& j) { j["pockets"]["2"]["x"] = 70; }, "pockets.2: only 20 from pocket 1, closer than the side offset (40)"},
  BadConfig{"probe_limit_above_loading", [](Json& j) { j["probe_limit"]["z"] = 0; }, "probe_limit.z: must not be above loading.z (-10)"},
  BadConfig{"units_unknown", [](Json& j) { j["units"] = "cm"; }, "units: expected \"mm\" or \"inch\", got \"cm\""},
  BadConfig{"feed_zero", [](Json& j) { j["pocket_feed"] = 0; }, "pocket_feed: must be from 0.01 to 100000 mm/min, got 0"},
  BadConfig{"latch_negative", [](Json& j) { j["probe_latch_feed"] = -5; }, "probe_latch_feed: must be from 0.01 to 100000 mm/min, got -5"},
  BadConfig{"verify_feed_text", [](Json& j) { j["verify_feed"] = "slow"; }, "verify_feed: expected a number, got \"slow\""},
  BadConfig{"backoff_zero", [](Json& j) { j["probe_backoff"] = 0; }, "probe_backoff: must be from 0.001 to 1000 mm, got 0"},
  BadConfig{"retract_zero", [](Json& j) { j["probe_retract_offset_z"] = 0; }, "probe_retract_offset_z: must be from 0.001 to 1000 mm, got 0"},
  BadConfig{"flush_fraction", [](Json& j) { j["flush"] = {{"pulses", 1.5}}; }, "flush.pulses: must be a whole number from 0 to 20"},
  BadConfig{"flush_unknown", [](Json& j) { j["flush"] = {{"pulse", 1}}; }, "flush.pulse: unknown key, did you mean \"pulses\"?"},
  BadConfig{"flush_pause_zero", [](Json& j) { j["flush"] = {{"pause_seconds", 0}}; }, "flush.pause_seconds: must be from 0.01 to 60 seconds, got 0"},
  BadConfig{"timeout_zero", [](Json& j) { j["spindle_stop_timeout_seconds"] = 0; }, "spindle_stop_timeout_seconds: must be from 0.01 to 3600 seconds, got 0"},
  BadConfig{"margin_negative", [](Json& j) { j["rack_keepout_margin"] = -1; }, "rack_keepout_margin: must be from 1 to 1000 mm, got -1"},
  BadConfig{"margin_over_side", [](Json& j) { j["rack_keepout_margin"] = 45; }, "rack_keepout_margin: must be smaller than the side offset (40)"},
  BadConfig{"keepout_all_motion_text", [](Json& j) { j["rack_keepout_all_motion"] = "yes"; }, "rack_keepout_all_motion: expected true or false, got \"yes\""},
  BadConfig{"keepout_above_zero", [](Json& j) { j["rack_keepout_above"] = 0; }, "rack_keepout_above: must be from 1 to 1000 mm, got 0"},
  BadConfig{"keepout_groups", [](Json& j) {
    for (int i = 0; i < 9; ++i) j["pockets"][std::to_string(10 + i)] = {{"x", 1000.0 + 200.0 * i}};
  }, "rack_keepout_all_motion: the pockets lie in 10 groups apart from each other, and the realtime guard holds 4: move pockets together or set it false"},
  BadConfig{"latch_default_above_seek", [](Json& j) { j["units"] = "inch"; j["probe_seek_feed"] = 0.5; }, "probe_latch_feed: must not be above probe_seek_feed (0.5), got 1: its default, left out"},
  BadConfig{"seek_default_below_latch", [](Json& j) { j["units"] = "inch"; j["probe_latch_feed"] = 15; }, "probe_latch_feed: must not be above probe_seek_feed (12: its default, left out), got 15"},
  BadConfig{"window_default_not_above_tolerance", [](Json& j) { j["probe_after_change"] = "check"; j["probe_check_tolerance"] = 12; }, "probe_window: must be larger than probe_check_tolerance (12), got 10: its default, left out"},
  BadConfig{"margin_inch_below_floor", [](Json& j) { j["units"] = "inch"; j["rack_keepout_margin"] = 0.01; }, "rack_keepout_margin: must be from 0.04 to 1000 inch, got 0.01"},
  BadConfig{"tools_key", [](Json& j) { j["tools"] = {{"T7", Json::object()}}; }, "tools.T7: the key must be a tool number from 1 to 999999999"},
  BadConfig{"tools_entry", [](Json& j) { j["tools"] = {{"7", "probe"}}; }, "tools.7: expected an object, got \"probe\""},
  BadConfig{"tools_kind", [](Json& j) { j["tools"]["7"]["kind"] = "laser"; }, "tools.7.kind: expected \"cutter\" or \"probe\", got \"laser\""},
  BadConfig{"tools_measure", [](Json& j) { j["tools"]["7"]["measure"] = "sometimes"; }, "tools.7.measure: expected \"off\", \"always\""},
  BadConfig{"tools_unknown", [](Json& j) { j["tools"]["7"]["mesure"] = "new"; }, "tools.7.mesure: unknown key, did you mean \"measure\"?"},
  BadConfig{"tools_tolerance_unused", [](Json& j) { j["tools"]["7"]["check_tolerance"] = 0.05; }, "tools.7.check_tolerance: only a tool checked at M6 uses it, and tool 7's rule is \"off\""},
  BadConfig{"tools_tolerance_window", [](Json& j) { j["tools"]["7"] = {{"measure", "check"}, {"check_tolerance", 20}}; }, "tools.7.check_tolerance: must be smaller than probe_window (10), got 20"},
  BadConfig{"tools_feed_never", [](Json& j) { j["tools"]["7"] = {{"measure", "never"}, {"probe_feed", 20}}; }, "tools.7.probe_feed: tool 7 is never measured"},
  BadConfig{"tools_feed_zero", [](Json& j) { j["tools"]["7"]["probe_feed"] = 0; }, "tools.7.probe_feed: must be from 0.01 to 100000"},
  BadConfig{"tools_feed_above_seek", [](Json& j) { j["tools"]["7"]["probe_feed"] = 5000; }, "tools.7.probe_feed: must not be above probe_seek_feed (300): it caps both probing feeds, got 5000"},
  BadConfig{"probe_after_change_word", [](Json& j) { j["probe_after_change"] = "sometimes"; }, "probe_after_change: expected \"off\", \"always\", \"new\", \"never\", \"check\" or \"measure\", got \"sometimes\""},
  BadConfig{"tolerance_zero", [](Json& j) { j["probe_check_tolerance"] = 0; }, "probe_check_tolerance: must be from 0.0001 to 100 mm, got 0"},
  BadConfig{"manual_tools_word", [](Json& j) { j["manual_tools"] = "yes"; }, "manual_tools: expected true or false, got \"yes\""},
  BadConfig{"blend_negative", [](Json& j) { j["blend_tolerance"] = -1; }, "blend_tolerance: must be from 0 to 1000 mm, got -1"},
  BadConfig{"blend_into_rack", [](Json& j) { j["blend_tolerance"] = 16; }, "blend_tolerance: must not be more than 15, how far safe.z lies above pocket 1's above-clearance"},
  BadConfig{"huge_number", [](Json& j) { j["safe"]["x"] = 1e308 * 10; }, "safe.x: expected a number, got null"}
));
// clang-format on

TEST(Config, shouldNameLineAndColumnOfAJsonSyntaxError) {
  const auto result = parse_config("{\n  \"safe\": {\"x\": 1,,}\n}");
  ASSERT_EQ(result.errors.size(), 1u);
  EXPECT_EQ(result.errors[0].rfind("line 2, column ", 0), 0u) << result.errors[0];
  EXPECT_NE(result.errors[0].find("invalid JSON"), std::string::npos);
}

TEST(Config, shouldRejectANumberTooLargeForADouble) {
  const std::string text = std::string(test::kValidConfig).replace(
      std::string(test::kValidConfig).find("\"chuck_seconds\": 0.5"), 20, "\"chuck_seconds\": 1e999");
  const auto result = parse_config(text);
  ASSERT_FALSE(result.config);
  EXPECT_EQ(result.errors.front(),
            "line 7, column 24: invalid JSON: number overflow parsing '1e999'");
}

TEST(Config, shouldRejectAKeyGivenTwice) {
  std::string text = test::kValidConfig;
  text.replace(text.find("\"2\": {\"x\": 100.0}"), 17, "\"2\": {\"x\": 100.0}, \"2\": {\"x\": 350.0}");
  const auto result = parse_config(text);
  ASSERT_FALSE(result.config);
  EXPECT_EQ(result.errors.front(), "pockets.2: appears twice");
}

TEST(Config, shouldReportEveryProblemNotOnlyTheFirst) {
  Json j = Json::parse(test::kValidConfig);
  j.erase("safe");
  j["chuck_seconds"] = "half";
  j["pockets"]["4"]["y"] = false;
  const auto result = parse_config(j.dump());
  EXPECT_EQ(result.errors.size(), 3u);
}

TEST(Config, shouldRejectATopLevelThatIsNoObject) {
  const auto result = parse_config("[1, 2]");
  ASSERT_EQ(result.errors.size(), 1u);
  EXPECT_EQ(result.errors[0], "config: expected a JSON object at the top, got an array");
}

TEST(ConfigFile, shouldPrefixEveryMessageWithTheFilePath) {
  const auto result = io::load_config_file(FATC_BAD_CONFIGS "/clearance_below_chuck.json");
  ASSERT_FALSE(result.config);
  EXPECT_EQ(result.errors.front().rfind(FATC_BAD_CONFIGS "/clearance_below_chuck.json: "
                                        "pocket_above_clearance_offset_z:", 0),
            0u)
      << result.errors.front();
}

TEST(ConfigFile, shouldSayWhenTheFileCannotBeOpened) {
  const auto result = io::load_config_file("/nonexistent/config.json");
  ASSERT_EQ(result.errors.size(), 1u);
  EXPECT_EQ(result.errors[0], "/nonexistent/config.json: cannot open (No such file or directory)");
}

}  // namespace
}  // namespace fatc
