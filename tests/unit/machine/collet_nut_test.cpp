// A collet-nut magazine (`chuck.kind` "collet_nut", issue 46): the return
// screws the nut off in reverse, the fetch screws it on forward, the spindle
// turns only over the served pocket, and the recognition zones catch a nut
// that stayed on, one that did not come, and one not screwed home. The
// Simulator models the magazine (Rack::screw); each test spoils one thing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/config/config.hpp"
#include "sim_rig.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::Lines;

const char* const kColletNut = R"({
  "path": "direct",
  "chuck": {"kind": "collet_nut", "spin_off_offset_z": 12.0, "rise_after_unload_offset_z": 25.0,
            "engage_feed": 1800.0, "unload_rpm": 1200.0, "load_rpm": 1000.0,
            "tighten_plunges": 2, "spindle_ramp_seconds": 1.5}
})";
const char* const kRecognition =
    R"({"chuck": {"recognition": {"zone_1_z": -60.0, "zone_2_z": -54.0}}})";

Config collet_config(const char* more = "{}") {
  auto json = nlohmann::ordered_json::parse(test::sample_config_with(kColletNut));
  json.merge_patch(nlohmann::ordered_json::parse(more));
  const auto parsed = parse_config(json.dump());
  if (!parsed.config) throw std::runtime_error(parsed.errors.front());
  return *parsed.config;
}

/// The first error parse_config gives the collet-nut config patched with `patch`.
std::string error_of(const char* patch) {
  auto json = nlohmann::ordered_json::parse(test::sample_config_with(kColletNut));
  json.merge_patch(nlohmann::ordered_json::parse(patch));
  const auto parsed = parse_config(json.dump());
  return parsed.errors.empty() ? "" : parsed.errors.front();
}

