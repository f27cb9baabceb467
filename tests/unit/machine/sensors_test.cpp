// The optional sensors: every check the tables make with them, the retry of
// a pick-up, the comparison with the saved tool state at start, the probe
// window, and the words that reach the panel. The Simulator models the rack
// (the tool follows the chuck, the sensors read what is there); each test
// spoils one thing in it.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/machine/changer.hpp"
#include "core/dry_run/simulator.hpp"
#include "io/status_file.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using Lines = std::vector<std::string>;

const std::string kAllSensors =
    R"("sensors": {"tool_present": true, "drawbar_open": true, "drawbar_closed": true,
                   "air_pressure": true, "pocket_occupancy": true, "zero_speed": true})";

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// A changer on a Simulator that models the rack with every sensor wired;
/// the rack is as the tool state says, unless a test spoils it.
struct Rig {
  explicit Rig(int spindle = 0, const std::string& extra = kAllSensors,
               std::map<int, double> lengths = {})
      : config(test::valid_config(extra)) {
    tools = ToolState::fresh(config);
    tools.spindle = spindle;
    test::take_out(tools, spindle);
    tools.lengths = std::move(lengths);
    sim.model_rack(config, tools);
  }
  ~Rig() {
    EXPECT_TRUE(sim.unexpected_events.empty())
        << (sim.unexpected_events.empty() ? "" : sim.unexpected_events.front());
  }
  /// The changer starts and the machine becomes ready, the sensors reported.
  Changer& start() {
    changer = std::make_unique<Changer>(config, sim, tools);
    sim.report_sensors(*changer);
    changer->ready();
    return *changer;
  }
  void run() { sim.run(*changer); }
  /// Runs until `done` says so (checked before each event), at most `limit` events.
  void run_until(const std::function<bool()>& done, int limit = 500) {
    for (int i = 0; i < limit && !done(); ++i) {
      if (sim.run(*changer, 1) == 0) return;
    }
  }
  Status status() const { return changer->status(); }
  std::string activity() const { return changer->status().activity; }
  std::string last_error() const {
    const auto errors = sim.messages(MessageKind::error);
    return errors.empty() ? "" : errors.back();
  }
  /// The records since `from`: "rapid safe Z", "chuck open", "dwell 0.50", ...
  Lines lines(std::size_t from = 0) const {
    Lines out;
    char buffer[32];
    for (std::size_t i = from; i < sim.records.size(); ++i) {
      const Record& r = sim.records[i];
      if (r.kind == Record::Kind::step) {
        out.push_back(std::string(step_kind_name(r.step.kind)) + " " + r.step.label);
      } else if (r.kind == Record::Kind::chuck) {
        out.push_back(r.chuck_open ? "chuck open" : "chuck close");
      } else if (r.kind == Record::Kind::dwell) {
        std::snprintf(buffer, sizeof buffer, "dwell %.2f", r.seconds);
        out.push_back(buffer);
      }
    }
    return out;
  }
  std::size_t moves_since(std::size_t from) const {
    std::size_t moves = 0;
    for (std::size_t i = from; i < sim.records.size(); ++i) {
      if (sim.records[i].kind == Record::Kind::step && is_motion(sim.records[i].step.kind)) ++moves;
    }
    return moves;
  }
  bool last_step_is(const std::string& label) const {
    const auto moves = sim.motion_steps();
    return !moves.empty() && moves.back().label == label;
  }

  Config config;
  ToolState tools;
  Simulator sim;
  std::unique_ptr<Changer> changer;
};

// ---------------------------------------------------------------- config

TEST(SensorConfig, shouldLeaveEverySensorOffUnlessTheConfigWiresIt) {
  const Config plain = test::valid_config();
  EXPECT_FALSE(plain.sensors.any());
  EXPECT_DOUBLE_EQ(plain.sensor_timeout_seconds, 1.0);
  EXPECT_DOUBLE_EQ(plain.window(), 10.0);
  EXPECT_DOUBLE_EQ(
      test::valid_config(R"("units": "inch", "probe_check_tolerance": 0.004)").window(), 0.4);
}

TEST(SensorConfig, shouldReadEveryWiredSensorTheTimeoutAndTheWindow) {
  const Config c =
      test::valid_config(kAllSensors + R"(, "sensor_timeout_seconds": 0.5, "probe_window": 3)");
  for (const Sensor sensor : {Sensor::tool_present, Sensor::drawbar_open, Sensor::drawbar_closed,
                              Sensor::air_pressure, Sensor::zero_speed}) {
    EXPECT_TRUE(c.sensors.wired(sensor)) << declared(sensor).words.key;
  }
  EXPECT_EQ(c.sensors.pocket_occupancy, (std::set<int>{1, 2, 3, 4, 5, 6}));
  EXPECT_DOUBLE_EQ(c.sensor_timeout_seconds, 0.5);
  EXPECT_DOUBLE_EQ(c.window(), 3.0);
}

