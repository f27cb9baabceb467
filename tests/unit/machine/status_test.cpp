// The status view (phase, awaiting, activity and the flags the pins show),
// the refusals and the answers to buttons that have nothing to act on.

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <tuple>
#include <vector>

#include "core/machine/changer.hpp"
#include "core/dry_run/simulator.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using Lines = std::vector<std::string>;

/// Where the test sensor trips, and the length it gives with the test config
/// (probe_length_compensation_offset -95).
constexpr double kSensorZ = -60.0;
constexpr double kMeasured = 35.0;

const std::string kNotReady = "the machine is not on and homed, or is in estop";
const std::string kTaskBusy = "a program or MDI command is running";

/// A ready changer on a Simulator whose sensor trips at kSensorZ; an
/// unexpected event fails the test.
struct Rig {
  explicit Rig(int spindle = 0, const std::string& extra_config = "",
               std::map<int, double> lengths = {})
      : config(test::valid_config(extra_config)) {
    ToolState tools = ToolState::fresh(config);
    tools.spindle = spindle;
    test::take_out(tools, spindle);
    tools.lengths = std::move(lengths);
    sim.sensor_z = kSensorZ;
    changer = std::make_unique<Changer>(config, sim, tools);
    changer->ready();
  }
  ~Rig() {
    for (const std::string& event : sim.unexpected_events) ADD_FAILURE() << "unexpected " << event;
  }

  Status status() const { return changer->status(); }

  /// One event, as the executor or the clock would give it; false when the
  /// changer waits for nothing the simulator gives (the operator, or nothing).
  bool step() { return sim.run(*changer, 1) == 1; }
  /// One event at a time until `reached` holds for the status.
  void advance_until(const std::function<bool(const Status&)>& reached) {
    while (!reached(status())) ASSERT_TRUE(step()) << "stuck at " << status().activity;
  }
  void advance_until(Awaiting awaiting) {
    advance_until([awaiting](const Status& s) { return s.awaiting == awaiting; });
  }
  /// Runs the flow to its end, pressing Continue at every question.
  void finish() {
    for (int presses = 0; presses < 10; ++presses) {
      sim.run(*changer);
      if (!status().awaits_operator()) return;
      changer->operator_continue();
    }
  }

  /// The messages of `kind` told since record `from`.
  Lines told(MessageKind kind, std::size_t from = 0) const {
    Lines out;
    for (std::size_t i = from; i < sim.records.size(); ++i) {
      const Record& r = sim.records[i];
      if (r.kind == Record::Kind::message && r.message_kind == kind) out.push_back(r.text);
    }
    return out;
  }
  /// The steps published since record `from`.
  std::vector<Step> published(std::size_t from) const {
    std::vector<Step> out;
    for (std::size_t i = from; i < sim.records.size(); ++i) {
      if (sim.records[i].kind == Record::Kind::step) out.push_back(sim.records[i].step);
    }
    return out;
  }
  std::size_t mark() const { return sim.records.size(); }

  Config config;
  Simulator sim;
  std::unique_ptr<Changer> changer;
};

/// A changer on a plain Simulator, not yet ready; unexpected events are only recorded.
struct Bare {
  Config config = test::valid_config();
  Simulator sim;
  Changer changer{config, sim, ToolState::fresh(config)};
};

/// Everything the pins show, as one line, so that "unchanged" compares at once.
std::string shown(const Status& s) {
  return std::to_string(static_cast<int>(s.phase)) + "/" +
         std::to_string(static_cast<int>(s.awaiting)) + " " + s.activity +
         (s.holds_program ? " holds" : "") + (s.probe_cancellable ? " cancellable" : "") +
         (s.accepting ? " accepting" : "") +
         (s.last_length ? " length " + std::to_string(*s.last_length) : "");
}

// ---------------------------------------------------------------- phase and awaiting