ToolState with_spindle(const Config& config, int tool) {
  ToolState tools = ToolState::fresh(config);
  tools.spindle = tool;
  test::take_out(tools, tool);
  return tools;
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// ---------------------------------------------------------------- config

TEST(ColletNutConfig, shouldReadEveryKeyAndEnterEveryPocketFromTheTop) {
  const Config config = collet_config(kRecognition);
  EXPECT_TRUE(config.screws_nuts());
  EXPECT_EQ(config.chuck.unload_rpm, 1200.0);
  EXPECT_EQ(config.chuck.load_rpm, 1000.0);
  EXPECT_EQ(config.chuck.tighten_plunges, 2);
  ASSERT_TRUE(config.chuck.recognition);
  EXPECT_EQ(config.chuck.recognition->zone_2_z, -54.0);
  EXPECT_TRUE(config.sensors.wired(Sensor::nut_seen));
  for (const auto& [number, pocket] : config.pockets) EXPECT_EQ(pocket.approach, Approach::top);
}

TEST(ColletNutConfig, shouldKeepTheDrawbarByDefault) {
  EXPECT_FALSE(test::valid_config().screws_nuts());
  EXPECT_FALSE(test::valid_config(R"("chuck": {"kind": "drawbar"})").screws_nuts());
}

TEST(ColletNutConfig, shouldRefuseBadInputInOneLineNamingTheKey) {
  EXPECT_EQ(error_of(R"({"chuck": {"kind": "collet"}})"),
            "chuck.kind: expected \"drawbar\" or \"collet_nut\", got \"collet\"");
  EXPECT_EQ(error_of(R"({"chuck": {"unload_rpm": null}})"),
            "chuck.unload_rpm: missing: \"kind\": \"collet_nut\" needs it");
  EXPECT_EQ(error_of(R"({"chuck": {"load_rpm": -5}})"),
            "chuck.load_rpm: must be from 1 to 100000 rpm, got -5");
  EXPECT_EQ(error_of(R"({"chuck": {"tighten_plunges": 1.5}})"),
            "chuck.tighten_plunges: must be a whole number, got 1.5");
  EXPECT_EQ(error_of(R"({"chuck": {"rise_after_unload_offset_z": 5}})"),
            "chuck.rise_after_unload_offset_z: must not be below chuck.spin_off_offset_z (12), "
            "got 5");
  EXPECT_EQ(error_of(R"({"chuck": {"recognition": {"zone_1_z": -54, "zone_2_z": -60}}})"),
            "chuck.recognition.zone_2_z: must be above zone_1_z (-54): a nut not screwed home "
            "hangs lower, so zone 2 is the higher one, got -60");
  EXPECT_EQ(error_of(R"({"chuck": {"recognition": {"zone_1_z": -75, "zone_2_z": -54}}})"),
            "chuck.recognition.zone_1_z: must not be below pocket 1's spin-off (-68): there the "
            "nose reaches into the nut left in the pocket, got -75");
  EXPECT_EQ(error_of(R"({"chuck": {"recognition": {"zone_1_z": -60}}})"),
            "chuck.recognition.zone_2_z: missing");
  EXPECT_EQ(error_of(R"({"pockets": {"2": {"approach": "side"}}})"),
            "pockets.2.approach: \"side\" cannot serve \"chuck\": \"collet_nut\" (its nuts are "
            "screwed from the top)");
  EXPECT_EQ(error_of(R"({"sensors": {"drawbar_open": true}})"),
            "sensors.drawbar_open: a collet-nut spindle (\"chuck\": \"collet_nut\") has no "
            "drawbar");
  EXPECT_EQ(error_of(R"({"tools": {"7": {"kind": "probe"}}, "pockets": {"2": {"tool": 7}}})"),
            "pockets.2.tool: tool 7 is a touch probe: a collet-nut magazine cannot hold it (the "
            "spindle would turn it to screw it); leave it out of the rack, it is handed in at "
            "loading");
  const auto drawbar =
      parse_config(test::sample_config_with(R"({"chuck": {"kind": "drawbar", "unload_rpm": 900}})"));
  ASSERT_FALSE(drawbar.errors.empty());
  EXPECT_EQ(drawbar.errors.front(),
            "chuck.unload_rpm: only for \"kind\": \"collet_nut\" (a drawbar has no use for it)");
  EXPECT_EQ(error_of(R"({"chuck": {"spin_off": 3}})").rfind("chuck.spin_off: unknown key", 0), 0u)
      << error_of(R"({"chuck": {"spin_off": 3}})");
}

// ---------------------------------------------------------------- the sequences

/// Where the spindle stood each time it was asked to turn, and every move
/// it made while turning: all over the served pocket, at or above its engage Z.
void expect_turning_only_over(const Simulator& sim, const Config& config) {
  Point at;
  double rpm = 0.0;
  int served = 0;
  int turns = 0;
  for (const Record& r : sim.records) {
    if (r.kind != Record::Kind::step) continue;
    const Step& s = r.step;
    if (s.kind == StepKind::spindle) {
      rpm = s.value;
      if (rpm == 0.0) continue;
      ++turns;
      served = s.pocket;
      ASSERT_NE(served, 0) << "the spindle turns only for a pocket";
    } else if (is_motion(s.kind)) {
      at = moved_to(at, s);
    } else {
      continue;
    }
    if (rpm == 0.0) continue;
    const Point& pocket = config.pockets.at(served).at;
    EXPECT_DOUBLE_EQ(at.x, pocket.x) << describe(s);
    EXPECT_DOUBLE_EQ(at.y, pocket.y) << describe(s);
    EXPECT_GE(at.z, pocket.z - 1e-9) << describe(s);
    EXPECT_LE(at.z, pocket.z + config.chuck.rise_after_unload_offset_z + 1e-9) << describe(s);
  }
  EXPECT_GT(turns, 0);
}

TEST(ColletNut, shouldScrewTheNutOffInReverseAndTheNextOnForward) {
  const Config config = collet_config();
  test::SimRig rig(config, with_spindle(config, 1));
  rig.changer->tool_change(3);
  const Lines lines = rig.run();
  const Lines expected = {
      "rapid safe Z", "rapid over pocket 1", "rapid spin-off of pocket 1",
      "spindle spindle 1200 rpm in reverse over pocket 1", "dwell 1.50",
      "feed engage Z of pocket 1", "feed rise after unload of pocket 1",
      "spindle spindle stopped over pocket 1", "dwell 1.50",
      "rapid safe Z",  // a fetch follows on the direct path: it starts over pocket 1
      "rapid over pocket 3", "rapid spin-off of pocket 3",
      "spindle spindle 1000 rpm forward over pocket 3", "dwell 1.50",
      "feed engage Z of pocket 3", "feed spin-off of pocket 3",
      "feed engage Z of pocket 3", "feed spin-off of pocket 3",
      "spindle spindle stopped over pocket 3", "dwell 1.50",
      "rapid safe Z", "rapid safe XY", "done T3"};
  ASSERT_GE(lines.size(), expected.size());
  EXPECT_EQ(Lines(lines.begin() + static_cast<long>(lines.size() - expected.size()), lines.end()),
            expected);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rig.changer->tools().spindle, 3);
  EXPECT_EQ(rig.changer->tools().tool_of(1), 1);
  EXPECT_FALSE(rig.changer->status().turns_spindle);
  expect_turning_only_over(rig.sim, config);
}