TEST(SensorConfig, shouldWireOnlyTheListedPockets) {
  const Config c = test::valid_config(R"("sensors": {"pocket_occupancy": [3, 1]})");
  EXPECT_EQ(c.sensors.pocket_occupancy, (std::set<int>{1, 3}));
  EXPECT_FALSE(c.sensors.wired(Sensor::tool_present));
}

struct Hostile {
  const char* extra;
  const char* expected;
};
class HostileSensorKeys : public ::testing::TestWithParam<Hostile> {};

TEST_P(HostileSensorKeys, shouldBeRefusedInOneLineNamingTheJsonPath) {
  std::string text = test::kValidConfig;
  text.insert(text.rfind('}'), std::string(",") + GetParam().extra);
  const ConfigResult result = parse_config(text);
  ASSERT_FALSE(result.config.has_value()) << GetParam().extra;
  ASSERT_EQ(result.errors.size(), 1u) << result.errors.front();
  EXPECT_EQ(result.errors.front(), GetParam().expected);
}

INSTANTIATE_TEST_SUITE_P(
    Each, HostileSensorKeys,
    ::testing::Values(
        Hostile{R"("sensors": [true])", "sensors: expected an object, got an array"},
        Hostile{R"("sensors": {"air_presure": true})",
                "sensors.air_presure: unknown key, did you mean \"air_pressure\"?"},
        Hostile{R"("sensors": {"zero_speed": 1})",
                "sensors.zero_speed: expected true or false, got 1"},
        Hostile{R"("sensors": {"drawbar_open": "true"})",
                "sensors.drawbar_open: expected true or false, got \"true\""},
        Hostile{R"("sensors": {"pocket_occupancy": [7]})",
                "sensors.pocket_occupancy[0]: pocket 7 is not in pockets"},
        Hostile{R"("sensors": {"pocket_occupancy": [1.5]})",
                "sensors.pocket_occupancy[0]: expected a pocket number (1 to 999999999), "
                "got 1.5"},
        Hostile{R"("sensors": {"pocket_occupancy": {"1": true}})",
                "sensors.pocket_occupancy: expected true, false or a list of pockets like [1, 2], "
                "got an "
                "object"},
        Hostile{R"("sensor_timeout_seconds": 0)",
                "sensor_timeout_seconds: must be from 0.01 to 60 seconds, got 0"},
        Hostile{R"("sensor_timeout_seconds": -0.5)",
                "sensor_timeout_seconds: must be from 0.01 to 60 seconds, got -0.5"},
        Hostile{R"("probe_window": -10)", "probe_window: must be from 0.001 to 1000 mm, got -10"},
        Hostile{R"("probe_window": 0.2, "probe_check_tolerance": 0.5, "probe_after_change": "check")",
                "probe_window: must be larger than probe_check_tolerance (0.5), got 0.2"}));

// ---------------------------------------------------------------- a healthy rack changes nothing

/// The records of a plan, the saves left out (sensors wired or not, the same
/// tool state is saved at the same points; the plan is what must match).
Lines plan_lines(const Simulator& sim) {
  Lines out;
  for (const Record& r : sim.records) {
    if (r.kind != Record::Kind::save) out.push_back(describe(r));
  }
  return out;
}

TEST(SensorsWired, shouldPlanEverySequenceAsWithoutSensorsWhenTheRackBehaves) {
  const Config plain = test::valid_config(R"("probe_after_change": "measure")");
  const Config wired = test::valid_config(kAllSensors + R"(, "probe_after_change": "measure")");
  for (const auto& [from, to] :
       std::vector<std::pair<int, int>>{{0, 3}, {1, 3}, {2, 0}, {2, 7}, {7, 1}}) {
    SCOPED_TRACE("M6 T" + std::to_string(to) + " from T" + std::to_string(from));
    EXPECT_EQ(plan_lines(plan_change(wired, from, to, -60.0)),
              plan_lines(plan_change(plain, from, to, -60.0)));
  }
  EXPECT_EQ(plan_lines(plan_load(wired, 4, 2, -60.0)), plan_lines(plan_load(plain, 4, 2, -60.0)));
  EXPECT_EQ(plan_lines(plan_unload(wired, 4, 2)), plan_lines(plan_unload(plain, 4, 2)));
}

