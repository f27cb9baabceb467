// What a rack may need around it: the dust cover, opened before the first
// move into the rack and closed after the last, and the air blast that cleans
// the spindle taper while the chuck is open at a pocket with the spindle empty.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "core/machine/changer.hpp"
#include "core/config/config.hpp"
#include "core/dry_run/simulator.hpp"
#include "core/rack/tool_state.hpp"
#include "sim_lines.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using test::Lines;
using test::valid_config;

struct CoverRig {
  explicit CoverRig(const std::string& extra, int spindle = 0) : config(valid_config(extra)) {
    ToolState start = ToolState::fresh(config);
    if (spindle != 0) start.put_in_spindle(spindle);
    sim.model_rack(config, start);
    changer = std::make_unique<Changer>(config, sim, start);
    sim.report_sensors(*changer);
    changer->ready();
    sim.run(*changer);
  }
  ~CoverRig() { EXPECT_TRUE(sim.unexpected_events.empty()) << sim.unexpected_events.front(); }
  Lines run() {
    std::size_t from = 0;
    sim.run(*changer);
    return test::record_lines(sim, from);
  }
  Config config;
  Simulator sim;
  std::unique_ptr<Changer> changer;
};

std::ptrdiff_t index_of(const Lines& lines, const std::string& line) {
  return std::find(lines.begin(), lines.end(), line) - lines.begin();
}
std::ptrdiff_t first_move(const Lines& lines) {
  return std::find_if(lines.begin(), lines.end(),
                      [](const std::string& l) { return l.rfind("rapid", 0) == 0; }) -
         lines.begin();
}
std::ptrdiff_t last_move(const Lines& lines) {
  std::ptrdiff_t last = -1;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind("rapid", 0) == 0 || lines[i].rfind("feed", 0) == 0) last = i;
  }
  return last;
}
long count(const Lines& lines, const std::string& line) {
  return std::count(lines.begin(), lines.end(), line);
}

// ---------------------------------------------------------------- config

TEST(RackCoverConfig, shouldBeOffUntilNamed) {
  const Config c = valid_config();
  EXPECT_FALSE(c.rack_cover.has_value());
  EXPECT_FALSE(c.air_blast);
  const Config named = valid_config(R"("rack_cover": {}, "air_blast": true)");
  ASSERT_TRUE(named.rack_cover.has_value());
  EXPECT_FALSE(named.sensors.wired(Sensor::rack_cover_opened));
  EXPECT_EQ(named.rack_cover->seconds, 1.0);
  EXPECT_EQ(named.rack_cover->timeout_seconds, 5.0);
  EXPECT_TRUE(named.air_blast);
}

TEST(RackCoverConfig, shouldNameTheBadKeyInOneLine) {
  const std::pair<const char*, const char*> cases[] = {
      {R"("rack_cover": {"opened": true})", "rack_cover.opened: unknown key"},
      {R"("rack_cover": {"seconds": -1})",
       "rack_cover.seconds: must be from 0.01 to 3600 seconds, got -1"},
      {R"("rack_cover": {"closed_sensor": "yes"})",
       "rack_cover.closed_sensor: expected true or false, got \"yes\""},
      {R"("rack_cover": true)", "rack_cover: expected an object, got true"},
      {R"("air_blast": 1)", "air_blast: expected true or false, got 1"},
  };
  for (const auto& [extra, expected] : cases) {
    std::string text = test::kValidConfig;
    text.insert(text.rfind('}'), std::string(",") + extra);
    const auto parsed = parse_config(text);
    ASSERT_FALSE(parsed.config) << extra;
    EXPECT_EQ(parsed.errors.front(), expected) << extra;
  }
}

// ---------------------------------------------------------------- the cover