TEST(Status, shouldFollowPhaseAndAwaitingThroughAnM6FromAnEmptySpindle) {
  Bare bare;
  Simulator& sim = bare.sim;
  Changer& changer = bare.changer;
  EXPECT_EQ(changer.status().phase, Phase::not_ready) << "before ready()";
  EXPECT_EQ(changer.status().awaiting, Awaiting::nothing);
  EXPECT_EQ(changer.status().activity, "machine off, not homed or in estop");

  changer.ready();
  EXPECT_EQ(changer.status().phase, Phase::idle);
  EXPECT_EQ(changer.status().awaiting, Awaiting::nothing);
  EXPECT_EQ(changer.status().activity, "idle");

  changer.tool_change(2);
  EXPECT_EQ(changer.status().phase, Phase::changing);
  EXPECT_EQ(changer.status().awaiting, Awaiting::motion);
  ASSERT_TRUE(sim.pending.has_value()) << "a move is pending";

  while (changer.status().awaiting == Awaiting::motion) ASSERT_EQ(sim.run(changer, 1), 1);
  EXPECT_EQ(changer.status().phase, Phase::changing);
  EXPECT_EQ(changer.status().awaiting, Awaiting::timer);
  EXPECT_TRUE(sim.timer_armed);

  sim.run(changer);
  EXPECT_EQ(changer.tools().spindle, 2);
  EXPECT_EQ(changer.status().phase, Phase::idle);
  EXPECT_EQ(changer.status().awaiting, Awaiting::nothing);
  EXPECT_EQ(changer.status().activity, "idle");

  changer.not_ready();
  EXPECT_EQ(changer.status().phase, Phase::not_ready);
  EXPECT_EQ(changer.status().activity, "machine off, not homed or in estop");
  EXPECT_TRUE(sim.unexpected_events.empty());
}

TEST(Status, shouldShowTheFaultWithItsReasonWhenAbortedMidSequence) {
  Rig rig;
  rig.changer->tool_change(2);
  ASSERT_TRUE(rig.step());
  rig.changer->abort("program aborted");
  EXPECT_EQ(rig.status().phase, Phase::fault);
  EXPECT_EQ(rig.status().awaiting, Awaiting::nothing);
  EXPECT_EQ(rig.status().activity, "fault: program aborted");
  EXPECT_FALSE(rig.status().busy());
  EXPECT_FALSE(rig.status().accepting);

  rig.changer->not_ready();
  EXPECT_EQ(rig.status().activity, "fault: program aborted")
      << "a fault outlasts the machine going off";
}

// ---------------------------------------------------------------- activity

TEST(Status, shouldNameTheKindAndLabelOfThePendingStepOrTheDwellAsActivity) {
  Rig rig;
  rig.changer->tool_change(2);
  Lines seen;
  while (rig.status().phase == Phase::changing) {
    if (seen.empty() || seen.back() != rig.status().activity) seen.push_back(rig.status().activity);
    ASSERT_TRUE(rig.step());
  }
  EXPECT_EQ(seen, (Lines{"rapid to safe Z", "rapid to safe XY", "rapid to over pocket 2",
                         "rapid to above-clearance of pocket 2", "rapid to above-chuck of pocket 2",
                         "flushing the chuck (open)", "flushing the chuck (closed)",
                         "opening the chuck above pocket 2", "feed to pocket 2",
                         "letting the tool settle", "gripping tool 2", "feed to side of pocket 2",
                         "rapid to safe Z", "rapid to safe XY"}));
}

TEST(Status, shouldNameTheProbeMoveAsActivityWhileItRuns) {
  Rig rig(4);
  rig.changer->load(4);
  rig.sim.run(*rig.changer);
  rig.changer->operator_continue();
  EXPECT_EQ(rig.status().awaiting, Awaiting::probe);
  EXPECT_EQ(rig.status().activity, "probe to touch-off sensor (seek)");
  ASSERT_TRUE(rig.step());
  EXPECT_EQ(rig.status().activity, "feed to back off the sensor");
  ASSERT_TRUE(rig.step());
  EXPECT_EQ(rig.status().activity, "probe to touch-off sensor (latch)");
}

