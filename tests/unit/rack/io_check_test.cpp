// The I/O check's rule: what each sensor should read and why, which outputs
// may be driven now and why not, and how an answer's time is told.
#include "core/rack/io_check.hpp"

#include <gtest/gtest.h>

#include "test_config.hpp"

namespace fatc {
namespace {

/// Every sensor wired, a rack cover, the air blast; pockets 1 and 2 with sensors.
Config wired_config() {
  return test::valid_config(
      R"("sensors": {"tool_present": true, "drawbar_open": true, "drawbar_closed": true,
          "air_pressure": true, "zero_speed": true, "pocket_occupancy": [1, 2]},
         "rack_cover": {"opened_sensor": true, "closed_sensor": true, "timeout_seconds": 2.0},
         "air_blast": true, "sensor_timeout_seconds": 0.5)");
}

/// A machine on and homed, idle, the spindle off and empty, well above the rack.
IoFacts idle_facts(const Config& config) {
  IoFacts f;
  f.tools = ToolState::fresh(config);
  f.machine_on = true;
  f.homed = true;
  f.nose = Point{120.0, 80.0, -5.0};
  return f;
}

/// What a clamped, empty spindle with air reads: as it should.
SensorReadings clamped_readings() {
  SensorReadings r;
  r.set(Sensor::zero_speed, true);
  r.set(Sensor::drawbar_closed, true);
  r.set(Sensor::air_pressure, true);
  r.set(Sensor::rack_cover_closed, true);
  r.pockets = {{1, true}, {2, true}};
  return r;
}

const IoSensorLine& line_of(const std::vector<IoSensorLine>& lines, const std::string& pin) {
  for (const IoSensorLine& line : lines) {
    if (line.pin == pin) return line;
  }
  throw std::runtime_error("no line for " + pin);
}

TEST(IoCheckTest, shouldExpectTheDrawbarClosedWhenTheChuckIsClamped) {
  const Config config = wired_config();
  const auto lines = io_sensor_lines(config, clamped_readings(), idle_facts(config));
  EXPECT_EQ(line_of(lines, "drawbar-closed").words(),
            "drawbar-closed: on, expected on (the chuck is clamped)");
  EXPECT_EQ(line_of(lines, "drawbar-open").words(),
            "drawbar-open: off, expected off (the chuck is clamped)");
  EXPECT_EQ(line_of(lines, "tool-present").words(),
            "tool-present: off, expected off (the spindle is empty)");
  EXPECT_EQ(line_of(lines, "pocket-occupied-1").words(),
            "pocket-occupied-1: on, expected on (tool 1 is recorded in it)");
  for (const IoSensorLine& line : lines) EXPECT_TRUE(line.agrees()) << line.words();
}

TEST(IoCheckTest, shouldListOnlyTheWiredSensorsInTheirOrder) {
  const Config config =
      test::valid_config(R"("sensors": {"drawbar_closed": true, "zero_speed": true})");
  const auto lines = io_sensor_lines(config, {}, idle_facts(config));
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].pin, "zero-speed");
  EXPECT_EQ(lines[1].pin, "drawbar-closed");
}

TEST(IoCheckTest, shouldFlagASensorThatReadsOtherwiseThanTheBeliefSays) {
  const Config config = wired_config();
  SensorReadings r = clamped_readings();
  r.set(Sensor::drawbar_closed, false);
  const auto line = line_of(io_sensor_lines(config, r, idle_facts(config)), "drawbar-closed");
  EXPECT_FALSE(line.agrees());
  EXPECT_EQ(line.words(),
            "drawbar-closed: off, expected on (the chuck is clamped): NOT as expected, check its "
            "wiring");
}

TEST(IoCheckTest, shouldExpectWhatTheCommandedOutputsAndTheToolsSay) {
  const Config config = wired_config();
  IoFacts f = idle_facts(config);
  f.chuck_open = true;
  f.cover_open = true;
  f.spindle_stopped = false;
  f.tools.put_in_spindle(2);
  const auto lines = io_sensor_lines(config, clamped_readings(), f);
  EXPECT_EQ(line_of(lines, "drawbar-open").expected, true);
  EXPECT_EQ(line_of(lines, "drawbar-open").why, "the chuck is released");
  EXPECT_EQ(line_of(lines, "rack-cover-opened").expected, true);
  EXPECT_EQ(line_of(lines, "rack-cover-closed").why, "the cover is commanded open");
  EXPECT_EQ(line_of(lines, "zero-speed").expected, false);
  // A released chuck may hold its tool or not.
  EXPECT_FALSE(line_of(lines, "tool-present").expected.has_value());
  EXPECT_EQ(line_of(lines, "pocket-occupied-2").words(),
            "pocket-occupied-2: on, expected off (its tool 2 is recorded elsewhere): NOT as "
            "expected, check its wiring");
  f.chuck_open = false;
  EXPECT_EQ(line_of(io_sensor_lines(config, clamped_readings(), f), "tool-present").words(),
            "tool-present: off, expected on (tool 2 is in the spindle): NOT as expected, check "
            "its wiring");
}