TEST(RackCover, shouldOpenBeforeTheFirstMoveAndCloseAfterTheLast) {
  CoverRig rig(R"("rack_cover": {})", 2);
  rig.changer->tool_change(5);
  const Lines lines = rig.run();
  ASSERT_EQ(rig.changer->tools().spindle, 5);
  EXPECT_EQ(count(lines, "cover open"), 1) << "once for the return and the fetch";
  EXPECT_EQ(count(lines, "cover close"), 1);
  EXPECT_LT(index_of(lines, "cover open"), first_move(lines));
  EXPECT_LT(index_of(lines, "cover open"), index_of(lines, "dwell 1.00"))
      << "an unsensed cover has its seconds to open";
  EXPECT_GT(index_of(lines, "cover close"), last_move(lines));
  EXPECT_FALSE(rig.sim.cover_open);
}

TEST(RackCover, shouldWaitForItsOpenedSensor) {
  CoverRig rig(R"("rack_cover": {"opened_sensor": true, "closed_sensor": true})");
  rig.changer->tool_change(3);
  const Lines lines = rig.run();
  EXPECT_EQ(rig.changer->tools().spindle, 3);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_EQ(count(lines, "dwell 1.00"), 0) << "the sensor says when it is open";
  EXPECT_FALSE(rig.sim.rack.cover_open);
}

TEST(RackCover, shouldFaultWithNothingMovedWhenItDoesNotOpen) {
  CoverRig rig(R"("rack_cover": {"opened_sensor": true, "timeout_seconds": 3})");
  rig.sim.rack.cover_jammed = true;
  rig.changer->tool_change(3);
  const Lines lines = rig.run();
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
  EXPECT_EQ(first_move(lines), static_cast<std::ptrdiff_t>(lines.size())) << "nothing moved";
  EXPECT_FALSE(rig.changer->tools().uncertain) << "the spindle still holds what it held";
  EXPECT_EQ(
      rig.sim.messages(MessageKind::error)
          .front()
          .rfind("fault: the rack cover did not open within rack_cover.timeout_seconds (3.0 s, "
                 "rack-cover-opened off): nothing moved into the rack",
                 0),
      0u)
      << rig.sim.messages(MessageKind::error).front();
  EXPECT_TRUE(rig.sim.cover_open) << "the cover stays as it is";
}

TEST(RackCover, shouldRefuseWorkWhileItReadsNotClosed) {
  CoverRig rig(R"("rack_cover": {"closed_sensor": true})");
  rig.changer->tool_change(3);
  for (int i = 0; i < 50 && !rig.sim.rack.cover_open; ++i) rig.sim.run(*rig.changer, 1);
  ASSERT_TRUE(rig.sim.rack.cover_open);
  rig.sim.rack.cover_jammed = true;  // opened, and now it sticks open
  rig.run();
  EXPECT_EQ(rig.changer->tools().spindle, 3);
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
  EXPECT_NE(
      rig.changer->status().activity.find("the rack cover is not closed (rack-cover-closed off)"),
      std::string::npos)
      << rig.changer->status().activity;
}

/// Runs `rig`'s change to its end, one event at a time: the changer has just
/// commanded the cover closed, and the rack has not yet said it is.
void run_until_the_change_ends(CoverRig& rig) {
  rig.sim.rack.cover_slow = true;
  for (int i = 0; i < 500 && rig.changer->status().busy(); ++i) {
    ASSERT_EQ(rig.sim.run(*rig.changer, 1), 1) << "event " << i;
  }
  ASSERT_FALSE(rig.changer->status().busy());
  ASSERT_FALSE(rig.sim.cover_open) << "commanded closed after the change";
  ASSERT_EQ(rig.changer->status().awaiting, Awaiting::sensor) << "rack-cover-closed not yet on";
}

// LinuxCNC 2.10's task hands the M6 back within a cycle, so a program's next
// M6 can come before the cover the last one closed reads closed.
TEST(RackCover, shouldTakeAChangeThatComesWhileTheCoverItClosedIsStillMoving) {
  CoverRig rig(R"("rack_cover": {"opened_sensor": true, "closed_sensor": true})");
  rig.changer->tool_change(3);
  run_until_the_change_ends(rig);
  rig.changer->tool_change(5);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle) << rig.changer->status().activity;
  EXPECT_TRUE(rig.sim.messages(MessageKind::error).empty())
      << rig.sim.messages(MessageKind::error).front();
  const Lines lines = rig.run();
  EXPECT_TRUE(rig.sim.messages(MessageKind::error).empty())
      << rig.sim.messages(MessageKind::error).front();
  EXPECT_EQ(rig.changer->tools().spindle, 5);
  EXPECT_EQ(rig.changer->status().phase, Phase::idle);
  EXPECT_FALSE(rig.sim.rack.cover_open);
}