TEST(Status, shouldSayItWaitsForTheSpindleToStopAsActivity) {
  Rig rig;
  rig.changer->spindle_stopped(false);
  rig.changer->tool_change(2);
  EXPECT_EQ(rig.status().activity, "rapid to safe Z") << "up to safe Z while it runs down";
  rig.sim.run(*rig.changer);
  EXPECT_EQ(rig.status().awaiting, Awaiting::spindle);
  EXPECT_EQ(rig.status().activity, "waiting for the spindle to stop");
  rig.changer->spindle_stopped(true);
  EXPECT_EQ(rig.status().awaiting, Awaiting::motion);
}

TEST(Status, shouldShowThePromptAsActivityWhileTheOperatorIsAsked) {
  {
    Rig rig;
    rig.changer->tool_change(9);  // no pocket: a manual tool
    rig.advance_until(Awaiting::operator_choice);
    EXPECT_EQ(
        rig.status().activity,
        "M6 T9: insert tool 9 into the spindle, then press Continue (Cancel stops the program)");
  }
  {
    Rig rig(4);
    rig.changer->load(4);
    rig.advance_until(Awaiting::operator_choice);
    EXPECT_EQ(rig.status().activity,
              "Tool 4 is in the spindle. Jog it closer to the touch-off sensor if you like, then "
              "press Continue to probe (Cancel to stop)");
  }
  {
    Rig rig(4);
    rig.changer->unload(4);
    rig.advance_until(Awaiting::operator_choice);
    EXPECT_EQ(rig.status().activity,
              "Remove tool 4 from the spindle, then press Continue (Cancel to stop)");
  }
}

// ---------------------------------------------------------------- holds_program

TEST(Status, shouldHoldTheProgramExactlyWhileAnM6WaitsForTheOperatorToHandAManualToolOver) {
  struct Case {
    int from;
    int to;
  };
  for (const Case c : {Case{0, 9}, Case{9, 2}}) {
    SCOPED_TRACE("M6 T" + std::to_string(c.to) + " with " + std::to_string(c.from) +
                 " in the spindle");
    Rig rig(c.from);
    rig.changer->tool_change(c.to);
    int questions = 0;
    while (rig.status().phase == Phase::changing) {
      const Status s = rig.status();
      EXPECT_EQ(s.holds_program, s.awaits_operator()) << s.activity;
      if (s.awaits_operator()) {
        ++questions;
        rig.changer->operator_continue();
      } else {
        ASSERT_TRUE(rig.step());
      }
    }
    EXPECT_EQ(questions, 1);
    EXPECT_EQ(rig.changer->tools().spindle, c.to);
    EXPECT_FALSE(rig.status().holds_program);
    for (const Step& step : rig.sim.steps()) {
      EXPECT_NE(step.kind, StepKind::wait_operator) << "the program holds: its run must not end";
    }
  }
}

TEST(Status, shouldNotHoldTheProgramWhenAnOperatorFlowAsksAndEndsTheRun) {
  for (const bool loading : {true, false}) {
    SCOPED_TRACE(loading ? "load" : "unload");
    Rig rig(4);
    loading ? rig.changer->load(4) : rig.changer->unload(4);
    rig.advance_until(Awaiting::operator_choice);
    EXPECT_EQ(rig.status().phase, loading ? Phase::loading : Phase::unloading);
    EXPECT_FALSE(rig.status().holds_program);
    EXPECT_EQ(rig.sim.steps().back().kind, StepKind::wait_operator);
  }
}

// ---------------------------------------------------------------- refusals

