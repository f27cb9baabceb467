// The component's side of the I/O check: a button drives its output once,
// the answer is timed on the component's clock, the changer keeps its own
// command and sees the held output's sensors as they were.
#include "linuxcnc/live/io_check_driver.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "linuxcnc/live/hal_pins_detail.hpp"
#include "test_config.hpp"

namespace fatc::linuxcnc {
namespace {

using Clock = IoCheckDriver::Clock;
using std::chrono::milliseconds;

/// The I/O check's pins and the outputs, each pointing at storage of its own.
struct IoPins {
  hal_bit_t chuck = 0, cover = 0, air = 0, held = 0, holding = 0;
  hal_bit_t release = 0, clamp = 0, open = 0, close = 0, blast = 0;
  HalPins pins{};
  IoPins() {
    pins.chuck = &chuck;
    pins.rack_cover_open = &cover;
    pins.air_blast = &air;
    pins.io_check_held = &held;
    pins.io_check_holding_tool = &holding;
    pins.io_check_chuck_release = &release;
    pins.io_check_chuck_clamp = &clamp;
    pins.io_check_cover_open = &open;
    pins.io_check_cover_close = &close;
    pins.io_check_air_blast = &blast;
  }
};

struct Said : Ports {
  std::vector<std::string> lines;
  void publish(const Step&) override {}
  void set_chuck_open(bool) override {}
  void set_rack_cover_open(bool) override {}
  void set_air_blast(bool) override {}
  void start_timer(double) override {}
  void cancel_timer() override {}
  void tell(MessageKind, const std::string& text) override { lines.push_back(text); }
  void ask(const Prompt&) override {}
  void save(const ToolState&) override {}
  void write_found(const std::vector<Found>&, bool) override {}
  void unexpected(const std::string&, const std::string&) override {}
};

struct IoRig {
  Config config = test::valid_config(
      R"("sensors": {"drawbar_open": true, "drawbar_closed": true, "tool_present": true},
         "sensor_timeout_seconds": 0.5, "air_blast": true)");
  IoPins io;
  IoCheckDriver driver{&io.pins};
  Said said;
  Clock::time_point now{};
  SensorReadings read;