TEST(RackCover, shouldTakeAnUnloadThatComesWhileTheCoverItClosedIsStillMoving) {
  CoverRig rig(R"("rack_cover": {"closed_sensor": true})", 2);
  rig.changer->tool_change(0);
  run_until_the_change_ends(rig);
  rig.changer->unload(3);
  rig.run();
  EXPECT_TRUE(rig.sim.messages(MessageKind::error).empty())
      << rig.sim.messages(MessageKind::error).front();
  EXPECT_EQ(rig.changer->status().phase, Phase::unloading) << rig.changer->status().activity;
  EXPECT_TRUE(rig.changer->status().awaits_operator()) << "tool 3 at loading for the operator";
}

TEST(RackCover, shouldRefuseAtOnceWhileACoverItDidNotCloseReadsOpen) {
  CoverRig rig(R"("rack_cover": {"closed_sensor": true})");
  rig.sim.rack.cover_open = true;  // opened by hand while idle
  ASSERT_TRUE(rig.sim.report_sensors(*rig.changer));
  ASSERT_EQ(rig.changer->status().awaiting, Awaiting::sensor);
  rig.changer->tool_change(3);
  const auto errors = rig.sim.messages(MessageKind::error);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors.front(),
            "M6 T3 refused: the sensors disagree with the saved tool state; the rack cover is not "
            "closed (rack-cover-closed off)");
  EXPECT_EQ(rig.changer->tools().spindle, 0);
}

TEST(RackCover, shouldRefuseAWaitingChangeAsAFaultWhenTheCoverItClosedDoesNotClose) {
  CoverRig rig(R"("rack_cover": {"closed_sensor": true, "timeout_seconds": 3})");
  rig.changer->tool_change(3);
  for (int i = 0; i < 50 && !rig.sim.rack.cover_open; ++i) rig.sim.run(*rig.changer, 1);
  ASSERT_TRUE(rig.sim.rack.cover_open);
  rig.sim.rack.cover_jammed = true;  // opened, and now it sticks open
  run_until_the_change_ends(rig);
  rig.changer->tool_change(5);
  EXPECT_TRUE(rig.sim.messages(MessageKind::error).empty()) << "it waits for the cover";
  rig.run();
  EXPECT_EQ(rig.changer->tools().spindle, 3);
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
  const auto errors = rig.sim.messages(MessageKind::error);
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors.front().rfind("fault: the sensors disagree with the saved tool state; the rack "
                                 "cover is not closed (rack-cover-closed off)",
                                 0),
            0u)
      << errors.front();
  EXPECT_EQ(errors.back(),
            "M6 T5 refused: the changer is in fault (the sensors disagree with the saved tool "
            "state; the rack cover is not closed (rack-cover-closed off)); clear it first");
}

TEST(RackCover, shouldRefuseAWaitingChangeWhenTheMachineGoesOff) {
  CoverRig rig(R"("rack_cover": {"closed_sensor": true})");
  rig.changer->tool_change(3);
  run_until_the_change_ends(rig);
  rig.changer->tool_change(5);
  EXPECT_TRUE(rig.sim.messages(MessageKind::error).empty()) << "it waits for the cover";
  rig.changer->not_ready();
  const auto errors = rig.sim.messages(MessageKind::error);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors.front(), "M6 T5 refused: the machine is not on and homed, or is in estop");
  EXPECT_EQ(rig.changer->status().phase, Phase::not_ready);
  EXPECT_EQ(rig.changer->tools().spindle, 3);
}

// ---------------------------------------------------------------- the air blast