TEST(SensorsWired, shouldChangeToolsWithEveryCheckPassing) {
  Rig rig(1);
  rig.start().tool_change(3);
  rig.run();
  EXPECT_EQ(rig.status().phase, Phase::idle) << rig.activity();
  EXPECT_EQ(rig.changer->tools().spindle, 3);
  EXPECT_EQ(rig.sim.rack.spindle, 3);
  EXPECT_EQ(rig.sim.rack.pockets[1], 1);
  EXPECT_TRUE(rig.sim.messages(MessageKind::error).empty()) << rig.last_error();
}

// ---------------------------------------------------------------- air pressure

TEST(AirPressure, shouldRefuseAChangeWithoutAirAndMoveNothing) {
  Rig rig(1);
  rig.sim.rack.air = false;
  rig.start().tool_change(3);
  rig.run();
  EXPECT_EQ(rig.last_error(),
            "M6 T3 refused: air pressure is low (air-pressure-ok off): the chuck cannot open");
  EXPECT_TRUE(rig.sim.motion_steps().empty());
  EXPECT_EQ(rig.status().phase, Phase::idle);
  rig.changer->load(4);  // tool 4 is in its pocket: refused for that first
  rig.changer->unload(4);
  EXPECT_TRUE(has(rig.last_error(), "unload of tool 4 refused: air pressure is low"))
      << rig.last_error();
}

TEST(AirPressure, shouldFaultWithTheChuckClosedWhenAirIsLostBeforeItOpens) {
  Rig rig(1);
  rig.start().tool_change(3);
  rig.sim.run(*rig.changer, 1);  // safe Z
  rig.sim.rack.air = false;
  rig.run();
  EXPECT_EQ(rig.status().phase, Phase::fault);
  EXPECT_EQ(rig.activity(),
            "fault: air pressure low (air-pressure-ok off) before the chuck opened at pocket 1; it "
            "stayed closed");
  EXPECT_TRUE(rig.last_step_is("pocket 1"));
  for (const auto& line : rig.lines()) EXPECT_NE(line, "chuck open");
  EXPECT_FALSE(rig.changer->tools().uncertain) << "the chuck never moved";
  EXPECT_EQ(rig.changer->tools().spindle, 1);
}

TEST(AirPressure, shouldGoOnWhenAirComesBackWithinTheSensorTimeout) {
  Rig rig(1);
  rig.start().tool_change(3);
  rig.sim.run(*rig.changer, 1);
  rig.sim.rack.air = false;
  rig.run_until([&] { return rig.status().awaiting == Awaiting::sensor; });
  EXPECT_EQ(rig.activity(),
            "waiting for air pressure (air-pressure-ok) before the chuck opens at pocket 1");
  rig.sim.rack.air = true;
  rig.run();
  EXPECT_EQ(rig.status().phase, Phase::idle) << rig.activity();
  EXPECT_EQ(rig.changer->tools().spindle, 3);
}

// ---------------------------------------------------------------- zero speed

/// What moved, moved while the spindle ran down: up to safe Z and across at it.
void expect_only_at_safe_z(const Rig& rig) {
  for (const Step& step : rig.sim.motion_steps()) {
    EXPECT_TRUE(!(step.axes & axis_z) || step.target.z == rig.config.safe.z) << describe(step);
  }
  EXPECT_FALSE(rig.sim.chuck_open);
}

TEST(ZeroSpeed, shouldWaitForZeroSpeedBeforeAChangeAndFaultWhenItNeverComes) {
  Rig rig(1);
  rig.sim.rack.spindle_still = false;  // LinuxCNC has it off; the spindle still coasts
  rig.start().tool_change(3);
  rig.run();
  EXPECT_EQ(rig.status().awaiting, Awaiting::spindle);
  expect_only_at_safe_z(rig);
  rig.changer->timer_elapsed();
  EXPECT_EQ(rig.activity(),
            "fault: the spindle did not stop within spindle_stop_timeout_seconds (zero-speed off)");
}

TEST(ZeroSpeed, shouldNotOpenTheChuckUntilZeroSpeedSaysTheSpindleStands) {
  Rig rig(1);
  rig.start().tool_change(3);
  rig.sim.run(*rig.changer, 1);
  rig.sim.rack.spindle_still = false;  // something turned it (or the feedback dropped)
  rig.run_until([&] { return rig.status().awaiting == Awaiting::sensor; });
  EXPECT_EQ(rig.activity(), "waiting for the spindle to stop before the chuck opens at pocket 1");
  EXPECT_DOUBLE_EQ(rig.sim.records.back().seconds, 10.0) << "spindle_stop_timeout_seconds";
  EXPECT_FALSE(rig.sim.chuck_open);
  const std::size_t before = rig.sim.records.size();
  rig.run();  // the timeout runs out
  EXPECT_EQ(rig.activity(),
            "fault: the spindle did not stop within spindle_stop_timeout_seconds (zero-speed off) "
            "before the chuck opened at pocket 1; it stayed closed");
  EXPECT_EQ(rig.moves_since(before), 0u);
  for (const auto& line : rig.lines()) EXPECT_NE(line, "chuck open");
}