TEST(ColletNut, shouldAskForTheSpindleOnlyBetweenItsStartAndItsStop) {
  const Config config = collet_config();
  test::SimRig rig(config, with_spindle(config, 2));
  rig.changer->tool_change(0);
  bool seen_turning = false;
  for (int i = 0; i < 200 && rig.sim.run(*rig.changer, 1) > 0; ++i) {
    const Step& last = rig.sim.steps().back();
    const bool between = last.kind == StepKind::feed || (last.kind == StepKind::spindle &&
                                                         last.value != 0.0);
    if (rig.changer->status().turns_spindle) {
      seen_turning = true;
      EXPECT_TRUE(between) << describe(last);
    }
  }
  EXPECT_TRUE(seen_turning);
  EXPECT_EQ(rig.changer->tools().tool_of(2), 2);
}

/// With the tool-recognition sensor wired, the Simulator's magazine answers it.
struct Recognized : test::SimRig {
  explicit Recognized(int spindle, int failing = 0, bool hangs_low = false)
      : SimRig(collet_config(kRecognition), with_spindle(collet_config(kRecognition), spindle)) {
    sim.rack.screwings_failing = failing;
    sim.rack.nut_hangs_low = hangs_low;
  }
  std::vector<std::string> infos() const { return sim.messages(MessageKind::info); }
};

TEST(ColletNutRecognition, shouldReadZoneOneAfterAnUnloadAndBothZonesAfterALoad) {
  Recognized rig(1);
  rig.changer->tool_change(4);
  const Lines lines = rig.run();
  const auto zone = [&](const std::string& what) {
    return std::count(lines.begin(), lines.end(), "rapid " + what);
  };
  EXPECT_EQ(zone("recognition zone 1 of pocket 1"), 1);
  EXPECT_EQ(zone("recognition zone 1 of pocket 4"), 1);
  EXPECT_EQ(zone("recognition zone 2 of pocket 4"), 1);
  EXPECT_EQ(zone("recognition zone 2 of pocket 1"), 0);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle) << rig.last_message();
  EXPECT_EQ(rig.changer->tools().spindle, 4);
  EXPECT_EQ(rig.sim.rack.spindle, 4);
  EXPECT_EQ(rig.sim.rack.pockets[1], 1);
}

TEST(ColletNutRecognition, shouldUnscrewOnceMoreWhenZoneOneStillSeesTheNut) {
  Recognized rig(1, 1);
  rig.changer->tool_change(0);
  rig.run();
  const auto infos = rig.infos();
  EXPECT_TRUE(std::any_of(infos.begin(), infos.end(), [](const std::string& m) {
    return m == "tool 1's nut still seen at zone 1 (nut-seen on) over pocket 1; unscrewing it "
                "once more";
  }));
  EXPECT_EQ(rig.sim.rack.pockets[1], 1) << "unscrewed the second time";
}

TEST(ColletNutRecognition, shouldFaultWithTheFiguresWhenTheNutStaysOnTwice) {
  Recognized rig(1, 2);
  rig.changer->tool_change(3);
  rig.run();
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
  EXPECT_EQ(rig.changer->status().activity,
            "fault: tool 1's nut still on the spindle after it was unscrewed twice at pocket 1, "
            "the spindle at 1200 rpm in reverse down to the engage Z (Z -80.000) and up to "
            "Z -55.000: zone 1 (Z -60.000) sees it (nut-seen on)");
  EXPECT_EQ(rig.sim.steps().back().kind, StepKind::fail) << "nothing moved after";
  const auto moves = rig.sim.motion_steps();
  EXPECT_EQ(moves.back().label, "recognition zone 1 of pocket 1");
  EXPECT_EQ(rig.changer->tools().spindle, 1);
  EXPECT_TRUE(rig.changer->tools().uncertain);
  EXPECT_FALSE(rig.changer->status().turns_spindle);
}

TEST(ColletNutRecognition, shouldFaultNamingZoneOneWhenTheNutNeverComes) {
  Recognized rig(0, 2);
  rig.changer->tool_change(5);
  rig.run();
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
  EXPECT_TRUE(has(rig.changer->status().activity,
                  "tool 5 not on the spindle after it was screwed on twice at pocket 5, the "
                  "spindle at 1000 rpm forward down to the engage Z (Z -80.000), 2 plunges each: "
                  "zone 1 (Z -60.000) sees no nut (nut-seen off)"))
      << rig.changer->status().activity;
  EXPECT_EQ(rig.sim.motion_steps().back().label, "recognition zone 1 of pocket 5");
}

TEST(ColletNutRecognition, shouldFaultNamingZoneTwoWhenTheNutIsNotScrewedHome) {
  Recognized rig(0, 0, true);
  rig.changer->tool_change(2);
  rig.run();
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
  EXPECT_TRUE(has(rig.changer->status().activity,
                  "tool 2's nut not screwed home after it was screwed on twice at pocket 2"))
      << rig.changer->status().activity;
  EXPECT_TRUE(has(rig.changer->status().activity,
                  "zone 2 (Z -54.000) still sees it (nut-seen on)"));
  EXPECT_EQ(rig.sim.motion_steps().back().label, "recognition zone 2 of pocket 2");
  EXPECT_EQ(rig.changer->tools().spindle, 2);
  EXPECT_TRUE(rig.changer->tools().uncertain);
}

