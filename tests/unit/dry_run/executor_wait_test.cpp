// The executor stops a program when no step comes within STEP_TIMEOUT, so
// --check compares it with the longest wait between two steps that the plans
// themselves report, with every sensor answering as late as it may.
#include <gtest/gtest.h>

#include "core/dry_run/simulator.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::valid_config;

constexpr const char* kWired =
    R"("sensor_timeout_seconds": 2, "sensors": {"tool_present": true, "drawbar_open": true,
       "drawbar_closed": true, "air_pressure": true, "zero_speed": true,
       "pocket_occupancy": [1, 2]})";

TEST(ExecutorWait, shouldBeTheSpindlesStopWhenThatIsTheLongest) {
  EXPECT_DOUBLE_EQ(longest_executor_wait(valid_config(R"("spindle_stop_timeout_seconds": 10)")),
                   10.0);
}

TEST(ExecutorWait, shouldBeTheSettleAndGripWithoutSensors) {
  // chuck_seconds 0.5: the spindle settles on the tool, then the chuck grips it.
  EXPECT_DOUBLE_EQ(longest_executor_wait(valid_config(R"("spindle_stop_timeout_seconds": 0.1)")),
                   1.0);
}

TEST(ExecutorWait, shouldCountEachSensorCheckOfTheFlushAtItsTimeout) {
  // Over the pocket: air 2, pulse 0.2 and its drawbar check 2, pause 0.2 and
  // its check 2, the opening 0.5 and its check 2.
  const Config config =
      valid_config(std::string(R"("spindle_stop_timeout_seconds": 0.1, )") + kWired);
  EXPECT_NEAR(longest_executor_wait(config), 8.9, 1e-9);
}

TEST(ExecutorWait, shouldCountASecondGripAfterAFailedFirst) {
  // No flush: settle 0.5, grip 0.5 and its check 2, open 0.5 and its check 2,
  // grip 0.5 and its check 2.
  const Config config = valid_config(
      std::string(R"("spindle_stop_timeout_seconds": 0.1, "flush": {"pulses": 0}, )") + kWired);
  EXPECT_NEAR(longest_executor_wait(config), 8.0, 1e-9);
}

TEST(ExecutorWait, shouldCountTheRackCoverAtItsTimeout) {
  const Config config = valid_config(
      R"("spindle_stop_timeout_seconds": 0.1,
         "rack_cover": {"opened_sensor": true, "timeout_seconds": 12})");
  // The spindle stops (0.1 s), then the cover opens before the first move.
  EXPECT_NEAR(longest_executor_wait(config), 12.1, 1e-9);
}

TEST(ExecutorWait, shouldCountAChangeThatWaitsForTheCoverTheLastOneClosed) {
  const Config config = valid_config(
      R"("spindle_stop_timeout_seconds": 0.1, "sensor_timeout_seconds": 0.5,
         "rack_cover": {"closed_sensor": true, "seconds": 1, "timeout_seconds": 12})");
  // The next M6 waits up to 12 s for the cover to close (the spindle stops
  // meanwhile), then 1 s for it to open again before it moves.
  EXPECT_NEAR(longest_executor_wait(config), 13.0, 1e-9);
  const Config sensed = valid_config(
      R"("spindle_stop_timeout_seconds": 0.1,
         "rack_cover": {"opened_sensor": true, "closed_sensor": true, "timeout_seconds": 12})");
  // Closing and opening, each at its timeout.
  EXPECT_NEAR(longest_executor_wait(sensed), 24.0, 1e-9);
}

}  // namespace
}  // namespace fatc