TEST(ZeroSpeed, shouldOpenTheChuckOnceZeroSpeedComes) {
  Rig rig(1);
  rig.start().tool_change(3);
  rig.sim.run(*rig.changer, 1);
  rig.sim.rack.spindle_still = false;
  rig.run_until([&] { return rig.status().awaiting == Awaiting::sensor; });
  rig.sim.rack.spindle_still = true;
  rig.run();
  EXPECT_EQ(rig.status().phase, Phase::idle) << rig.activity();
  EXPECT_EQ(rig.changer->tools().spindle, 3);
}

// ---------------------------------------------------------------- drawbar

TEST(Drawbar, shouldFaultUncertainWithoutMovingWhenTheDrawbarDoesNotOpen) {
  Rig rig(1);
  rig.sim.rack.drawbar_jammed = true;
  rig.start().tool_change(3);
  rig.run();
  EXPECT_EQ(rig.activity(),
            "fault: the drawbar did not open at pocket 1 within 1.0 s (drawbar-open off, "
            "drawbar-closed on)");
  EXPECT_TRUE(rig.last_step_is("pocket 1")) << "nothing moves away from the pocket";
  EXPECT_TRUE(rig.changer->tools().uncertain);
  EXPECT_FALSE(rig.sim.chuck_open);
  EXPECT_TRUE(has(rig.last_error(), "pocket 1 may or may not hold tool 1")) << rig.last_error();
}

TEST(Drawbar, shouldFaultUncertainWhenTheDrawbarDoesNotCloseOnAPickUp) {
  Rig rig(0);
  rig.start().tool_change(3);
  // Down into the pocket with the chuck open; there the drawbar jams open.
  rig.run_until([&] { return rig.last_step_is("pocket 3") && !rig.sim.pending; });
  rig.sim.rack.drawbar_jammed = true;
  rig.run();
  EXPECT_EQ(rig.activity(),
            "fault: the drawbar did not close at pocket 3 within 1.0 s (drawbar-open on, "
            "drawbar-closed off)");
  EXPECT_TRUE(rig.last_step_is("pocket 3"));
  EXPECT_TRUE(rig.changer->tools().uncertain);
}

TEST(Drawbar, shouldFaultWhenTheDrawbarDoesNotCloseAfterAReturn) {
  Rig rig(1);
  rig.start().tool_change(0);
  rig.run_until([&] { return rig.last_step_is("above-chuck of pocket 1"); });
  rig.sim.rack.drawbar_jammed = true;  // open, as the release left it
  rig.run();
  EXPECT_EQ(rig.activity(),
            "fault: the drawbar did not close above pocket 1 within 1.0 s (drawbar-open on, "
            "drawbar-closed off)");
  EXPECT_TRUE(rig.last_step_is("above-chuck of pocket 1"));
}

TEST(Drawbar, shouldCheckOnlyTheDrawbarSensorThatIsWired) {
  Rig rig(1, R"("sensors": {"drawbar_closed": true})");
  rig.start().tool_change(3);
  rig.run();
  EXPECT_EQ(rig.status().phase, Phase::idle) << rig.activity();
  EXPECT_EQ(rig.changer->tools().spindle, 3);
}

// ---------------------------------------------------------------- pockets

TEST(PocketOccupancy, shouldNotReturnIntoAPocketThatIsNotEmpty) {
  Rig rig(1);
  rig.sim.rack.spindle_still = false;  // the M6 waits for the spindle ...
  rig.start().tool_change(3);
  rig.run();
  rig.sim.rack.pockets[1] = 9;  // ... meanwhile something lands in pocket 1
  rig.sim.rack.spindle_still = true;
  rig.run();
  EXPECT_EQ(rig.activity(),
            "fault: pocket 1 is not empty (pocket-occupied-1 on): tool 1 cannot go in");
  EXPECT_TRUE(rig.last_step_is("side of pocket 1")) << "checked beside it, before going in";
  for (const auto& line : rig.lines()) EXPECT_NE(line, "chuck open");
  EXPECT_FALSE(rig.changer->tools().uncertain);
}

TEST(PocketOccupancy, shouldNotFetchFromAPocketThatReadsEmpty) {
  Rig rig(1);
  rig.start().tool_change(3);
  rig.sim.run(*rig.changer, 1);
  rig.sim.rack.pockets[3] = 0;  // taken out by hand while tool 1 goes home
  rig.run();
  EXPECT_EQ(rig.activity(),
            "fault: pocket 3 reads empty (pocket-occupied-3 off): tool 3 cannot be fetched");
  EXPECT_TRUE(rig.last_step_is("safe XY")) << "tool 1 went home; nothing moved toward pocket 3";
  EXPECT_EQ(rig.changer->tools().spindle, 0);
  EXPECT_TRUE(rig.changer->tools().holds(1));
  EXPECT_FALSE(rig.changer->tools().uncertain);
}