TEST(AirBlast, shouldBlowOnlyWhileTheChuckIsOpenAtAPocketWithTheSpindleEmpty) {
  CoverRig rig(R"("air_blast": true)", 2);
  rig.changer->tool_change(5);
  const Lines lines = rig.run();
  ASSERT_EQ(rig.changer->tools().spindle, 5);
  EXPECT_GE(count(lines, "blast on"), 2) << "after the return and before the grip";
  EXPECT_EQ(count(lines, "blast on"), count(lines, "blast off"));
  bool chuck_open = false;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i] == "chuck open") chuck_open = true;
    if (lines[i] == "chuck close") chuck_open = false;
    if (lines[i] == "blast on") {
      EXPECT_TRUE(chuck_open) << "blast on at line " << i;
    }
    if (lines[i] == "blast off") {
      ASSERT_LT(i + 1, lines.size());
      EXPECT_EQ(lines[i + 1], "chuck close") << "off just before the chuck closes";
    }
  }
  EXPECT_FALSE(rig.sim.blowing);
}

TEST(AirBlast, shouldNotBlowAtLoadingWhereTheOperatorsHandIs) {
  const Config config = valid_config(R"("air_blast": true)");
  Simulator sim = plan_load(config, 3, 0, -60.0);
  std::size_t from = 0;
  const Lines lines = test::record_lines(sim, from);
  // The flush at loading opens the chuck first; the put-away at the pocket last.
  const auto at_loading = index_of(lines, "chuck open");
  ASSERT_LT(at_loading + 1, static_cast<std::ptrdiff_t>(lines.size()));
  EXPECT_NE(lines[at_loading + 1], "blast on") << ::testing::PrintToString(lines);
  EXPECT_EQ(count(lines, "blast on"), 1) << "only at the pocket the tool is put away in";
}

TEST(AirBlast, shouldStopOnAFaultAndLeaveTheCoverAsItIs) {
  CoverRig rig(R"("air_blast": true, "rack_cover": {})");
  rig.changer->tool_change(3);
  for (int i = 0; i < 200 && !rig.sim.blowing; ++i) rig.sim.run(*rig.changer, 1);
  ASSERT_TRUE(rig.sim.blowing);
  rig.changer->abort("estop");
  EXPECT_EQ(rig.changer->status().phase, Phase::fault);
  EXPECT_FALSE(rig.sim.blowing);
  EXPECT_FALSE(rig.sim.chuck_open);
  EXPECT_TRUE(rig.sim.cover_open) << "the cover stays as it is";
}

// ---------------------------------------------------------------- the fault matrix

/// An M6 from tool 1 to tool 2 with cover and blast, cut off after each of its
/// events by an abort and by an estop: the blast is off, the chuck closed, the
/// cover as it was.
TEST(FaultMatrixAroundTheRack, shouldStopTheBlastAndLeaveTheCoverWhereverAChangeIsCutOff) {
  const std::string extra = R"("rack_cover": {}, "air_blast": true)";
  int events = 0;
  {
    CoverRig rig(extra, 1);
    rig.changer->tool_change(2);
    while (rig.changer->status().busy() && rig.sim.run(*rig.changer, 1) == 1) ++events;
    ASSERT_EQ(rig.changer->tools().spindle, 2);
  }
  ASSERT_GT(events, 20);
  int blowing = 0;
  int covered = 0;
  for (const bool estop : {false, true}) {
    for (int at = 0; at < events; ++at) {
      CoverRig rig(extra, 1);
      rig.changer->tool_change(2);
      for (int i = 0; i < at; ++i) ASSERT_EQ(rig.sim.run(*rig.changer, 1), 1);
      const bool cover_was_open = rig.sim.cover_open;
      blowing += rig.sim.blowing;
      covered += cover_was_open;
      if (estop) {
        rig.changer->not_ready();
      } else {
        rig.changer->abort("LinuxCNC aborted the program");
      }
      EXPECT_FALSE(rig.sim.blowing) << "event " << at << (estop ? " estop" : " abort");
      EXPECT_FALSE(rig.sim.chuck_open) << "event " << at;
      EXPECT_EQ(rig.sim.cover_open, cover_was_open) << "event " << at;
    }
  }
  EXPECT_GT(blowing, 0) << "some cases cut the change off while blowing";
  EXPECT_GT(covered, 0) << "some cases cut the change off with the cover open";
}

}  // namespace
}  // namespace fatc