TEST(Refusal, shouldSayTheMachineIsNotReadyWhenARequestComesWhileItIsOff) {
  Rig rig;
  rig.changer->not_ready();
  const std::size_t from = rig.mark();
  rig.changer->tool_change(2);
  rig.changer->load(4);
  rig.changer->unload(4);
  EXPECT_EQ(rig.told(MessageKind::error, from),
            (Lines{"M6 T2 refused: " + kNotReady, "load of tool 4 refused: " + kNotReady,
                   "unload of tool 4 refused: " + kNotReady}));
  const std::vector<Step> steps = rig.published(from);
  ASSERT_EQ(steps.size(), 1u) << "only the M6 has an executor waiting";
  EXPECT_EQ(steps[0].kind, StepKind::fail);
  EXPECT_EQ(steps[0].label, "M6 T2 refused: " + kNotReady);
  EXPECT_EQ(steps[0].tool, 2);
  EXPECT_EQ(rig.status().phase, Phase::not_ready);
}

TEST(Refusal, shouldNameTheFaultWhenARequestComesWhileFaulted) {
  Rig rig;
  rig.changer->tool_change(2);
  ASSERT_TRUE(rig.step());
  rig.changer->abort("program aborted");
  const std::size_t from = rig.mark();
  rig.changer->tool_change(3);
  rig.changer->load(4);
  rig.changer->unload(4);
  const std::string why = " refused: the changer is in fault (program aborted); clear it first";
  EXPECT_EQ(rig.told(MessageKind::error, from),
            (Lines{"M6 T3" + why, "load of tool 4" + why, "unload of tool 4" + why}));
  const std::vector<Step> steps = rig.published(from);
  ASSERT_EQ(steps.size(), 1u);
  EXPECT_EQ(steps[0].kind, StepKind::fail);
  EXPECT_EQ(steps[0].label, "M6 T3" + why);
  EXPECT_EQ(rig.status().phase, Phase::fault);
}

struct BusyFlow {
  const char* name;
  int spindle;
  std::function<void(Changer&)> start;
  const char* doing;  ///< what the refusal says the changer is busy with
  int spindle_after;
};
std::ostream& operator<<(std::ostream& out, const BusyFlow& f) { return out << f.name; }

class WhileBusy : public ::testing::TestWithParam<BusyFlow> {};

TEST_P(WhileBusy, shouldRefuseEveryRequestAndFinishTheRunningFlowWhenOneComes) {
  const BusyFlow& flow = GetParam();
  Rig rig(flow.spindle);
  flow.start(*rig.changer);
  ASSERT_TRUE(rig.step());
  const std::string before = shown(rig.status());
  const std::size_t from = rig.mark();

  rig.changer->tool_change(5);
  rig.changer->load(5);
  rig.changer->unload(5);
  const std::string why = std::string(" refused: the changer is busy ") + flow.doing;
  EXPECT_EQ(rig.told(MessageKind::error, from),
            (Lines{"M6 T5" + why, "load of tool 5" + why, "unload of tool 5" + why}));
  const std::vector<Step> steps = rig.published(from);
  ASSERT_EQ(steps.size(), 1u) << "exactly one fail step, for the refused M6's executor";
  EXPECT_EQ(steps[0].kind, StepKind::fail);
  EXPECT_EQ(steps[0].label, "M6 T5" + why);
  EXPECT_EQ(steps[0].tool, 5);
  EXPECT_EQ(shown(rig.status()), before) << "the running flow goes on as it was";

  rig.finish();
  EXPECT_EQ(rig.status().phase, Phase::idle);
  EXPECT_EQ(rig.changer->tools().spindle, flow.spindle_after);
  EXPECT_EQ(rig.sim.steps().back().kind, StepKind::done);
  EXPECT_EQ(rig.told(MessageKind::error, from).size(), 3u) << "no error after the refusals";
}

// clang-format off
INSTANTIATE_TEST_SUITE_P(Each, WhileBusy, ::testing::Values(
  BusyFlow{"changing", 0, [](Changer& c) { c.tool_change(2); }, "changing to tool 2", 2},
  BusyFlow{"loading", 4, [](Changer& c) { c.load(4); }, "loading tool 4", 0},
  BusyFlow{"unloading", 4, [](Changer& c) { c.unload(4); }, "unloading tool 4", 0}
), [](const auto& info) { return std::string(info.param.name); });
// clang-format on