TEST(PocketOccupancy, shouldNotFetchIntoASpindleThatReadsATool) {
  Rig rig(0);
  rig.sim.rack.spindle_still = false;
  rig.start().tool_change(3);
  rig.run();
  rig.sim.rack.spindle = 8;  // someone put a tool in by hand meanwhile
  rig.sim.rack.spindle_still = true;
  rig.run();
  EXPECT_EQ(rig.activity(),
            "fault: the spindle is not empty (tool-present on): tool 3 cannot be fetched");
  expect_only_at_safe_z(rig);
}

// ---------------------------------------------------------------- tool present

TEST(ToolPresent, shouldFaultUncertainWhenTheToolComesUpWithTheSpindle) {
  Rig rig(1);
  rig.sim.rack.tool_sticks = true;
  rig.start().tool_change(3);
  rig.run();
  EXPECT_EQ(rig.activity(),
            "fault: tool 1 still in the spindle after the chuck opened at pocket 1 and the spindle "
            "lifted (tool-present on)");
  EXPECT_TRUE(rig.last_step_is("above-chuck of pocket 1"));
  EXPECT_TRUE(rig.changer->tools().uncertain);
  EXPECT_EQ(rig.changer->tools().spindle, 1) << "the last known: where the sensor saw it";
  EXPECT_FALSE(rig.changer->tools().holds(1));
  EXPECT_FALSE(rig.sim.chuck_open) << "the fault closes the chuck: the tool stays held";
}

TEST(ToolPresent, shouldGripOnceMoreAtThePocketWhenThePickUpFailedOnce) {
  Rig rig(0);
  rig.sim.rack.grips_failing = 1;
  rig.start().tool_change(3);
  rig.run_until([&] { return rig.last_step_is("pocket 3") && !rig.sim.pending; });
  const std::size_t at_pocket = rig.sim.records.size();
  rig.run();
  EXPECT_EQ(rig.status().phase, Phase::idle) << rig.activity();
  EXPECT_EQ(rig.changer->tools().spindle, 3);
  const Lines after = rig.lines(at_pocket);
  // grip, the sensor timeout runs out, open again in place, grip again, away
  const Lines expected = {"chuck close", "dwell 0.50",  "dwell 1.00", "chuck open",
                          "dwell 0.50",  "chuck close", "dwell 0.50", "feed side of pocket 3"};
  ASSERT_GE(after.size(), expected.size());
  EXPECT_EQ(Lines(after.begin(), after.begin() + expected.size()), expected);
  const auto infos = rig.sim.messages(MessageKind::info);
  EXPECT_TRUE(std::any_of(infos.begin(), infos.end(), [](const std::string& m) {
    return m ==
           "tool 3 not in the spindle after the chuck closed at pocket 3 (tool-present off); "
           "gripping it once more";
  }));
}

TEST(ToolPresent, shouldFaultSayingWhatWasSeenWhenThePickUpFailsTwice) {
  Rig rig(0);
  rig.sim.rack.grips_failing = 2;
  rig.start().tool_change(3);
  rig.run();
  EXPECT_EQ(rig.status().phase, Phase::fault);
  EXPECT_EQ(
      rig.activity(),
      "fault: tool 3 not in the spindle after the chuck closed at pocket 3 (tool-present off, "
      "retried once)");
  EXPECT_TRUE(rig.last_step_is("pocket 3")) << "nothing moved after";
  int opens = 0;
  for (const auto& line : rig.lines()) opens += line == "chuck open";
  EXPECT_EQ(opens, 3) << "flush, above the pocket, and the one retry";
  EXPECT_TRUE(rig.changer->tools().uncertain);
  EXPECT_EQ(rig.changer->tools().spindle, 0);
  EXPECT_FALSE(rig.sim.chuck_open);
  EXPECT_TRUE(has(rig.last_error(),
                  "fault: tool 3 not in the spindle after the chuck closed at "
                  "pocket 3 (tool-present off, retried once); the spindle is "
                  "empty (last known; not certain)"))
      << rig.last_error();
  // Refused until the operator confirms.
  rig.changer->tool_change(2);
  EXPECT_TRUE(has(rig.last_error(), "M6 T2 refused: the changer is in fault")) << rig.last_error();
}