  IoRig() {
    read.set(Sensor::drawbar_closed, true);
    driver.changer_sets(IoOutput::chuck, false);
  }
  IoFacts facts() const {
    IoFacts f;
    f.tools = ToolState::fresh(config);
    f.machine_on = f.homed = true;
    f.nose = Point{120.0, 80.0, -5.0};
    return f;
  }
  void poll(IoFacts f) {
    driver.seen_by_changer(read);
    driver.poll(now, config, read, std::move(f), said);
  }
  void poll() { poll(facts()); }
  /// A button's press as the panel gives it: up one poll, down the next.
  void press(hal_bit_t& button) {
    button = 1;
    poll();
    button = 0;
    now += milliseconds(20);
    poll();
  }
};

TEST(IoCheckDriverTest, shouldTimeTheDrawbarOnTheComponentsClock) {
  IoRig rig;
  rig.io.release = 1;
  rig.poll();
  EXPECT_TRUE(rig.io.chuck);
  EXPECT_TRUE(rig.io.held);
  EXPECT_TRUE(rig.driver.timing());
  rig.now += milliseconds(180);
  rig.read.set(Sensor::drawbar_closed, false);
  rig.read.set(Sensor::drawbar_open, true);
  rig.poll();
  ASSERT_EQ(rig.said.lines.size(), 1u);
  EXPECT_EQ(rig.said.lines[0],
            "I/O check: drawbar opened in 0.18 s; your timeout 0.5 s (sensor_timeout_seconds)");
  EXPECT_EQ(rig.driver.words().last,
            "drawbar opened in 0.18 s; your timeout 0.5 s (sensor_timeout_seconds)");
  EXPECT_FALSE(rig.driver.timing());
}

TEST(IoCheckDriverTest, shouldHideAHeldOutputsSensorsFromTheChanger) {
  IoRig rig;
  rig.press(rig.io.release);
  rig.read.set(Sensor::drawbar_closed, false);
  rig.read.set(Sensor::drawbar_open, true);
  const SensorReadings seen = rig.driver.seen_by_changer(rig.read);
  EXPECT_TRUE(seen.reads(Sensor::drawbar_closed));
  EXPECT_FALSE(seen.reads(Sensor::drawbar_open));
  EXPECT_TRUE(rig.driver.holds_chuck_open());
  // Clamped again and answered: the changer's once more, and it sees them as they are.
  rig.press(rig.io.clamp);
  rig.read.set(Sensor::drawbar_closed, true);
  rig.read.set(Sensor::drawbar_open, false);
  rig.poll();
  EXPECT_FALSE(rig.io.held);
  EXPECT_FALSE(rig.io.chuck);
  rig.read.set(Sensor::tool_present, true);
  EXPECT_TRUE(rig.driver.seen_by_changer(rig.read).reads(Sensor::tool_present));
}

TEST(IoCheckDriverTest, shouldSayNoAnswerOnceTheTimeoutPassed) {
  IoRig rig;
  rig.press(rig.io.release);
  rig.now += milliseconds(600);
  rig.poll();
  ASSERT_EQ(rig.said.lines.size(), 1u);
  EXPECT_EQ(rig.said.lines[0],
            "I/O check: drawbar opened: NO answer within your timeout 0.5 s "
            "(sensor_timeout_seconds); it reads drawbar-open off, drawbar-closed on: check the "
            "sensor, its wiring and the output");
}

TEST(IoCheckDriverTest, shouldRefuseWithTheReasonAndDriveNothing) {
  IoRig rig;
  IoFacts f = rig.facts();
  f.spindle_stopped = false;
  rig.io.release = 1;
  rig.poll(f);
  EXPECT_FALSE(rig.io.chuck);
  EXPECT_FALSE(rig.io.held);
  ASSERT_EQ(rig.said.lines.size(), 1u);
  EXPECT_EQ(rig.said.lines[0],
            "I/O check: chuck-release refused: the spindle is on (spindle-stopped off): the chuck "
            "opens only on a spindle that stands");
  EXPECT_EQ(rig.driver.words().refusals[0].second,
            "the spindle is on (spindle-stopped off): the chuck opens only on a spindle that "
            "stands");
}

TEST(IoCheckDriverTest, shouldGiveTheOutputsBackWhenAProgramStarts) {
  IoRig rig;
  rig.press(rig.io.release);
  ASSERT_TRUE(rig.io.chuck);
  IoFacts f = rig.facts();
  f.busy = "a program or MDI command is running";
  rig.poll(f);
  EXPECT_FALSE(rig.io.chuck);
  EXPECT_FALSE(rig.io.held);
  EXPECT_EQ(rig.said.lines.back(),
            "I/O check: the chuck back as the changer commands: a program or MDI command is "
            "running");
}

TEST(IoCheckDriverTest, shouldLetTheChangerTakeItsOutputBack) {
  IoRig rig;
  rig.press(rig.io.release);
  rig.driver.changer_sets(IoOutput::chuck, false);
  EXPECT_FALSE(rig.io.chuck);
  EXPECT_FALSE(rig.io.held);
  EXPECT_FALSE(rig.driver.timing());
}

TEST(IoCheckDriverTest, shouldBlowTheAirForItsSecondThenStop) {
  IoRig rig;
  rig.press(rig.io.blast);
  EXPECT_TRUE(rig.io.air);
  EXPECT_EQ(rig.said.lines.at(0),
            "I/O check: air blast on for 1.0 s; no sensor answers it: listen and feel at the "
            "spindle's taper");
  rig.now += milliseconds(1000);
  rig.poll();
  EXPECT_FALSE(rig.io.air);
  EXPECT_FALSE(rig.io.held);
}

TEST(IoCheckDriverTest, shouldReleaseOnAToolOnlyWhenTheOperatorHoldsIt) {
  IoRig rig;
  IoFacts f = rig.facts();
  f.tools.put_in_spindle(3);
  rig.io.release = 1;
  rig.poll(f);
  EXPECT_FALSE(rig.io.chuck);
  rig.io.release = 0;
  rig.poll(f);
  rig.io.holding = 1;
  rig.io.release = 1;
  rig.poll(f);
  EXPECT_TRUE(rig.io.chuck);
}

}  // namespace
}  // namespace fatc::linuxcnc
