#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/dry_run/teach.hpp"
#include "test_config.hpp"

// What the rack found by touch writes through the teach path: the datum's
// x, y, z, and several pockets in one text, all or nothing.

namespace fatc {
namespace {

using Kind = TeachTarget::Kind;
using OrderedJson = nlohmann::ordered_json;

const char* const kTouch = R"({"rack_touch": {
  "feature": "bore", "stylus_radius": 1.5, "bore_diameter": 30.0, "top": {"x": 0, "y": -20},
  "pocket_above_top": 10.0, "depth": 5.0, "datum": {"pocket": 1}}})";

TEST(TeachByTouch, shouldWriteTheDatumWhereItsFeatureWasFound) {
  const TeachResult r = teach(test::sample_config_with(kTouch), {Kind::datum, 0},
                              {50.41, 19.73, -79.87}, std::nullopt);
  ASSERT_TRUE(r.text) << r.error;
  EXPECT_EQ(r.change, "the rack datum: x unset → 50.4100, y unset → 19.7300, z unset → -79.8700");
  const auto datum = OrderedJson::parse(*r.text)["rack_touch"]["datum"];
  EXPECT_EQ(datum.dump(), R"({"pocket":1,"x":50.41,"y":19.73,"z":-79.87})");
  EXPECT_EQ(parse_config(*r.text).config->rack_touch->datum->x, 50.41);
}

TEST(TeachByTouch, shouldRefuseTheDatumWhereConfigJsonNamesNone) {
  const TeachResult r = teach(test::kValidConfig, {Kind::datum, 0}, {50, 20, -80}, std::nullopt);
  EXPECT_FALSE(r.text);
  EXPECT_EQ(r.error,
            "teach the rack datum at X50 Y20 Z-80: not written: config.json has no "
            "rack_touch.datum: name the datum's pocket there first, \"datum\": {\"pocket\": N}");
  EXPECT_EQ(parse_teach_target("datum")->kind, Kind::datum);
}

TEST(TeachByTouch, shouldWriteSeveralPocketsIntoOneText) {
  const TeachResult r = teach_all(test::sample_config_with(kTouch),
                                  {{{Kind::pocket, 2}, {100.41, 19.73, -79.87}},
                                   {{Kind::pocket, 3}, {150.2, 20.1, -80.0}}},
                                  std::nullopt);
  ASSERT_TRUE(r.text) << r.error;
  EXPECT_EQ(r.change,
            "pocket 2: x 100.0000 → 100.4100, y 20.0000 → 19.7300, z -80.0000 → -79.8700\n"
            "pocket 3: x 150.0000 → 150.2000, y 20.0000 → 20.1000, z -80.0000 (unchanged)");
  const Config c = *parse_config(*r.text).config;
  EXPECT_EQ(c.pockets.at(2).at.x, 100.41);
  EXPECT_EQ(c.pockets.at(3).at.y, 20.1);
}

TEST(TeachByTouch, shouldWriteNothingWhenOnePocketIsRefused) {
  const TeachResult r = teach_all(test::sample_config_with(kTouch),
                                  {{{Kind::pocket, 2}, {100.41, 19.73, -79.87}},
                                   {{Kind::pocket, 3}, {110.0, 20.0, -80.0}}},
                                  std::nullopt);
  EXPECT_FALSE(r.text);
  EXPECT_EQ(r.error.rfind("teach pocket 3 at X110 Y20 Z-80: not written: ", 0), 0u) << r.error;
}

}  // namespace
}  // namespace fatc