TEST(ToolPresent, shouldNotTakeContinueAtTheInsertPromptUntilTheToolIsThere) {
  Rig rig(0);
  test::take_out(rig.tools, 4);
  rig.sim.model_rack(rig.config, rig.tools);
  rig.start().load(4);
  rig.run();
  ASSERT_EQ(rig.status().awaiting, Awaiting::operator_choice) << rig.activity();
  rig.changer->operator_continue();
  EXPECT_TRUE(
      has(rig.last_error(), "tool 4 is not in the spindle (tool-present off): Insert tool 4"))
      << rig.last_error();
  EXPECT_EQ(rig.status().awaiting, Awaiting::operator_choice);
  EXPECT_EQ(rig.changer->tools().spindle, 0);
  rig.sim.rack.spindle = 4;
  rig.run();
  rig.changer->operator_continue();
  EXPECT_EQ(rig.changer->tools().spindle, 4);
}

TEST(ToolPresent, shouldNotTakeContinueAtTheRemovePromptWhileTheToolIsThere) {
  Rig rig(4);
  rig.start().unload(4);
  rig.run();
  ASSERT_EQ(rig.status().awaiting, Awaiting::operator_choice) << rig.activity();
  rig.changer->operator_continue();
  EXPECT_TRUE(
      has(rig.last_error(), "tool 4 is still in the spindle (tool-present on): Remove tool 4"))
      << rig.last_error();
  rig.sim.rack.spindle = 0;
  rig.run();
  rig.changer->operator_continue();
  rig.run();
  EXPECT_EQ(rig.status().phase, Phase::idle) << rig.activity();
  EXPECT_EQ(rig.changer->tools().spindle, 0);
}

// ---------------------------------------------------------------- the saved state at start

TEST(StartUp, shouldFaultNamingEachDisagreementBetweenSensorsAndSavedState) {
  Rig rig(2);
  rig.sim.rack.spindle = 0;  // tool 2 went back by hand while the machine was off
  rig.sim.rack.pockets[2] = 2;
  rig.sim.rack.pockets[5] = 0;  // and tool 5 was taken out
  rig.start();
  EXPECT_EQ(rig.status().awaiting, Awaiting::sensor);
  EXPECT_FALSE(rig.status().accepting);
  rig.changer->tool_change(3);
  EXPECT_TRUE(
      has(rig.last_error(), "M6 T3 refused: the sensors disagree with the saved tool state"))
      << rig.last_error();
  rig.run();  // sensor_timeout_seconds: they do not come to agree
  EXPECT_EQ(rig.status().phase, Phase::fault);
  EXPECT_EQ(rig.activity(),
            "fault: the sensors disagree with the saved tool state; tool 2 is recorded in the "
            "spindle, but tool-present reads it empty (off); pocket 2 reads occupied "
            "(pocket-occupied-2 on), but tool 2 is recorded in the spindle; pocket 5 reads empty "
            "(pocket-occupied-5 off), but tool 5 is recorded in it");
  EXPECT_TRUE(rig.sim.motion_steps().empty());
  EXPECT_FALSE(rig.sim.chuck_open);
  // The operator looked: the spindle is empty. The pockets are taken as their sensors read.
  rig.changer->clear_fault(0);
  const auto infos = rig.sim.messages(MessageKind::info);
  EXPECT_TRUE(has(infos.back(), "pocket 2 recorded full, as pocket-occupied-2 reads (on)"))
      << infos.back();
  EXPECT_TRUE(has(infos.back(), "pocket 5 recorded empty, as pocket-occupied-5 reads (off)"));
  rig.run();
  EXPECT_EQ(rig.status().phase, Phase::idle) << rig.activity();
  EXPECT_EQ(test::tools_in_rack(rig.changer->tools()), (std::set<int>{1, 2, 3, 4, 6}));
  rig.changer->tool_change(5);
  EXPECT_TRUE(has(rig.last_error(), "tool 5 belongs in pocket 5 but is not in it")) << rig.last_error();
}

TEST(StartUp, shouldFaultAgainWhenTheOperatorsWordContradictsToolPresent) {
  Rig rig(2);
  rig.sim.rack.spindle = 0;
  rig.sim.rack.pockets[2] = 2;
  rig.start();
  rig.run();
  ASSERT_EQ(rig.status().phase, Phase::fault);
  rig.changer->clear_fault(2);  // "it holds tool 2" - the sensor says otherwise
  rig.run();
  EXPECT_EQ(rig.status().phase, Phase::fault);
  EXPECT_TRUE(
      has(rig.activity(), "tool 2 is recorded in the spindle, but tool-present reads it empty"))
      << rig.activity();
  rig.changer->clear_fault(0);
  rig.run();
  EXPECT_EQ(rig.status().phase, Phase::idle) << rig.activity();
}