// ---------------------------------------------------------------- nothing to act on

struct Situation {
  const char* name;
  std::function<void(Rig&)> enter;
};
struct Press {
  const char* name;
  std::function<void(Changer&)> press;
  const char* answer;
};

class NothingToActOn : public ::testing::TestWithParam<std::tuple<Situation, Press>> {};

TEST_P(NothingToActOn, shouldOnlySaySoWhenPressed) {
  const auto& [situation, press] = GetParam();
  Rig rig;
  situation.enter(rig);
  const std::string before = shown(rig.status());
  const ToolState tools = rig.changer->tools();
  const bool timer_armed = rig.sim.timer_armed;
  const std::optional<Step> pending = rig.sim.pending;
  const std::size_t from = rig.mark();

  press.press(*rig.changer);
  ASSERT_EQ(rig.mark(), from + 1) << "one record: the message, nothing published";
  EXPECT_EQ(rig.told(MessageKind::info, from), Lines{press.answer});
  EXPECT_EQ(shown(rig.status()), before);
  EXPECT_TRUE(rig.changer->tools() == tools);
  EXPECT_EQ(rig.sim.timer_armed, timer_armed);
  EXPECT_EQ(rig.sim.pending.has_value(), pending.has_value());
}

const Situation kIdle{"idle", [](Rig&) {}};
const Situation kNotReadySituation{"not_ready", [](Rig& rig) { rig.changer->not_ready(); }};
const Situation kFaulted{"faulted", [](Rig& rig) {
                           rig.changer->tool_change(2);
                           rig.step();
                           rig.changer->abort("program aborted");
                         }};
const Situation kM6Moving{"m6_moving", [](Rig& rig) { rig.changer->tool_change(2); }};

const Press kContinue{"continue", [](Changer& c) { c.operator_continue(); },
                      "Continue: nothing is waiting for the operator"};
const Press kCancel{"cancel", [](Changer& c) { c.operator_cancel(); },
                    "Cancel: nothing is waiting for the operator"};
const Press kClearFault{"clear_fault", [](Changer& c) { c.clear_fault(3); },
                        "clear fault: there is no fault"};

std::string situation_and_press(
    const ::testing::TestParamInfo<std::tuple<Situation, Press>>& info) {
  return std::string(std::get<0>(info.param).name) + "_" + std::get<1>(info.param).name;
}

INSTANTIATE_TEST_SUITE_P(OperatorButtons, NothingToActOn,
                         ::testing::Combine(::testing::Values(kIdle, kNotReadySituation, kFaulted,
                                                              kM6Moving),
                                            ::testing::Values(kContinue, kCancel)),
                         situation_and_press);
INSTANTIATE_TEST_SUITE_P(ClearFault, NothingToActOn,
                         ::testing::Combine(::testing::Values(kIdle, kNotReadySituation, kM6Moving),
                                            ::testing::Values(kClearFault)),
                         situation_and_press);

// ---------------------------------------------------------------- cancel during a probe

TEST(Probe, shouldGoOnWithTheProbeWhenCancelIsPressedDuringAnM6Measure) {
  Rig rig(0, R"("probe_after_change": "measure")");
  rig.changer->tool_change(4);
  int probes = 0;
  while (rig.status().phase == Phase::changing) {
    if (rig.status().awaiting == Awaiting::probe) {
      ++probes;
      EXPECT_FALSE(rig.status().probe_cancellable) << "the probe runs inside the program";
      const std::string before = shown(rig.status());
      const std::size_t from = rig.mark();
      rig.changer->operator_cancel();
      EXPECT_EQ(rig.told(MessageKind::info, from),
                Lines{"Cancel: nothing is waiting for the operator"});
      EXPECT_TRUE(rig.published(from).empty());
      EXPECT_EQ(shown(rig.status()), before);
      ASSERT_TRUE(rig.sim.pending && rig.sim.pending->kind == StepKind::probe);
    }
    ASSERT_TRUE(rig.step());
  }
  EXPECT_EQ(probes, 2) << "seek and latch";
  EXPECT_EQ(rig.status().phase, Phase::idle);
  EXPECT_EQ(rig.changer->tools().spindle, 4);
  EXPECT_DOUBLE_EQ(rig.changer->tools().lengths.at(4), kMeasured);
}