TEST(IoCheckTest, shouldAllowEveryOutputOnAnIdleMachineWithAnEmptySpindle) {
  const Config config = wired_config();
  for (const IoActionDeclaration& a : kIoActions) {
    EXPECT_EQ(io_refusal(a.action, config, clamped_readings(), idle_facts(config)), std::nullopt)
        << a.name;
  }
}

TEST(IoCheckTest, shouldRefuseEverythingWhenTheMachineIsOff) {
  const Config config = wired_config();
  IoFacts f = idle_facts(config);
  f.machine_on = false;
  for (const IoActionDeclaration& a : kIoActions) {
    EXPECT_EQ(io_refusal(a.action, config, clamped_readings(), f),
              "the machine is off (machine-on off): turn it on first")
        << a.name;
  }
}

TEST(IoCheckTest, shouldRefuseEverythingWithTheReasonWhileBusy) {
  const Config config = wired_config();
  IoFacts f = idle_facts(config);
  f.busy = "a program or MDI command is running";
  for (const IoActionDeclaration& a : kIoActions) {
    EXPECT_EQ(io_refusal(a.action, config, clamped_readings(), f), *f.busy) << a.name;
  }
}

TEST(IoCheckTest, shouldRefuseAReleaseWhileTheSpindleIsOn) {
  const Config config = wired_config();
  IoFacts f = idle_facts(config);
  f.spindle_stopped = false;
  EXPECT_EQ(io_refusal(IoAction::chuck_release, config, clamped_readings(), f),
            "the spindle is on (spindle-stopped off): the chuck opens only on a spindle that "
            "stands");
  // Clamping stays allowed: it is the safe way.
  EXPECT_EQ(io_refusal(IoAction::chuck_clamp, config, clamped_readings(), f), std::nullopt);
}

TEST(IoCheckTest, shouldRefuseAReleaseWhileZeroSpeedSaysItStillTurns) {
  const Config config = wired_config();
  SensorReadings r = clamped_readings();
  r.set(Sensor::zero_speed, false);
  EXPECT_EQ(io_refusal(IoAction::chuck_release, config, r, idle_facts(config)),
            "the spindle still turns (zero-speed off): the chuck opens only on a spindle that "
            "stands");
}

TEST(IoCheckTest, shouldRefuseAReleaseWithoutAir) {
  const Config config = wired_config();
  SensorReadings r = clamped_readings();
  r.set(Sensor::air_pressure, false);
  EXPECT_EQ(io_refusal(IoAction::chuck_release, config, r, idle_facts(config)),
            "no air (air-pressure-ok off): the drawbar cannot open");
}

TEST(IoCheckTest, shouldRefuseAReleaseWithAToolUnlessTheOperatorHoldsIt) {
  const Config config = wired_config();
  IoFacts f = idle_facts(config);
  f.tools.put_in_spindle(3);
  EXPECT_EQ(io_refusal(IoAction::chuck_release, config, clamped_readings(), f),
            "tool 3 is in the spindle: it drops when the chuck opens; hold it and say so "
            "(io-check-holding-tool, --holding-tool)");
  f.holding_tool = true;
  EXPECT_EQ(io_refusal(IoAction::chuck_release, config, clamped_readings(), f), std::nullopt);
}

TEST(IoCheckTest, shouldRefuseAReleaseWhenToolPresentReadsAToolTheBeliefDoesNotHave) {
  const Config config = wired_config();
  SensorReadings r = clamped_readings();
  r.set(Sensor::tool_present, true);
  EXPECT_EQ(io_refusal(IoAction::chuck_release, config, r, idle_facts(config)),
            "a tool is in the spindle (tool-present on): it drops when the chuck opens; hold it "
            "and say so (io-check-holding-tool, --holding-tool)");
}

TEST(IoCheckTest, shouldRefuseAReleaseWhenWhatTheSpindleHoldsIsUncertain) {
  const Config config = wired_config();
  IoFacts f = idle_facts(config);
  f.tools.uncertain = true;
  EXPECT_NE(io_refusal(IoAction::chuck_release, config, clamped_readings(), f), std::nullopt);
}

TEST(IoCheckTest, shouldRefuseClosingTheCoverOverTheSpindle) {
  const Config config = wired_config();
  IoFacts f = idle_facts(config);
  f.nose = Point{50.0, 20.0, -70.0};  // down by pocket 1
  EXPECT_EQ(io_refusal(IoAction::cover_close, config, clamped_readings(), f),
            "the spindle is in the rack (X50.000 Y20.000 Z-70.000, by pocket 1): the cover would "
            "close on it; move it up out of the rack first");
  // Opening it never closes on anything.
  EXPECT_EQ(io_refusal(IoAction::cover_open, config, clamped_readings(), f), std::nullopt);
}