TEST(StartUp, shouldBecomeIdleWhenTheSensorsSettleWithinTheTimeout) {
  Rig rig(0);
  rig.sim.rack.pockets[4] = 0;  // its sensor is slow to come up
  rig.start();
  EXPECT_EQ(rig.status().awaiting, Awaiting::sensor);
  rig.sim.rack.pockets[4] = 4;
  rig.run();
  EXPECT_EQ(rig.status().phase, Phase::idle) << rig.activity();
  EXPECT_TRUE(rig.sim.messages(MessageKind::error).empty()) << rig.last_error();
}

TEST(StartUp, shouldCompareAgainEachTimeTheMachineBecomesReady) {
  Rig rig(0);
  rig.start();
  EXPECT_EQ(rig.status().phase, Phase::idle);
  rig.changer->not_ready();
  rig.sim.rack.pockets[6] = 0;  // machine off: tool 6 taken out
  rig.sim.report_sensors(*rig.changer);
  EXPECT_EQ(rig.status().phase, Phase::not_ready) << "nothing compared while off";
  rig.changer->ready();
  rig.run();
  EXPECT_TRUE(has(rig.activity(),
                  "pocket 6 reads empty (pocket-occupied-6 off), but tool 6 is "
                  "recorded in it"))
      << rig.activity();
}

TEST(StartUp, shouldFaultWhenASensorContradictsTheStateWhileIdle) {
  Rig rig(0);
  rig.start();
  rig.sim.rack.pockets[4] = 0;
  rig.run();
  EXPECT_EQ(rig.status().phase, Phase::fault);
  EXPECT_TRUE(has(rig.activity(), "pocket 4 reads empty")) << rig.activity();
}

TEST(StartUp, shouldAddWhatTheSensorsReadToTheFaultOfACutOffSequence) {
  Rig rig(0);
  rig.tools.spindle = 2;
  test::take_out(rig.tools, 2);
  rig.tools.uncertain = true;
  rig.tools.in_progress = InProgress{"M6 T5", "returning tool 2 to pocket 2", 2};
  rig.sim.model_rack(rig.config, ToolState::fresh(rig.config));  // it did go home
  rig.start();
  EXPECT_EQ(rig.status().phase, Phase::fault);
  EXPECT_TRUE(has(rig.activity(),
                  "the last sequence was cut off (the saved tool state is "
                  "uncertain); tool 2 is recorded in the spindle, but tool-present "
                  "reads it empty (off); pocket 2 reads occupied"))
      << rig.activity();
  rig.changer->clear_fault(0, true);
  rig.run();
  EXPECT_EQ(rig.status().phase, Phase::idle) << rig.activity();
}

TEST(StartUp, shouldCompareNothingWithoutSensors) {
  Rig rig(2, "");
  rig.sim.rack.spindle = 0;
  rig.start();
  EXPECT_EQ(rig.status().phase, Phase::idle);
  EXPECT_EQ(rig.status().awaiting, Awaiting::nothing);
}

// ---------------------------------------------------------------- probe window

const std::string kMeasure = R"("probe_after_change": "measure", "probe_window": 5)";

/// M6 T3 from an empty spindle, the sensor touching at `sensor_z`; tool 3
/// stored at 25 (it touches at -70 with the test config's offset of -95).
std::unique_ptr<Rig> measured_change(double sensor_z, const std::string& extra = kMeasure,
                                     std::map<int, double> lengths = {{3, 25.0}}) {
  auto rig = std::make_unique<Rig>(0, extra, std::move(lengths));
  rig->sim.sensor_z = sensor_z;
  rig->start().tool_change(3);
  rig->run();
  return rig;
}

bool wrote_a_length(const Rig& rig) {
  for (const auto& step : rig.sim.steps()) {
    if (step.kind == StepKind::set_tool_length) return true;
  }
  return false;
}

TEST(ProbeWindow, shouldMeasureATouchWithinTheWindow) {
  const auto owned = measured_change(-67.0);
  const Rig& rig = *owned;
  EXPECT_EQ(rig.status().phase, Phase::idle) << rig.activity();
  EXPECT_TRUE(wrote_a_length(rig));
  EXPECT_NEAR(rig.changer->tools().lengths.at(3), 28.0, 1e-9);
}