TEST(Probe, shouldAbandonTheLoadProbeWhenCancelledAtEitherStage) {
  for (const char* stage : {"touch-off sensor (seek)", "touch-off sensor (latch)"}) {
    SCOPED_TRACE(stage);
    Rig rig(4);
    rig.changer->load(4);
    rig.advance_until(Awaiting::operator_choice);
    EXPECT_FALSE(rig.status().probe_cancellable) << "at the prompt";
    rig.changer->operator_continue();
    rig.advance_until([stage](const Status& s) {
      return s.awaiting == Awaiting::probe && s.activity == std::string("probe to ") + stage;
    });
    EXPECT_TRUE(rig.status().probe_cancellable);
    rig.sim.pending.reset();  // the adapter aborts the probe move first
    const std::size_t from = rig.mark();

    rig.changer->operator_cancel();
    const std::vector<Step> steps = rig.published(from);
    ASSERT_EQ(steps.size(), 1u);
    EXPECT_EQ(steps[0].kind, StepKind::rapid);
    EXPECT_EQ(steps[0].label, "loading Z");
    EXPECT_EQ(rig.told(MessageKind::info, from),
              Lines{"probe of tool 4 cancelled by the operator; nothing written"});
    EXPECT_FALSE(rig.status().probe_cancellable);
    EXPECT_EQ(rig.status().activity, "rapid to loading Z");

    rig.finish();
    EXPECT_EQ(rig.status().phase, Phase::idle);
    EXPECT_TRUE(rig.changer->tools().lengths.empty());
    EXPECT_FALSE(rig.status().last_length.has_value());
  }
}

// ---------------------------------------------------------------- timers

TEST(Timer, shouldLeaveNoTimerArmedWhenADwellIsCutOff) {
  struct Cut {
    const char* name;
    std::function<void(Changer&)> cut;
  };
  for (const Cut& cut : {Cut{"abort", [](Changer& c) { c.abort("program aborted"); }},
                         Cut{"machine off", [](Changer& c) { c.not_ready(); }}}) {
    SCOPED_TRACE(cut.name);
    Rig rig;
    rig.changer->tool_change(2);
    rig.advance_until(Awaiting::timer);
    ASSERT_TRUE(rig.sim.timer_armed);
    cut.cut(*rig.changer);
    EXPECT_EQ(rig.status().phase, Phase::fault);
    EXPECT_FALSE(rig.sim.timer_armed);
  }
}

TEST(Timer, shouldStopTheSpindleTimeoutWhenTheSpindleStops) {
  Rig rig;
  rig.changer->spindle_stopped(false);
  rig.changer->tool_change(2);
  rig.sim.run(*rig.changer);
  ASSERT_TRUE(rig.sim.timer_armed);
  rig.changer->spindle_stopped(true);
  EXPECT_EQ(rig.status().awaiting, Awaiting::motion);
  EXPECT_FALSE(rig.sim.timer_armed) << "no TimerElapsed may outlive the wait";
}