TEST(ColletNutSpindle, shouldFaultBeforeThePlungeWhenTheSpindleNeverComesUpToSpeed) {
  const Config config = collet_config(R"({"sensors": {"at_speed": true}})");
  test::SimRig rig(config, with_spindle(config, 1));
  rig.sim.rack.stalled = true;
  rig.changer->tool_change(3);
  rig.run();
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
  EXPECT_EQ(rig.changer->status().activity,
            "fault: the spindle did not come up to 1200 rpm in reverse over pocket 1 within "
            "spindle_stop_timeout_seconds (10.0 s, spindle-at-speed off): tool 1 not screwed");
  EXPECT_EQ(rig.sim.motion_steps().back().label, "spin-off of pocket 1") << "no plunge";
  EXPECT_FALSE(rig.changer->status().turns_spindle);
  EXPECT_FALSE(rig.changer->tools().uncertain) << "nothing was screwed";
}

TEST(ColletNutSpindle, shouldPlungeOnlyOnceAtSpeedWhereItIsWired) {
  const Config config = collet_config(R"({"sensors": {"at_speed": true, "zero_speed": true}})");
  test::SimRig rig(config, with_spindle(config, 1));
  rig.changer->tool_change(2);
  rig.run();
  EXPECT_EQ(rig.changer->status().phase, Phase::idle) << rig.last_message();
  EXPECT_EQ(rig.changer->tools().spindle, 2);
}

TEST(ColletNutProbe, shouldRefuseToLoadAProbeIntoTheMagazine) {
  const Config config = collet_config(R"({"tools": {"9": {"kind": "probe"}}})");
  test::SimRig rig(config, with_spindle(config, 0));
  rig.changer->load(9, 0);
  rig.run();
  EXPECT_TRUE(has(rig.last_message(),
                  "tool 9 is a touch probe: a collet-nut magazine cannot hold it (the spindle "
                  "would turn it to screw it); M6 hands it in at loading"))
      << rig.last_message();
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
}

TEST(ColletNutChuck, shouldRefuseAChuckRelease) {
  const Config config = collet_config();
  test::SimRig rig(config, with_spindle(config, 0));
  rig.changer->chuck(ChuckRequest::Action::release, Point{});
  rig.run();
  EXPECT_TRUE(has(rig.last_message(), "has no drawbar to release")) << rig.last_message();
}

}  // namespace
}  // namespace fatc

namespace fatc {
namespace {

TEST(ColletNutStepByStep, shouldHoldEachSpindleStartForContinueButNeverItsStop) {
  const Config config = collet_config();
  test::SimRig rig(config, with_spindle(config, 1));
  rig.changer->step_by_step(true);
  rig.changer->tool_change(3);
  rig.run();
  std::vector<std::string> starts;
  for (int turn = 0; turn < 200 && rig.changer->status().awaits_operator(); ++turn) {
    ASSERT_TRUE(rig.sim.asked);
    if (rig.sim.asked->action.rfind("turn the spindle", 0) == 0) {
      starts.push_back(rig.sim.asked->action + " " + rig.sim.asked->waypoint);
      EXPECT_FALSE(rig.changer->status().turns_spindle) << "not before Continue";
    }
    rig.changer->operator_continue();
    rig.run();
  }
  EXPECT_EQ(starts, (std::vector<std::string>{
                        "turn the spindle in reverse at 1200 rpm spindle 1200 rpm in reverse over "
                        "pocket 1",
                        "turn the spindle forward at 1000 rpm spindle 1000 rpm forward over "
                        "pocket 3"}));
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(rig.changer->tools().spindle, 3);
}

}  // namespace
}  // namespace fatc

namespace fatc {
namespace {

TEST(ColletNutPlan, shouldShowEachRampAsTheSpindleTakesItNotTheTimeout) {
  const Config config = collet_config(R"({"sensors": {"at_speed": true, "zero_speed": true}})");
  const Simulator plan = plan_change_timed(config, with_spindle(config, 1), 3, -50.0);
  int ramps = 0;
  for (const Record& r : plan.records) {
    if (r.kind != Record::Kind::dwell) continue;
    EXPECT_LE(r.seconds, config.chuck.spindle_ramp_seconds) << "no dwell of the 10 s timeout";
    ramps += r.seconds == config.chuck.spindle_ramp_seconds;
  }
  EXPECT_EQ(ramps, 4) << "a start and a stop for each nut";
  EXPECT_EQ(plan.steps().back().kind, StepKind::done);
}

}  // namespace
}  // namespace fatc
