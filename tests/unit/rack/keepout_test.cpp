// The rack's volume every motion but the changer's own keeps out of: its
// parts from the pockets, and where a move of the nose enters it with a tool.
#include "core/rack/keepout.hpp"

#include <gtest/gtest.h>

#include "test_config.hpp"

namespace fatc {
namespace {

// The valid config: six side pockets in a row along X at y 20, z -80, 50 apart,
// side offset 40 (margin 20), above_chuck 20: holders' tops at -60, volume to -55.
TEST(RackVolume, shouldMakeARowOfPocketsOneBoxUpToTheHoldersTopsAndTheMarginAbove) {
  const Config config = test::valid_config();
  const auto volume = rack_volume(config);
  ASSERT_EQ(volume.size(), 1u);
  EXPECT_EQ(volume[0].pockets.size(), config.pockets.size());
  EXPECT_DOUBLE_EQ(volume[0].box.low.x, 50.0 - 20.0);
  EXPECT_DOUBLE_EQ(volume[0].box.high.x, 300.0 + 20.0);
  EXPECT_DOUBLE_EQ(volume[0].box.low.y, 0.0);
  EXPECT_DOUBLE_EQ(volume[0].box.high.y, 40.0);
  EXPECT_DOUBLE_EQ(volume[0].box.high.z, -80.0 + 20.0 + 5.0);
  EXPECT_LT(volume[0].box.low.z, -1e9);  // no floor
}

TEST(RackVolume, shouldKeepPocketsFarApartInPartsOfTheirOwn) {
  Config config = test::valid_config();
  config.pockets.at(6).at = {300.0, 250.0, -70.0};  // a second rack, 210 behind the first
  config.rack_keepout_above = 2.0;
  const auto volume = rack_volume(config);
  ASSERT_EQ(volume.size(), 2u);
  EXPECT_EQ(volume[1].pockets.size(), 1u);
  EXPECT_EQ(volume[1].pockets[0].number, 6);
  EXPECT_DOUBLE_EQ(volume[1].box.high.z, -70.0 + 20.0 + 2.0);
  EXPECT_DOUBLE_EQ(volume[0].box.high.x, 250.0 + 20.0);
}

TEST(RackEntry, shouldFindAMoveDownIntoAPocketsColumnAndNameThePocket) {
  const auto volume = rack_volume(test::valid_config());
  const auto entry = rack_entry(volume, {150.0, 20.0, -5.0}, {150.0, 20.0, -80.0}, 0.0);
  ASSERT_TRUE(entry);
  EXPECT_EQ(entry->pocket, 3);
  EXPECT_NEAR(entry->nose.z, -55.0, 1e-5);
}

TEST(RackEntry, shouldRaiseTheVolumeByTheToolsLength) {
  const auto volume = rack_volume(test::valid_config());
  const auto entry = rack_entry(volume, {150.0, 20.0, -5.0}, {150.0, 20.0, -40.0}, 30.0);
  ASSERT_TRUE(entry);
  EXPECT_NEAR(entry->nose.z, -25.0, 1e-5);
  EXPECT_FALSE(rack_entry(volume, {150.0, 20.0, -5.0}, {150.0, 20.0, -40.0}, 10.0));
}

TEST(RackEntry, shouldFindAMoveSidewaysIntoTheRackAtPocketHeight) {
  const auto volume = rack_volume(test::valid_config());
  const auto entry = rack_entry(volume, {100.0, 120.0, -80.0}, {100.0, 20.0, -80.0}, 0.0);
  ASSERT_TRUE(entry);
  EXPECT_EQ(entry->pocket, 2);
  EXPECT_NEAR(entry->nose.y, 40.0, 1e-5);
}

TEST(RackEntry, shouldLetMovesBesideAndAboveTheRackThrough) {
  const auto volume = rack_volume(test::valid_config());
  // Low, in the work area just in front of the rack.
  EXPECT_FALSE(rack_entry(volume, {30.0, 45.0, -100.0}, {320.0, 45.0, -100.0}, 0.0));
  // Over the rack, the tip above the volume.
  EXPECT_FALSE(rack_entry(volume, {30.0, 20.0, -20.0}, {320.0, 20.0, -20.0}, 30.0));
  // Leaving the rack from inside it is no entry.
  EXPECT_FALSE(rack_entry(volume, {150.0, 20.0, -80.0}, {150.0, 20.0, -5.0}, 0.0));
}

TEST(RackEntry, shouldFindADiagonalThatCutsTheRacksCorner) {
  const auto volume = rack_volume(test::valid_config());
  const auto entry = rack_entry(volume, {10.0, 60.0, -60.0}, {60.0, 10.0, -60.0}, 0.0);
  ASSERT_TRUE(entry);
  EXPECT_EQ(entry->pocket, 1);
}

TEST(ConfigRackKeepout, shouldTakeAnyNumberOfGroupsWhenSwitchedOffAndDefaultTheHeight) {
  std::string pockets;
  for (int i = 0; i < 9; ++i) {
    pockets += ",\"" + std::to_string(10 + i) + "\": {\"x\": " + std::to_string(1000 + 200 * i) + "}";
  }
  std::string text = test::kValidConfig;
  text.insert(text.find("\"6\":"), pockets.substr(1) + ", ");
  EXPECT_FALSE(parse_config(text).config);
  text.insert(text.rfind('}'), ", \"rack_keepout_all_motion\": false");
  const auto read = parse_config(text);
  ASSERT_TRUE(read.config) << read.errors.front();
  EXPECT_FALSE(read.config->rack_keepout_all_motion);
  EXPECT_TRUE(test::valid_config().rack_keepout_all_motion);
  EXPECT_DOUBLE_EQ(test::valid_config().keepout_above(), 5.0);
  EXPECT_DOUBLE_EQ(test::valid_config("\"units\": \"inch\"").keepout_above(), 0.2);
}

TEST(KeepoutState, shouldBeArmedOnlyOnAReadyMachineOutsideTheChangersOwnMoves) {
  const Config config = test::valid_config();
  KeepoutInputs in{true, true, false, false};
  EXPECT_EQ(keepout_state(config, in), KeepoutState::armed);
  in.changer_busy = true;
  EXPECT_EQ(keepout_state(config, in), KeepoutState::lifted_for_changer);
  in.changer_busy = false;
  in.operator_lifts = true;
  EXPECT_EQ(keepout_state(config, in), KeepoutState::lifted_by_operator);
  in.machine_ready = false;
  EXPECT_EQ(keepout_state(config, in), KeepoutState::not_armed);
  EXPECT_EQ(keepout_state(test::valid_config(R"("rack_keepout_all_motion": false)"), in),
            KeepoutState::off);
  EXPECT_STREQ(keepout_words(KeepoutState::off),
               "rack keep-out OFF (rack_keepout_all_motion is false)");
}

TEST(KeepoutRefusal, shouldNameWhatMovedThePocketTheToolAndWhereItStopped) {
  EXPECT_EQ(keepout_refusal(test::valid_config(), "program line 12", 3, 1, 30.0,
                            {150.0, 20.0, -21.25}),
            "program line 12 would have entered the rack at pocket 3 with T1 (length 30.0000 mm): "
            "stopped near X150.000 Y20.000 Z-21.250 and aborted; move clear above or beside the "
            "rack");
  EXPECT_NE(keepout_refusal(test::valid_config(), "a jog", 1, 0, 0.0, {}).find("empty spindle"),
            std::string::npos);
}

}  // namespace
}  // namespace fatc
