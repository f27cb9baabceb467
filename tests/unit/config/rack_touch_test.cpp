#include <gtest/gtest.h>

#include <ostream>
#include <string>

#include "core/config/config.hpp"
#include "test_config.hpp"

// `rack_touch` of config.json: its defaults in either unit, and each bad
// value or relation refused in one line naming the key.

namespace fatc {
namespace {

const char* const kBore = R"({"rack_touch": {
  "feature": "bore", "stylus_radius": 1.5, "bore_diameter": 30.0, "top": {"x": 0, "y": -20},
  "pocket_above_top": 10.0, "depth": 5.0}})";

/// The sample config with kBore, then `patch` merged in.
std::string with(const char* patch) {
  auto json = nlohmann::ordered_json::parse(test::sample_config_with(kBore));
  json.merge_patch(nlohmann::ordered_json::parse(patch));
  return json.dump();
}

TEST(RackTouchConfig, shouldFindNothingByTouchWhereRackTouchIsAbsent) {
  EXPECT_FALSE(parse_config(test::kValidConfig).config->rack_touch);
}

TEST(RackTouchConfig, shouldReadEveryKeyAndTakeTheDefaultsInMillimetres) {
  const ConfigResult parsed = parse_config(with(R"({"rack_touch": {
    "datum": {"pocket": 2, "x": 100.1, "y": 20.2, "z": -80.3}, "check_every_changes": 50,
    "check_at_start": true}})"));
  ASSERT_TRUE(parsed.config) << parsed.errors.front();
  const RackTouch& rack = *parsed.config->rack_touch;
  EXPECT_EQ(rack.feature, TouchFeature::bore);
  EXPECT_EQ(rack.stylus_radius, 1.5);
  EXPECT_EQ(rack.bore_diameter, 30.0);
  EXPECT_EQ(rack.top.y, -20.0);
  EXPECT_EQ(rack.pocket_above_top, 10.0);
  EXPECT_EQ(rack.depth, 5.0);
  EXPECT_EQ(rack.search, 5.0);
  EXPECT_EQ(rack.clear, 3.0);
  EXPECT_EQ(rack.drift_tolerance, 0.1);
  EXPECT_EQ(rack.bore_tolerance, 0.5);
  EXPECT_EQ(rack.datum_pocket, 2);
  ASSERT_TRUE(rack.datum);
  EXPECT_EQ(rack.datum->z, -80.3);
  EXPECT_EQ(rack.check_every_changes, 50);
  EXPECT_TRUE(rack.check_at_start);
}

TEST(RackTouchConfig, shouldTakeTheDefaultsInInches) {
  const ConfigResult parsed = parse_config(
      with(R"({"units": "inch", "rack_touch": {"stylus_radius": 0.06, "bore_diameter": 1.2,
                "depth": 0.2}})"));
  ASSERT_TRUE(parsed.config) << parsed.errors.front();
  const RackTouch& rack = *parsed.config->rack_touch;
  EXPECT_EQ(rack.search, 0.2);
  EXPECT_EQ(rack.clear, 0.12);
  EXPECT_EQ(rack.drift_tolerance, 0.004);
  EXPECT_EQ(rack.bore_tolerance, 0.02);
}

struct Refused {
  const char* patch;
  const char* line;  ///< the whole message
};

std::ostream& operator<<(std::ostream& out, const Refused& refused) { return out << refused.line; }

class RackTouchRefused : public ::testing::TestWithParam<Refused> {};

TEST_P(RackTouchRefused, shouldSayInOneLineWhichKeyIsWrong) {
  const ConfigResult parsed = parse_config(with(GetParam().patch));
  EXPECT_FALSE(parsed.config);
  ASSERT_EQ(parsed.errors.size(), 1u) << parsed.errors.front();
  EXPECT_EQ(parsed.errors.front(), GetParam().line);
}

INSTANTIATE_TEST_SUITE_P(
    Each, RackTouchRefused,
    ::testing::Values(
        Refused{R"({"rack_touch": {"feature": null}})", "rack_touch.feature: missing"},
        Refused{R"({"rack_touch": {"feature": "pin"}})",
                "rack_touch.feature: expected \"bore\", \"fork\" or \"faces\", got \"pin\" (pins "
                "are not supported: docs/sequences.md, teach by touch)"},
        Refused{R"({"rack_touch": {"stylus_radius": null}})", "rack_touch.stylus_radius: missing"},
        Refused{R"({"rack_touch": {"stylus_radius": 5.0}})",
                "rack_touch.stylus_radius: must be below rack_touch.depth (5), got 5"},
        Refused{R"({"rack_touch": {"bore_diameter": null}})",
                "rack_touch.bore_diameter: missing: rack_touch.feature \"bore\" needs it"},
        Refused{R"({"rack_touch": {"bore_diameter": 3.0}})",
                "rack_touch.bore_diameter: must be above twice rack_touch.stylus_radius (3), got 3"},
        Refused{R"({"rack_touch": {"top": null}})", "rack_touch.top: missing"},
        Refused{R"({"rack_touch": {"depth": 0}})",
                "rack_touch.depth: must be from 0.001 to 1000 mm, got 0"},
        Refused{R"({"rack_touch": {"feature": "faces", "x_face": {"x": 0, "y": 3},
                     "y_face": {"x": 0, "y": 3}}})",
                "rack_touch.x_face.x: must not be 0: its sign says on which side of the pocket "
                "the face lies"},
        Refused{R"({"rack_touch": {"feature": "faces", "x_face": {"x": 4, "y": 3}}})",
                "rack_touch.y_face: missing"},
        Refused{R"({"rack_touch": {"feature": "fork"},
                    "pocket_side_offset": {"x": 30.0, "y": 30.0}})",
                "pockets.1.side_offset: a fork (rack_touch.feature) needs a side offset longer "
                "in X or in Y: the jaws are touched across the other axis"},
        Refused{R"({"rack_touch": {"datum": {"pocket": 9}}})",
                "rack_touch.datum.pocket: pocket 9 is not in pockets"},
        Refused{R"({"rack_touch": {"datum": {"pocket": 1, "x": 50}}})",
                "rack_touch.datum: needs x, y and z together (teach-datum writes them), or none"},
        Refused{R"({"rack_touch": {"check_every_changes": 20}})",
                "rack_touch.check_every_changes: needs rack_touch.datum: the drift check touches "
                "it"},
        Refused{R"({"rack_touch": {"datum": {"pocket": 1}, "check_every_changes": 2.5}})",
                "rack_touch.check_every_changes: must be a whole number, got 2.5"},
        Refused{R"({"rack_touch": {"datum": {"pocket": 1}, "check_at_start": 1}})",
                "rack_touch.check_at_start: expected true or false, got 1"},
        Refused{R"({"rack_touch": {"serch": 4}})",
                "rack_touch.serch: unknown key, did you mean \"search\"?"}));

}  // namespace
}  // namespace fatc