TEST(IoCheckTest, shouldCountTheToolBelowTheNoseForTheCover) {
  const Config config = wired_config();
  // Pocket 1's part reaches to Z-55 (its holder top -60, 5 mm above).
  EXPECT_EQ(io_pocket_under_spindle(config, {50.0, 20.0, -40.0}, 0.0), 0);
  EXPECT_EQ(io_pocket_under_spindle(config, {50.0, 20.0, -40.0}, 30.0), 1);
  EXPECT_EQ(io_pocket_under_spindle(config, {120.0, 80.0, -70.0}, 0.0), 0);
}

TEST(IoCheckTest, shouldRefuseClosingTheCoverWhereTheSpindleIsNotKnown) {
  const Config config = wired_config();
  IoFacts f = idle_facts(config);
  f.homed = false;
  EXPECT_EQ(io_refusal(IoAction::cover_close, config, clamped_readings(), f),
            "where the spindle stands is not known (not homed): the cover could close on it");
}

TEST(IoCheckTest, shouldRefuseOutputsTheConfigDoesNotDrive) {
  const Config config = test::valid_config();
  const IoFacts f = idle_facts(config);
  EXPECT_EQ(io_refusal(IoAction::cover_open, config, {}, f),
            "config.json has no rack_cover: there is none to drive");
  EXPECT_EQ(io_refusal(IoAction::air_blast, config, {}, f),
            "config.json's air_blast is off: the changer drives no air blast");
}

TEST(IoCheckTest, shouldTellTheTimeAgainstTheTimeout) {
  const Config config = wired_config();
  EXPECT_EQ(io_timing_words(IoAction::chuck_release, config, 0.18, {}),
            "drawbar opened in 0.18 s; your timeout 0.5 s (sensor_timeout_seconds)");
  EXPECT_EQ(io_timing_words(IoAction::cover_open, config, 0.21, {}),
            "rack cover opened in 0.21 s; your timeout 2 s (rack_cover.timeout_seconds)");
}

TEST(IoCheckTest, shouldWarnPastHalfTheTimeout) {
  const Config config = wired_config();
  EXPECT_EQ(io_timing_words(IoAction::chuck_clamp, config, 0.26, {}),
            "drawbar closed in 0.26 s; your timeout 0.5 s (sensor_timeout_seconds): slow, over "
            "50% of the timeout; a change may time out on a cold morning or with less air");
  EXPECT_EQ(io_timing_words(IoAction::chuck_clamp, config, 0.25, {}),
            "drawbar closed in 0.25 s; your timeout 0.5 s (sensor_timeout_seconds)");
}

TEST(IoCheckTest, shouldSayWhatTheSensorsReadWhenNoAnswerCame) {
  const Config config = wired_config();
  EXPECT_EQ(io_timing_words(IoAction::chuck_release, config, std::nullopt, clamped_readings()),
            "drawbar opened: NO answer within your timeout 0.5 s (sensor_timeout_seconds); it "
            "reads drawbar-open off, drawbar-closed on: check the sensor, its wiring and the "
            "output");
}

TEST(IoCheckTest, shouldSayNothingTimesAnOutputWithoutSensor) {
  const Config config = test::valid_config(R"("air_blast": true)");
  EXPECT_EQ(io_timeout(IoAction::chuck_release, config), std::nullopt);
  EXPECT_EQ(io_timing_words(IoAction::chuck_release, config, std::nullopt, {}),
            "chuck released; no drawbar sensor is wired to time it (sensors.drawbar_open, "
            "sensors.drawbar_closed)");
  EXPECT_EQ(io_timing_words(IoAction::air_blast, config, std::nullopt, {}),
            "air blast on for 1.0 s; no sensor answers it: listen and feel at the spindle's taper");
}

TEST(IoCheckTest, shouldWaitForTheCoversCloseAsLongAsTheChangerDoes) {
  const Config config = wired_config();
  EXPECT_EQ(io_timeout(IoAction::cover_close, config)->seconds, 2.0);
  const Config slow_sensors = test::valid_config(
      R"("rack_cover": {"closed_sensor": true, "timeout_seconds": 0.5}, "sensor_timeout_seconds": 3.0)");
  EXPECT_EQ(io_timeout(IoAction::cover_close, slow_sensors)->key, "sensor_timeout_seconds");
}

TEST(IoCheckTest, shouldAnswerOnceEveryWiredSensorOfTheActionReadsIt) {
  const Config config = wired_config();
  SensorReadings r = clamped_readings();
  EXPECT_TRUE(io_answered(IoAction::chuck_clamp, config, r));
  EXPECT_FALSE(io_answered(IoAction::chuck_release, config, r));
  r.set(Sensor::drawbar_open, true);
  EXPECT_FALSE(io_answered(IoAction::chuck_release, config, r));  // closed still on
  r.set(Sensor::drawbar_closed, false);
  EXPECT_TRUE(io_answered(IoAction::chuck_release, config, r));
}

TEST(IoCheckTest, shouldNameEachActionBothWays) {
  for (const IoActionDeclaration& a : kIoActions) {
    EXPECT_EQ(io_action_named(a.name), a.action);
    EXPECT_STREQ(io_action_name(a.action), a.name);
  }
  EXPECT_EQ(io_action_named("flush"), std::nullopt);
}

}  // namespace
}  // namespace fatc