/// States cancel their timers on exit, so the core no longer filters stale
/// TimerElapsed: one that arrives while no timer runs is a bug, and says so.
void expect_stray_timer_reported_and_faulted(Bare& bare) {
  ASSERT_FALSE(bare.sim.timer_armed);
  bare.changer.timer_elapsed();
  ASSERT_EQ(bare.sim.unexpected_events.size(), 1u);
  EXPECT_NE(bare.sim.unexpected_events[0].find("TimerElapsed"), std::string::npos)
      << bare.sim.unexpected_events[0];
  EXPECT_EQ(bare.changer.status().phase, Phase::fault)
      << "Ports::unexpected: the machine faults after this";
  EXPECT_EQ(bare.changer.status().activity, "fault: internal error: unexpected fatc::TimerElapsed");
}

TEST(Timer, shouldReportATimerElapsedThatNoTimerRaisedAndFaultWhenAMoveIsPending) {
  Bare bare;
  bare.changer.ready();
  bare.changer.tool_change(2);
  expect_stray_timer_reported_and_faulted(bare);
}

TEST(Timer, shouldReportATimerElapsedThatNoTimerRaisedAndFaultWhenIdle) {
  Bare bare;
  bare.changer.ready();
  expect_stray_timer_reported_and_faulted(bare);
}

// ---------------------------------------------------------------- task availability

TEST(TaskAvailability, shouldRefuseLoadAndUnloadWithTheReasonWhileTaskIsBusy) {
  Rig rig(4);  // either request could start: tool 4 is in the spindle
  rig.changer->task_availability(kTaskBusy);
  EXPECT_EQ(rig.status().phase, Phase::idle);
  EXPECT_FALSE(rig.status().accepting);
  const std::size_t from = rig.mark();
  rig.changer->load(4);
  rig.changer->unload(4);
  EXPECT_EQ(rig.told(MessageKind::error, from), (Lines{"load of tool 4 refused: " + kTaskBusy,
                                                       "unload of tool 4 refused: " + kTaskBusy}));
  EXPECT_TRUE(rig.published(from).empty()) << "no executor waits for a load or unload";
  EXPECT_EQ(rig.status().phase, Phase::idle);
}

TEST(TaskAvailability, shouldAcceptOnlyWhileIdleAndTaskIsFree) {
  Rig rig(4);
  rig.changer->task_availability(kTaskBusy);
  rig.changer->task_availability(std::nullopt);
  EXPECT_TRUE(rig.status().accepting);
  rig.changer->load(4);
  EXPECT_EQ(rig.status().phase, Phase::loading);
  EXPECT_FALSE(rig.status().accepting) << "busy";
  rig.finish();
  EXPECT_EQ(rig.status().phase, Phase::idle);
  EXPECT_TRUE(rig.status().accepting);
  rig.changer->not_ready();
  EXPECT_FALSE(rig.status().accepting) << "not ready";
}

TEST(TaskAvailability, shouldStartAnM6WhileTaskIsBusy) {
  Rig rig;
  rig.changer->task_availability(kTaskBusy);  // the program that calls the M6 runs
  rig.changer->tool_change(2);
  EXPECT_EQ(rig.status().phase, Phase::changing);
  rig.finish();
  EXPECT_TRUE(rig.told(MessageKind::error).empty());
  EXPECT_EQ(rig.changer->tools().spindle, 2);
  EXPECT_EQ(rig.status().phase, Phase::idle);
  EXPECT_FALSE(rig.status().accepting) << "task is still busy";
}

// ---------------------------------------------------------------- last length

TEST(LastLength, shouldBeUnsetUntilAProbeMeasures) {
  Rig rig(4);
  EXPECT_FALSE(rig.status().last_length.has_value());
  rig.changer->load(4);
  rig.finish();
  ASSERT_TRUE(rig.status().last_length.has_value());
  EXPECT_DOUBLE_EQ(*rig.status().last_length,
                   kSensorZ - rig.config.probe_length_compensation_offset);
  EXPECT_DOUBLE_EQ(*rig.status().last_length, kMeasured);
  EXPECT_DOUBLE_EQ(rig.changer->tools().lengths.at(4), kMeasured);
}