TEST(ProbeWindow, shouldStopATouchFarTooEarlyWritingNothing) {
  const auto owned = measured_change(-50.0);
  const Rig& rig = *owned;
  EXPECT_EQ(rig.status().phase, Phase::fault);
  EXPECT_EQ(
      rig.activity(),
      "fault: tool 3 could not be measured after the change (probe_after_change is \"always\"): tool 3 "
      "touched the sensor at Z -50.0000 mm, 20.0000 mm too early: its stored length 25.0000 mm "
      "puts the touch at Z -70.0000 mm (probe_window 5.0000 mm); a shorted sensor, a wrong or "
      "pulled-out tool?");
  EXPECT_FALSE(wrote_a_length(rig));
  EXPECT_NEAR(rig.changer->tools().lengths.at(3), 25.0, 1e-12);
  EXPECT_TRUE(rig.last_step_is("loading Z")) << "retracted off the sensor, no latch";
  for (const auto& step : rig.sim.steps()) EXPECT_NE(step.label, "touch-off sensor (latch)");
}

TEST(ProbeWindow, shouldStopATouchFarTooLate) {
  const auto owned = measured_change(-80.0);
  const Rig& rig = *owned;
  EXPECT_EQ(rig.status().phase, Phase::fault);
  EXPECT_TRUE(has(rig.activity(), "10.0000 mm too late")) << rig.activity();
  EXPECT_TRUE(has(rig.activity(), "a broken or wrong tool?")) << rig.activity();
  EXPECT_FALSE(wrote_a_length(rig));
}

TEST(ProbeWindow, shouldStopACheckFarOutsideTheWindowBeforeComparing) {
  const auto owned = measured_change(-40.0, R"("probe_after_change": "check")");
  const Rig& rig = *owned;
  EXPECT_TRUE(has(rig.activity(), "30.0000 mm too early")) << rig.activity();
  EXPECT_TRUE(has(rig.activity(), "probe_window 10.0000 mm")) << rig.activity();
}

TEST(ProbeWindow, shouldMeasureAToolWithoutStoredLengthWherever) {
  const auto owned = measured_change(-40.0, kMeasure, {});
  const Rig& rig = *owned;
  EXPECT_EQ(rig.status().phase, Phase::idle) << rig.activity();
  EXPECT_NEAR(rig.changer->tools().lengths.at(3), 55.0, 1e-9);
}

TEST(ProbeWindow, shouldLetTheLoadFlowMeasureANewCutterWherever) {
  Rig rig(0, kMeasure, {{4, 25.0}});
  test::take_out(rig.tools, 4);
  rig.sim.model_rack(rig.config, rig.tools);
  rig.sim.sensor_z = -40.0;  // 30 longer than stored: a new cutter in the holder
  rig.start().load(4);
  for (int i = 0; i < 4 && rig.status().phase == Phase::loading; ++i) {
    rig.run();
    if (rig.status().awaiting != Awaiting::operator_choice) break;
    rig.sim.operator_obeys(*rig.changer);
    rig.sim.report_sensors(*rig.changer);
    rig.changer->operator_continue();
  }
  rig.run();
  EXPECT_EQ(rig.status().phase, Phase::idle) << rig.activity();
  EXPECT_NEAR(rig.changer->tools().lengths.at(4), 55.0, 1e-9);
}

// ---------------------------------------------------------------- the words reach the panel

TEST(SensorFaults, shouldReachThePanelThroughTheStatusFile) {
  char pattern[] = "/tmp/fatc_status_XXXXXX";
  const std::string folder = ::mkdtemp(pattern);
  io::StatusFile file(folder + "/state.json.status");
  Rig rig(0);
  rig.sim.rack.grips_failing = 2;
  rig.start().tool_change(3);
  rig.run();
  for (const auto& error : rig.sim.messages(MessageKind::error))
    file.said(MessageKind::error, error);
  file.write(rig.status(), rig.changer->cut_off(), "rack keep-out armed");
  std::ifstream in(file.path());
  const nlohmann::json status = nlohmann::json::parse(in);
  const std::string words =
      "tool 3 not in the spindle after the chuck closed at pocket 3 "
      "(tool-present off, retried once)";
  EXPECT_EQ(status["phase"], "fault");
  EXPECT_EQ(status["activity"], "fault: " + words);
  EXPECT_TRUE(has(status["messages"].back()["text"].get<std::string>(), words));
  EXPECT_EQ(status["cut_off"]["pocket"], 3);
  EXPECT_EQ(status["keepout"], "rack keep-out armed");
  std::filesystem::remove_all(folder);
}

TEST(SensorFaults, shouldShowTheSensorWaitOnTheAwaitingPin) {
  Rig rig(1);
  rig.sim.rack.air = true;
  rig.start().tool_change(3);
  rig.sim.run(*rig.changer, 1);
  rig.sim.rack.drawbar_jammed = true;
  rig.run_until([&] { return rig.status().awaiting == Awaiting::sensor; });
  EXPECT_EQ(static_cast<int>(rig.status().awaiting), 6);
  EXPECT_EQ(rig.activity(), "waiting for the drawbar to report open");
}

}  // namespace
}  // namespace fatc
