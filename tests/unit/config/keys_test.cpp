// config.json's keys are declared once (keys.cpp): the reader refuses what
// the declarations do not hold and checks each number against their bounds,
// and the reference is generated from them.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "core/config/keys.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

TEST(ConfigKeys, shouldRefuseEachTopLevelNumberBeyondItsDeclaredBounds) {
  int checked = 0;
  for (const KeyDeclaration& declared : config_keys()) {
    const std::string path = declared.path;
    if (!declared.bounds || path.find('.') != std::string::npos) continue;
    const std::string json = "\"" + path + "\": " + number(declared.bounds->max * 2 + 1);
    std::string text = test::kValidConfig;
    // The valid config's own value of the key, if it has one, goes.
    if (const auto at = text.find("\"" + path + "\""); at != std::string::npos) {
      text.erase(at, text.find_first_of(",}", at) + 1 - at);
    }
    text.insert(text.rfind('}'), "," + json);
    const ConfigResult result = parse_config(text);
    ASSERT_FALSE(result.config) << path;
    EXPECT_NE(result.errors.front().find(path + ": must be from " + number(declared.bounds->min) +
                                         " to " + number(declared.bounds->max)),
              std::string::npos)
        << path << ": " << result.errors.front();
    ++checked;
  }
  EXPECT_GE(checked, 12);
}

TEST(ConfigKeys, shouldRefuseAKeyTheDeclarationsDoNotHoldUnderAnyObject) {
  for (const char* extra : {R"("flush": {"pulses": 1, "pulse": 0.2})",
                            R"("sensors": {"tool_presence": true})",
                            R"("rack_cover": {"opened_sensr": true})"}) {
    const ConfigResult result = parse_config(
        std::string(test::kValidConfig).insert(std::string(test::kValidConfig).rfind('}'),
                                               std::string(",") + extra));
    ASSERT_FALSE(result.config) << extra;
    EXPECT_NE(result.errors.front().find("unknown key, did you mean"), std::string::npos)
        << result.errors.front();
  }
}

TEST(ConfigKeys, shouldFindAPocketsKeyByItsPattern) {
  EXPECT_STREQ(key("pockets.7.x").path, "pockets.N.{x,y,z}");
  EXPECT_STREQ(key("loading.z").path, "loading.{x,y,z}");
  EXPECT_THROW(key("loading.w"), std::logic_error);
  EXPECT_EQ(keys_below("pockets.12"),
            (std::vector<std::string>{"x", "y", "z", "tool", "approach", "side_offset"}));
}

TEST(ConfigKeys, shouldListEveryDeclaredKeyInTheReference) {
  const std::string table = config_markdown();
  for (const char* path : {"`units`", "`pockets.N.side_offset.y`", "`rack_cover.timeout_seconds`",
                           "`sensors.pocket_occupancy`", "`safe.z`"}) {
    EXPECT_NE(table.find(path), std::string::npos) << path;
  }
}

TEST(ConfigKeys, shouldGiveTheKeepOutMarginAFloorOfItsOwnInInches) {
  EXPECT_DOUBLE_EQ(bounds_in(key("rack_keepout_margin"), Units::mm).min, 1.0);
  EXPECT_DOUBLE_EQ(bounds_in(key("rack_keepout_margin"), Units::inch).min, 0.04);
}

}  // namespace
}  // namespace fatc

namespace fatc {
namespace {

/// The default a declaration states in words, as a number ("300 (sample: 3000)" -> 300).
double stated(const char* path) {
  return std::strtod(key(path).fallback.c_str(), nullptr);
}

TEST(ConfigKeys, shouldStateTheDefaultsTheReaderGives) {
  // The valid config leaves these keys out: what it reads is their default.
  const Config read = test::valid_config();
  const RackCoverConfig cover;
  EXPECT_DOUBLE_EQ(read.pocket_feed, stated("pocket_feed"));
  EXPECT_DOUBLE_EQ(read.probe_seek_feed, stated("probe_seek_feed"));
  EXPECT_DOUBLE_EQ(read.probe_latch_feed, stated("probe_latch_feed"));
  EXPECT_DOUBLE_EQ(read.probe_backoff, stated("probe_backoff"));
  EXPECT_DOUBLE_EQ(read.spindle_stop_timeout_seconds, stated("spindle_stop_timeout_seconds"));
  EXPECT_DOUBLE_EQ(read.sensor_timeout_seconds, stated("sensor_timeout_seconds"));
  EXPECT_DOUBLE_EQ(read.flush.pulses, stated("flush.pulses"));
  EXPECT_DOUBLE_EQ(read.flush.pulse_seconds, stated("flush.pulse_seconds"));
  EXPECT_DOUBLE_EQ(read.flush.pause_seconds, stated("flush.pause_seconds"));
  EXPECT_DOUBLE_EQ(cover.seconds, stated("rack_cover.seconds"));
  EXPECT_DOUBLE_EQ(cover.timeout_seconds, stated("rack_cover.timeout_seconds"));
}

}  // namespace
}  // namespace fatc