TEST(LastLength, shouldShowTheMeasuredLengthWhenACheckWritesNothing) {
  Rig rig(0, R"("probe_after_change": "check")", {{4, kMeasured + 0.05}});
  rig.changer->tool_change(4);
  rig.finish();
  EXPECT_EQ(rig.status().phase, Phase::idle);
  ASSERT_TRUE(rig.status().last_length.has_value());
  EXPECT_DOUBLE_EQ(*rig.status().last_length, kMeasured);
  EXPECT_DOUBLE_EQ(rig.changer->tools().lengths.at(4), kMeasured + 0.05)
      << "the stored length stays";
  for (const Step& step : rig.sim.steps()) EXPECT_NE(step.kind, StepKind::set_tool_length);
}

TEST(Status, shouldHoldTheSpindleWhileAProbeIsInItAndSayEachToolsRule) {
  const std::string tools =
      R"("tools": {"2": {"kind": "probe"}, "3": {"measure": "check", "check_tolerance": 0.05}})";
  Rig probe(2, tools);
  EXPECT_EQ(probe.status().spindle_probe, 2);
  EXPECT_EQ(probe.status().rule, "T2 probe, spindle held, not measured at M6");
  Rig cutter(1, tools);
  EXPECT_EQ(cutter.status().spindle_probe, 0);
  EXPECT_EQ(cutter.status().rule, "T1 not measured at M6");
  // During a change the rule shown is the requested tool's.
  cutter.changer->tool_change(3);
  cutter.step();
  EXPECT_EQ(cutter.status().rule, "T3 checked ±0.05");
  EXPECT_EQ(Rig(0, tools).status().rule, "");
}

TEST(Status, shouldHoldTheSpindleWhenACutOffSequenceMayHaveLeftTheProbeInIt) {
  const Config config = test::valid_config(R"("tools": {"2": {"kind": "probe"}})");
  ToolState tools = ToolState::fresh(config);
  tools.spindle = 1;
  test::take_out(tools, 1);
  test::take_out(tools, 2);  // the probe's pocket empty: cut off while fetching it
  tools.uncertain = true;
  EXPECT_EQ(spindle_probe(config, tools), 2);
  tools.uncertain = false;
  EXPECT_EQ(spindle_probe(config, tools), 0) << "known: T1 in the spindle, the probe elsewhere";
}

TEST(Status, shouldHoldTheSpindleWhenAChangeToTheProbeIsCutOffAtAnyStep) {
  // M6 T2 (a probe) from T1, aborted at each step: the probe may be gripped
  // before the record says it left its pocket.
  // Returning T1 the probe sits in pocket 2; from the first step at pocket 2 on it may not.
  const std::string probe = R"("tools": {"2": {"kind": "probe"}})";
  bool at_probe_pocket = false;
  for (int cut = 1;; ++cut) {
    Rig rig(1, probe);
    rig.changer->tool_change(2);
    int steps = 0;
    while (steps < cut && rig.status().busy() && rig.step()) ++steps;
    if (!rig.status().busy()) break;  // the change ended before this step
    rig.changer->abort("the test cut it off");
    const Status after = rig.status();
    const auto& cut_off = rig.changer->cut_off();
    at_probe_pocket = at_probe_pocket || (cut_off && cut_off->pocket == 2);
    EXPECT_EQ(after.phase, Phase::fault) << "cut at step " << cut;
    EXPECT_EQ(after.spindle_probe, at_probe_pocket ? 2 : 0)
        << "cut at step " << cut << ": " << (cut_off ? cut_off->step : std::string("-"));
  }
  EXPECT_TRUE(at_probe_pocket);
  Rig manual(0, R"("tools": {"7": {"kind": "probe"}})");
  manual.changer->tool_change(7);  // a probe with no pocket, handed in at loading
  manual.advance_until(Awaiting::operator_choice);
  manual.changer->abort("the test cut it off");
  EXPECT_EQ(manual.status().spindle_probe, 7);
}

}  // namespace
}  // namespace fatc
