#include "core/protocol/executor_link.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <deque>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace fatc {
namespace {

using namespace std::chrono_literals;
using Kind = LinkEvent::Kind;
using Lines = std::vector<std::string>;

/// The component's turn period while a handshake is open. Any period would
/// do: the link only compares the times it is given.
constexpr std::chrono::milliseconds kTurn{10};

Step move(StepKind kind, unsigned axes, Point target, std::string label, double feed = 0.0) {
  Step step;
  step.kind = kind;
  step.axes = axes;
  step.target = target;
  step.feed = feed;
  step.label = std::move(label);
  return step;
}

Step rapid_z(double z, std::string label) {
  return move(StepKind::rapid, axis_z, {0.0, 0.0, z}, std::move(label));
}

Step command(StepKind kind, int tool, std::string label = "") {
  Step step;
  step.kind = kind;
  step.tool = tool;
  step.label = std::move(label);
  return step;
}

/// One event as a line, so that a whole turn compares (and prints) at once.
std::string show(const LinkEvent& e) {
  char z[32];
  std::snprintf(z, sizeof z, "%.3f", e.z);
  switch (e.kind) {
    case Kind::tool_change:
      return "tool_change T" + std::to_string(e.tool);
    case Kind::in_position:
      return "in_position";
    case Kind::command_done:
      return "command_done";
    case Kind::probe_result:
      return std::string("probe ") +
             (e.tripped_before ? "tripped_before"
              : e.touched      ? "touched"
                               : "missed") +
             " z=" + z;
    case Kind::executor_lost:
      return "executor_lost: " + e.reason;
    case Kind::chuck_release:
      return "chuck_release";
    case Kind::chuck_clamp:
      return "chuck_clamp";
    case Kind::refused_call:
      return "refused_call: " + e.reason;
  }
  return "?";
}

Lines show(const std::vector<LinkEvent>& events, std::size_t from = 0) {
  Lines lines;
  for (std::size_t i = from; i < events.size(); ++i) lines.push_back(show(events[i]));
  return lines;
}

const std::string kAborted = "executor_lost: LinuxCNC aborted the program during the sequence";

/// The link between a fake changer and a fake executor, turn by turn, on a
/// fake clock. Inputs are changed directly between turns (as the pins would).
struct Timeline {
  ExecutorLink link;
  ExecutorLink::Time now = ExecutorLink::Time{} + 1h;  // any epoch
  LinkInputs in;
  LinkOutputs out;                   ///< the last turn's outputs
  std::vector<LinkEvent> events;     ///< the last turn's events
  std::vector<LinkEvent> log;        ///< every event so far
  std::vector<LinkOutputs> outputs;  ///< every turn's outputs
  /// The fake changer publishes the next of these after each event it is told.
  std::deque<Step> script;
  bool changer_idle = false;
  /// Runs once in the next turn, between read() and write(), as the changer would.
  std::function<void()> during_turn;

  Timeline() { in.interpreter_idle = false; }

  void turn() {
    events = link.read(in, now);
    log.insert(log.end(), events.begin(), events.end());
    for (const LinkEvent& e : events) react(e);
    if (during_turn) {
      const std::function<void()> once = std::move(during_turn);
      during_turn = nullptr;
      once();
    }
    out = link.write(changer_idle);
    outputs.push_back(out);
  }

  /// Turns every kTurn until `span` has passed, the last one exactly at its end.
  void pass(std::chrono::milliseconds span) {
    const ExecutorLink::Time end = now + span;
    while (now + kTurn <= end) {
      now += kTurn;
      turn();
    }
    if (now < end) {
      now = end;
      turn();
    }
  }

  // The executor's side of the handshake (nc_files/fixed_atc_probe_execute.ngc).

  /// Called with `call` (executor-call is set before the first M64).
  void start_executor(int call, int number = 0) {
    in.call = call;
    in.number = number;
    in.interpreter_idle = false;
    in.step_request = true;
    turn();
  }
  /// Step-ready is high (M66 L3): reads the step pins and drops the request (M65).
  Step take() {
    EXPECT_TRUE(in.step_request) << "the executor takes a step only while it asks";
    EXPECT_TRUE(out.step_ready) << "the executor would still be waiting in M66 L3";
    const Step step = out.step;
    in.step_request = false;
    turn();
    EXPECT_FALSE(out.step_ready) << "step-ready must fall once the request falls";
    return step;
  }
  /// Step-ready is low (M66 L4): performs the step, then asks for the next (M64).
  void report() {
    EXPECT_FALSE(in.step_request);
    EXPECT_FALSE(out.step_ready) << "the executor would still be waiting in M66 L4";
    in.step_request = true;
    turn();
  }
  void report_probe(double result, double z) {
    in.probe_result = result;  // M68 E<probe_result_out>, before the M64
    in.probe_z = z;
    report();
  }
  /// Takes one step and, unless it ends the run, performs it and asks again.
  Step run_step() {
    const Step step = take();
    if (step.kind != StepKind::done && step.kind != StepKind::fail &&
        step.kind != StepKind::wait_operator) {
      report();
    }
    return step;
  }

 private:
  void react(const LinkEvent& e) {
    if (e.kind == Kind::executor_lost) {
      // As the component: abort the changer (which publishes a fail step for
      // an executor that is no longer there), then drop().
      script.clear();
      link.publish(failure_step("program aborted"));
      link.drop();
      return;
    }
    if (!script.empty()) {
      link.publish(script.front());
      script.pop_front();
    }
  }
};

// ---------------------------------------------------------------- M6

TEST(ExecutorLink, shouldReportToolChangeWhenM6RaisesItsFirstRequest) {
  Timeline t;
  t.in.number = 99;  // a stale number before the M6 must not be used
  t.turn();
  EXPECT_TRUE(t.events.empty());
  t.start_executor(1, 5);
  ASSERT_EQ(show(t.events), Lines({"tool_change T5"}));
  EXPECT_EQ(t.events[0].kind, Kind::tool_change);
  EXPECT_EQ(t.events[0].tool, 5);
  EXPECT_TRUE(t.link.attached());
  EXPECT_FALSE(t.out.step_ready) << "the changer published nothing yet";
}

TEST(ExecutorLink, shouldRunAnM6StepByStepWhenEachRequestReportsTheStepBefore) {
  Timeline t;
  const Step rapid = move(StepKind::rapid, axis_xy, {120.0, 40.0, 0.0}, "above pocket 5");
  const Step feed = move(StepKind::feed, axis_z, {0.0, 0.0, -80.0}, "into pocket 5", 500.0);
  Step length = command(StepKind::set_tool_length, 5, "length of T5");
  length.value = 42.125;
  t.script = {rapid, feed, length, command(StepKind::set_spindle_tool, 5),
              command(StepKind::done, 5)};

  t.start_executor(1, 5);
  EXPECT_EQ(show(t.events), Lines({"tool_change T5"}));
  // The changer's answer to the event goes on the pins in the same turn.
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.kind, StepKind::rapid);
  EXPECT_EQ(t.out.step.axes, static_cast<unsigned>(axis_xy));
  EXPECT_DOUBLE_EQ(t.out.step.target.x, 120.0);
  EXPECT_DOUBLE_EQ(t.out.step.target.y, 40.0);
  EXPECT_EQ(t.out.step.label, "above pocket 5");

  // The step stays offered, unchanged, however long the executor takes to read it.
  t.pass(1s);
  EXPECT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.label, "above pocket 5");
  EXPECT_TRUE(t.events.empty());

  EXPECT_EQ(t.take().label, "above pocket 5");
  EXPECT_TRUE(t.events.empty()) << "taking a step is no event";
  t.pass(2s);  // the rapid runs
  EXPECT_TRUE(t.events.empty());
  EXPECT_FALSE(t.out.step_ready);
  t.report();
  EXPECT_EQ(show(t.events), Lines({"in_position"}));
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.kind, StepKind::feed);
  EXPECT_DOUBLE_EQ(t.out.step.target.z, -80.0);
  EXPECT_DOUBLE_EQ(t.out.step.feed, 500.0);

  EXPECT_EQ(t.run_step().kind, StepKind::feed);
  EXPECT_EQ(show(t.events), Lines({"in_position"}));
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.kind, StepKind::set_tool_length);
  EXPECT_EQ(t.out.step.tool, 5);
  EXPECT_DOUBLE_EQ(t.out.step.value, 42.125);

  EXPECT_EQ(t.run_step().kind, StepKind::set_tool_length);
  EXPECT_EQ(show(t.events), Lines({"command_done"}));
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.kind, StepKind::set_spindle_tool);

  EXPECT_EQ(t.run_step().kind, StepKind::set_spindle_tool);
  EXPECT_EQ(show(t.events), Lines({"command_done"}));
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.kind, StepKind::done);
  EXPECT_EQ(t.out.step.tool, 5);
  EXPECT_TRUE(t.link.attached());

  // done ends the run: the executor takes it, returns, and never asks again.
  EXPECT_EQ(t.run_step().kind, StepKind::done);
  EXPECT_TRUE(t.events.empty()) << "done itself is no event";
  EXPECT_FALSE(t.link.attached());
  EXPECT_FALSE(t.out.step_ready);

  // The remap goes on and the program ends: idle is no longer an abort.
  t.pass(1s);
  t.in.interpreter_idle = true;
  t.pass(1s);
  EXPECT_EQ(show(t.log), Lines({"tool_change T5", "in_position", "in_position", "command_done",
                                "command_done"}));
  EXPECT_FALSE(t.link.active());
}

// ---------------------------------------------------------------- probe

struct ProbeCase {
  const char* name;
  double result;
  double z;
  const char* line;
  bool touched;
  bool tripped_before;
};
std::ostream& operator<<(std::ostream& out, const ProbeCase& c) { return out << c.name; }

class ProbeStep : public ::testing::TestWithParam<ProbeCase> {};

TEST_P(ProbeStep, shouldReportTheProbePinsWhenTheRequestAfterAProbeRises) {
  const ProbeCase& c = GetParam();
  Timeline t;
  t.in.probe_result = 1.0;  // left over from an earlier probe: only the values at the report count
  t.in.probe_z = 3.0;
  t.script = {move(StepKind::probe, axis_z, {0.0, 0.0, -120.0}, "probe T5", 100.0)};
  t.start_executor(1, 5);
  EXPECT_EQ(t.take().kind, StepKind::probe);
  t.report_probe(c.result, c.z);
  ASSERT_EQ(show(t.events), Lines({c.line}));
  EXPECT_EQ(t.events[0].kind, Kind::probe_result);
  EXPECT_EQ(t.events[0].touched, c.touched);
  EXPECT_EQ(t.events[0].tripped_before, c.tripped_before);
  EXPECT_DOUBLE_EQ(t.events[0].z, c.z);
}

// clang-format off
INSTANTIATE_TEST_SUITE_P(Each, ProbeStep, ::testing::Values(
  ProbeCase{"touched", 1.0, -63.25, "probe touched z=-63.250", true, false},
  ProbeCase{"missed", 0.0, -120.0, "probe missed z=-120.000", false, false},
  ProbeCase{"tripped_before", -1.0, -20.0, "probe tripped_before z=-20.000", false, true}
), [](const auto& info) { return std::string(info.param.name); });
// clang-format on

// ---------------------------------------------------------------- operator flow

TEST(ExecutorLink, shouldAskForAnMdiRunWhenAnOperatorFlowStepWaitsWithoutAnExecutor) {
  Timeline t;
  t.in.interpreter_idle = true;  // the operator starts the load from the GUI: no program runs
  t.link.publish(rapid_z(50.0, "safe Z"));
  t.turn();
  EXPECT_FALSE(t.out.step_ready) << "nothing asks for it yet";
  EXPECT_TRUE(t.events.empty());
  EXPECT_TRUE(t.link.needs_run(t.now));

  // The MDI run is asked for; it may take a while to start.
  t.link.run_started(t.now);
  EXPECT_FALSE(t.link.needs_run(t.now));
  t.pass(std::chrono::milliseconds(ExecutorLink::kRunStartGrace) - 1ms);
  EXPECT_FALSE(t.link.needs_run(t.now));
  // It never came: ask again.
  t.pass(1ms);
  EXPECT_TRUE(t.link.needs_run(t.now));

  t.link.run_started(t.now);
  t.start_executor(2, 99);
  EXPECT_TRUE(t.events.empty()) << "an operator flow's executor is no tool change";
  EXPECT_TRUE(t.link.attached());
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.label, "safe Z");
  t.pass(10s);
  EXPECT_FALSE(t.link.needs_run(t.now)) << "attached: the run is there";

  t.script = {command(StepKind::wait_operator, 0, "insert tool 3")};
  EXPECT_EQ(t.run_step().label, "safe Z");
  EXPECT_EQ(show(t.events), Lines({"in_position"}));
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.kind, StepKind::wait_operator);

  // wait_operator ends the run; the MDI command then ends and the interpreter idles.
  EXPECT_EQ(t.run_step().kind, StepKind::wait_operator);
  EXPECT_TRUE(t.events.empty());
  EXPECT_FALSE(t.link.attached());
  EXPECT_FALSE(t.out.step_ready);
  t.in.interpreter_idle = true;
  t.pass(30s);
  EXPECT_TRUE(t.events.empty()) << "the operator may take any time: no executor_lost";
  EXPECT_FALSE(t.link.needs_run(t.now)) << "nothing waits";
  EXPECT_FALSE(t.link.active());

  // Continue: the flow's next step needs a new run.
  t.link.publish(move(StepKind::feed, axis_z, {0.0, 0.0, -80.0}, "into pocket 3", 400.0));
  t.turn();
  EXPECT_FALSE(t.out.step_ready);
  EXPECT_TRUE(t.link.needs_run(t.now));
  t.link.run_started(t.now);
  t.pass(1s);
  EXPECT_FALSE(t.link.needs_run(t.now));
  t.start_executor(2);
  EXPECT_TRUE(t.events.empty());
  EXPECT_TRUE(t.link.attached());
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.label, "into pocket 3");
  // The run came in time: it must not be asked for again once the grace is over.
  t.pass(std::chrono::milliseconds(ExecutorLink::kRunStartGrace) + 1s);
  EXPECT_FALSE(t.link.needs_run(t.now));
  EXPECT_EQ(t.run_step().label, "into pocket 3");
  EXPECT_EQ(show(t.events), Lines({"in_position"}));
}

TEST(ExecutorLink, shouldAskForTheNextRunAtOnceWhenTheLastOneCameAndEndedWithinTheGrace) {
  Timeline t;
  t.in.interpreter_idle = true;
  t.link.publish(rapid_z(50.0, "safe Z"));
  t.turn();
  const ExecutorLink::Time asked = t.now;
  t.link.run_started(asked);
  t.pass(100ms);
  t.start_executor(2);
  t.script = {command(StepKind::wait_operator, 0, "insert tool 3")};
  t.run_step();
  EXPECT_EQ(t.run_step().kind, StepKind::wait_operator);
  t.in.interpreter_idle = true;
  t.pass(100ms);
  // The operator is quick: the grace of the run asked for above is not over,
  // but that run came, so the next one is needed now.
  t.link.publish(rapid_z(60.0, "next"));
  ASSERT_LT(t.now, asked + ExecutorLink::kRunStartGrace);
  EXPECT_TRUE(t.link.needs_run(t.now));
}

// ---------------------------------------------------------------- hold

TEST(ExecutorLink, shouldWaitSilentlyWhenTheChangerHoldsInsideM6) {
  Timeline t;
  t.start_executor(1, 3);
  EXPECT_EQ(show(t.events), Lines({"tool_change T3"}));
  const std::size_t from = t.outputs.size();

  // The changer waits (for the spindle to stop, for the operator...): the
  // executor keeps its request high, the interpreter is busy in M66.
  t.pass(10min);
  EXPECT_EQ(show(t.log), Lines({"tool_change T3"}));
  for (std::size_t i = from; i < t.outputs.size(); ++i) {
    ASSERT_FALSE(t.outputs[i].step_ready) << "turn " << i;
  }
  EXPECT_TRUE(t.link.attached());
  EXPECT_TRUE(t.link.active());
  EXPECT_FALSE(t.link.needs_run(t.now)) << "an executor is attached: no MDI run";

  t.link.publish(rapid_z(50.0, "safe Z"));
  t.turn();
  EXPECT_TRUE(t.events.empty());
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.label, "safe Z");
  EXPECT_EQ(t.run_step().label, "safe Z");
  EXPECT_EQ(show(t.events), Lines({"in_position"}));
}

// ---------------------------------------------------------------- resync

/// A run aborted while its request was high (the changer had not answered
/// yet), the program idle afterwards: the request stays high.
void abort_with_request_high(Timeline& t) {
  t.script = {rapid_z(50.0, "safe Z")};
  t.start_executor(1, 4);
  t.run_step();
  ASSERT_EQ(show(t.log), Lines({"tool_change T4", "in_position"}));
  ASSERT_FALSE(t.out.step_ready);
  t.in.interpreter_idle = true;
  t.turn();
  t.pass(ExecutorLink::kAbortGrace);
  ASSERT_EQ(show(t.events), Lines({kAborted}));
  ASSERT_TRUE(t.in.step_request);
}

TEST(ExecutorLink, shouldOfferResyncWhenDroppedWithTheRequestHigh) {
  Timeline t;
  abort_with_request_high(t);
  // The fixture's changer answered the loss with a fail step, then drop()ped.
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.kind, StepKind::resync);
  EXPECT_FALSE(t.link.attached());
  t.pass(1min);
  EXPECT_EQ(show(t.log), Lines({"tool_change T4", "in_position", kAborted}))
      << "no more events while the program is gone";
  EXPECT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.kind, StepKind::resync);
  EXPECT_FALSE(t.link.needs_run(t.now)) << "nothing waits";
}

TEST(ExecutorLink, shouldTakeTheResyncThenAttachWhenAnOperatorFlowRunsAfterAnAbort) {
  Timeline t;
  abort_with_request_high(t);
  const std::size_t from = t.log.size();

  t.link.publish(rapid_z(50.0, "safe Z for the load"));
  t.turn();
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.kind, StepKind::resync) << "the resync stays until it is taken";
  EXPECT_TRUE(t.link.needs_run(t.now)) << "only the resync is offered: a run must take it";

  t.link.run_started(t.now);
  t.start_executor(2);  // its M64 finds the output already high: no edge
  EXPECT_TRUE(t.events.empty());
  EXPECT_EQ(t.take().kind, StepKind::resync);
  EXPECT_TRUE(t.events.empty()) << "a resync is not executed: no event for it";
  EXPECT_FALSE(t.link.attached());
  EXPECT_FALSE(t.link.needs_run(t.now)) << "the run was started";

  t.report();  // kind 0: nothing to do, ask again
  EXPECT_TRUE(t.events.empty()) << "executor-call 2: attach without a tool change";
  EXPECT_TRUE(t.link.attached());
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.label, "safe Z for the load");
  EXPECT_EQ(t.run_step().label, "safe Z for the load");
  EXPECT_EQ(show(t.log, from), Lines({"in_position"}));
}

TEST(ExecutorLink, shouldTakeTheResyncThenReportToolChangeWhenAnM6RunsAfterAnAbort) {
  Timeline t;
  abort_with_request_high(t);
  const std::size_t from = t.log.size();

  t.script = {rapid_z(50.0, "safe Z for T8")};
  t.start_executor(1, 8);
  EXPECT_TRUE(t.events.empty());
  EXPECT_EQ(t.take().kind, StepKind::resync);
  EXPECT_TRUE(t.events.empty());
  t.report();
  EXPECT_EQ(show(t.events), Lines({"tool_change T8"})) << "the first request of the new run";
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.label, "safe Z for T8");
  EXPECT_EQ(t.run_step().label, "safe Z for T8");
  EXPECT_EQ(show(t.log, from), Lines({"tool_change T8", "in_position"}));
}

// ---------------------------------------------------------------- executor lost

TEST(ExecutorLink, shouldReportNothingWhileAStepExecutesForAnyTime) {
  Timeline t;
  t.script = {move(StepKind::feed, axis_z, {0.0, 0.0, -80.0}, "slowly down", 1.0)};
  t.start_executor(1, 2);
  EXPECT_EQ(t.take().label, "slowly down");
  t.pass(30min);
  EXPECT_EQ(show(t.log), Lines({"tool_change T2"}));
  EXPECT_FALSE(t.out.step_ready);
  EXPECT_TRUE(t.link.attached());
  EXPECT_TRUE(t.link.active());
}

TEST(ExecutorLink, shouldReportExecutorLostOnceWhenTheInterpreterIdlesForTheGraceWhileAttached) {
  Timeline t;
  t.script = {move(StepKind::feed, axis_z, {0.0, 0.0, -80.0}, "slowly down", 1.0)};
  t.start_executor(1, 2);
  t.take();
  t.pass(1min);
  const std::size_t from = t.log.size();

  // A short idle (a status glitch) is no abort, and the grace starts over after it.
  t.in.interpreter_idle = true;
  t.turn();
  t.pass(ExecutorLink::kAbortGrace - 10ms);
  EXPECT_TRUE(show(t.log, from).empty());
  t.in.interpreter_idle = false;
  t.pass(kTurn);
  t.in.interpreter_idle = true;
  t.turn();
  t.pass(ExecutorLink::kAbortGrace - 1ms);
  EXPECT_TRUE(show(t.log, from).empty()) << "idle for less than the grace";

  t.pass(1ms);
  ASSERT_EQ(show(t.events), Lines({kAborted}));
  EXPECT_EQ(t.events[0].kind, Kind::executor_lost);
  EXPECT_EQ(t.events[0].reason, "LinuxCNC aborted the program during the sequence");
  EXPECT_FALSE(t.link.attached());
  EXPECT_FALSE(t.out.step_ready) << "the request was low: no resync";

  t.pass(10s);
  EXPECT_EQ(show(t.log, from), Lines({kAborted})) << "exactly once";
  EXPECT_FALSE(t.link.active());
}

TEST(ExecutorLink, shouldReportExecutorLostWhenTheExecutorTimesOutAndDropsItsRequest) {
  Timeline t;
  t.start_executor(1, 6);
  t.pass(30s);  // STEP_TIMEOUT: nothing was published
  // The executor's M65 then "(abort, ...)": the program ends.
  t.in.step_request = false;
  t.turn();
  EXPECT_TRUE(t.events.empty()) << "a request falling with nothing offered is no step";
  t.in.interpreter_idle = true;
  t.turn();
  t.pass(ExecutorLink::kAbortGrace);
  EXPECT_EQ(show(t.log), Lines({"tool_change T6", kAborted}));
  EXPECT_FALSE(t.out.step_ready);
  EXPECT_FALSE(t.link.active());
}

TEST(ExecutorLink,
     shouldReportExecutorLostAndOfferResyncWhenTheTimedOutExecutorLeftItsRequestHigh) {
  Timeline t;
  t.start_executor(1, 6);
  t.pass(30s);
  // The abort flushed motion before the M65 took effect.
  t.in.interpreter_idle = true;
  t.turn();
  t.pass(ExecutorLink::kAbortGrace);
  EXPECT_EQ(show(t.log), Lines({"tool_change T6", kAborted}));
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.kind, StepKind::resync) << "not the changer's fail step";
}

TEST(ExecutorLink, shouldNeverReportExecutorLostWhenTheInterpreterStatusIsUnknown) {
  Timeline t;
  t.in.interpreter_idle = std::nullopt;  // no NML status
  t.script = {rapid_z(50.0, "safe Z")};
  t.start_executor(1, 2);
  t.in.interpreter_idle = std::nullopt;
  t.pass(10min);  // request high, step offered
  t.take();
  t.pass(10min);  // executing
  t.report();
  t.pass(10min);  // request high, nothing offered
  EXPECT_EQ(show(t.log), Lines({"tool_change T2", "in_position"}));
  EXPECT_TRUE(t.link.attached());
}

// ---------------------------------------------------------------- abort at each phase

enum class HandshakePhase {
  request_up_before_offer,
  offered_request_up,
  request_down_unseen,  ///< the request fell but the link has not read it yet
  request_down_seen,    ///< the turn that reads the fall drops before it writes
  executing,
  request_up_reporting,
};

struct AbortCase {
  const char* name;
  HandshakePhase phase;
  bool resync;  ///< the link sees the request high when it drops
};
std::ostream& operator<<(std::ostream& out, const AbortCase& c) { return out << c.name; }

class AbortAt : public ::testing::TestWithParam<AbortCase> {};

TEST_P(AbortAt, shouldForgetTheRunAndOfferOnlyResyncWhenDropped) {
  const HandshakePhase phase = GetParam().phase;
  const Step stale = rapid_z(10.0, "stale");
  Timeline t;
  if (phase != HandshakePhase::request_up_before_offer) t.script = {rapid_z(50.0, "first")};
  t.start_executor(1, 4);
  ASSERT_EQ(show(t.events), Lines({"tool_change T4"}));
  // The changer had published one more step just before the abort: it must be forgotten too.
  const auto drop = [&t, &stale] {
    t.link.publish(stale);
    t.link.drop();
  };
  switch (phase) {
    case HandshakePhase::request_up_before_offer:
      ASSERT_FALSE(t.out.step_ready);
      drop();
      break;
    case HandshakePhase::offered_request_up:
      ASSERT_TRUE(t.out.step_ready);
      drop();
      break;
    case HandshakePhase::request_down_unseen:
      t.in.step_request = false;
      drop();
      break;
    case HandshakePhase::request_down_seen:
      t.during_turn = drop;
      t.in.step_request = false;
      t.turn();
      break;
    case HandshakePhase::executing:
      t.take();
      drop();
      break;
    case HandshakePhase::request_up_reporting:
      t.take();
      t.report();
      ASSERT_EQ(show(t.events), Lines({"in_position"}));
      ASSERT_FALSE(t.out.step_ready);
      drop();
      break;
  }
  EXPECT_FALSE(t.link.attached());
  const std::size_t from_outputs = t.outputs.size();
  const std::size_t from = t.log.size();

  // The program is gone: nothing is reported, step-ready is high only for a
  // resync and only while the request is high.
  t.in.interpreter_idle = true;
  t.pass(2s);
  EXPECT_TRUE(show(t.log, from).empty());
  for (std::size_t i = from_outputs; i < t.outputs.size(); ++i) {
    ASSERT_EQ(t.outputs[i].step_ready, GetParam().resync) << "turn " << i;
    if (t.outputs[i].step_ready) {
      EXPECT_EQ(t.outputs[i].step.kind, StepKind::resync);
    }
  }
  EXPECT_EQ(t.in.step_request, GetParam().resync);
  EXPECT_FALSE(t.link.needs_run(t.now)) << "the stale step is not pending";

  // A new M6. The changer answers its tool change later, on its own.
  t.start_executor(1, 9);
  if (GetParam().resync) {
    EXPECT_TRUE(t.events.empty());
    EXPECT_EQ(t.take().kind, StepKind::resync);
    EXPECT_TRUE(t.events.empty());
    t.report();
  }
  EXPECT_EQ(show(t.events), Lines({"tool_change T9"})) << "not a report of the dead run's step";
  EXPECT_FALSE(t.out.step_ready) << "the stale step must not be offered";
  t.pass(1s);
  EXPECT_FALSE(t.out.step_ready);

  t.link.publish(rapid_z(60.0, "fresh"));
  t.turn();
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.label, "fresh");
  EXPECT_EQ(t.run_step().label, "fresh");
  EXPECT_EQ(show(t.log, from), Lines({"tool_change T9", "in_position"}));
}

// clang-format off
INSTANTIATE_TEST_SUITE_P(Each, AbortAt, ::testing::Values(
  AbortCase{"request_up_before_offer", HandshakePhase::request_up_before_offer, true},
  AbortCase{"offered_request_up", HandshakePhase::offered_request_up, true},
  AbortCase{"request_down_unseen", HandshakePhase::request_down_unseen, false},
  AbortCase{"request_down_seen", HandshakePhase::request_down_seen, false},
  AbortCase{"executing", HandshakePhase::executing, false},
  AbortCase{"request_up_reporting", HandshakePhase::request_up_reporting, true}
), [](const auto& info) { return std::string(info.param.name); });
// clang-format on

// ---------------------------------------------------------------- iocontrol

TEST(ExecutorLink, shouldFollowToolPrepareWithPrepared) {
  Timeline t;
  t.changer_idle = true;
  t.turn();
  EXPECT_FALSE(t.out.prepared);
  t.in.tool_prepare = true;
  t.turn();
  EXPECT_TRUE(t.out.prepared);
  t.changer_idle = false;  // prepare does not wait for the changer
  t.turn();
  EXPECT_TRUE(t.out.prepared);
  t.in.tool_prepare = false;
  t.turn();
  EXPECT_FALSE(t.out.prepared);
}

TEST(ExecutorLink, shouldRaiseChangedOnlyWhileToolChangeIsHighAndTheChangerIsIdle) {
  Timeline t;
  t.changer_idle = true;
  t.turn();
  EXPECT_FALSE(t.out.changed) << "no tool-change";

  // tool-change while the changer still works: changed waits for it.
  t.changer_idle = false;
  t.in.tool_change = true;
  t.pass(1s);
  EXPECT_FALSE(t.out.changed);
  t.changer_idle = true;
  t.turn();
  EXPECT_TRUE(t.out.changed);
  t.pass(1s);
  EXPECT_TRUE(t.out.changed) << "a level: high until tool-change drops";

  t.in.tool_change = false;
  t.turn();
  EXPECT_FALSE(t.out.changed) << "falls in the turn tool-change drops";
}

TEST(ExecutorLink, shouldNeverRaiseChangedWhenToolChangeDropsBeforeTheChangerIsIdle) {
  Timeline t;
  t.changer_idle = false;
  t.in.tool_change = true;
  t.turn();
  EXPECT_FALSE(t.out.changed);
  t.in.tool_change = false;  // e.g. the program was aborted
  t.turn();
  t.changer_idle = true;
  t.pass(1s);
  for (const LinkOutputs& o : t.outputs) EXPECT_FALSE(o.changed);
}

// ---------------------------------------------------------------- bad call

class UnknownCall : public ::testing::TestWithParam<int> {};

TEST_P(UnknownCall, shouldFailTheExecutorNamingTheValueWhenCalledWithIt) {
  const int call = GetParam();
  Timeline t;
  t.start_executor(call, 5);
  ASSERT_EQ(t.events.size(), 1u) << "no tool change for a call that is not 1";
  EXPECT_EQ(t.events[0].kind, Kind::refused_call) << "the component tells the operator";
  EXPECT_NE(t.events[0].reason.find("executor-call " + std::to_string(call) + "; expected 1 (M6)"),
            std::string::npos)
      << t.events[0].reason;
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.kind, StepKind::fail);
  const std::string named = "executor-call " + std::to_string(call);
  EXPECT_NE(t.out.step.label.find(named), std::string::npos) << t.out.step.label;

  EXPECT_EQ(t.run_step().kind, StepKind::fail);
  EXPECT_FALSE(t.link.attached());
  t.in.interpreter_idle = true;  // the executor returned -1 and the program aborted
  t.pass(1s);
  EXPECT_EQ(t.log.size(), 1u) << "the changer never knew of this run, only the operator";
  EXPECT_FALSE(t.link.active());
}

INSTANTIATE_TEST_SUITE_P(Each, UnknownCall, ::testing::Values(0, 5, 7));

TEST(ExecutorLink, shouldKeepTheWaitingStepForTheNextRunWhenAnExecutorWithAnUnknownCallIsFailed) {
  Timeline t;
  t.in.interpreter_idle = true;
  t.link.publish(rapid_z(50.0, "safe Z for the load"));  // an operator flow waits for its run
  t.turn();
  ASSERT_TRUE(t.link.needs_run(t.now));

  t.start_executor(0);  // someone calls o<fixed_atc_probe_execute> without its argument
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.kind, StepKind::fail);
  t.run_step();
  t.in.interpreter_idle = true;
  t.turn();

  // The changer's step was never offered to a valid run: it still waits.
  EXPECT_TRUE(t.link.needs_run(t.now));
  t.link.run_started(t.now);
  t.start_executor(2);
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.label, "safe Z for the load");
}

// ---------------------------------------------------------------- publish

TEST(ExecutorLink, shouldForgetAStepLeftFromBeforeWhenAnM6StartsItsRun) {
  Timeline t;
  // A fault published its fail step while no executor was attached.
  t.link.publish(failure_step("fault: the machine went off"));
  t.script = {rapid_z(50.0, "safe Z")};
  t.start_executor(static_cast<int>(ExecutorCall::tool_change), 3);
  ASSERT_EQ(show(t.events), Lines({"tool_change T3"}));
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.label, "safe Z") << "the M6 gets its own first step, not the old fail";
}

TEST(ExecutorLink, shouldOfferResyncForARequestLeftHighThatWasNeverCounted) {
  Timeline t;
  // M64 reached the pin, then the program was aborted before task reported it.
  t.in.interpreter_idle = true;
  t.in.step_request = true;
  t.turn();
  EXPECT_FALSE(t.link.attached());
  t.link.drop();
  t.turn();
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.kind, StepKind::resync);
}

TEST(ExecutorLink, shouldOfferNothingWhenAStepIsPublishedWithoutARequest) {
  Timeline t;
  t.changer_idle = true;
  t.turn();
  const LinkOutputs before = t.out;
  t.link.publish(rapid_z(50.0, "safe Z"));
  t.pass(1s);
  EXPECT_FALSE(t.out.step_ready);
  EXPECT_EQ(t.out.step.kind, before.step.kind) << "the step pins keep their values";
  EXPECT_EQ(t.out.step.label, before.step.label);
}

TEST(ExecutorLink, shouldOfferOnlyTheLastStepWhenTwoArePublishedBeforeTheExecutorAsks) {
  Timeline t;
  t.link.publish(rapid_z(50.0, "first"));
  t.link.publish(rapid_z(60.0, "second"));
  t.turn();
  t.start_executor(2);
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.label, "second");
  EXPECT_EQ(t.run_step().label, "second");
  EXPECT_EQ(show(t.events), Lines({"in_position"}));
  EXPECT_FALSE(t.out.step_ready) << "the first one is gone";
  t.pass(1s);
  EXPECT_FALSE(t.out.step_ready);
}

TEST(ExecutorLink, shouldBeActiveWhileAHandshakeIsOpenOrAStepWaits) {
  Timeline t;
  t.changer_idle = true;
  t.turn();
  EXPECT_FALSE(t.link.active()) << "all quiet";

  t.link.publish(rapid_z(50.0, "safe Z"));
  EXPECT_TRUE(t.link.active()) << "a step waits";
  t.start_executor(2);
  EXPECT_TRUE(t.link.active()) << "offered";
  t.take();
  EXPECT_TRUE(t.link.active()) << "executing";
  t.script = {command(StepKind::done, 0)};
  t.report();
  EXPECT_TRUE(t.link.active()) << "request high";
  t.take();
  EXPECT_FALSE(t.link.attached());
  EXPECT_FALSE(t.link.active()) << "the run ended and nothing waits";
  t.in.interpreter_idle = true;
  t.pass(1s);
  EXPECT_FALSE(t.link.active());
}

// ---------------------------------------------------------------- request before the run

TEST(ExecutorLink, shouldCountARequestThatRoseWhileTheInterpreterWasIdleOnceTaskReportsTheRun) {
  Timeline t;
  t.script = {rapid_z(50.0, "safe Z")};  // the changer's answer to the M6
  // The executor's M64 is seen before task reports the run that raised it:
  // executor-call and number may still be a previous run's.
  t.in.interpreter_idle = true;
  t.in.call = 2;
  t.in.number = 99;
  t.in.step_request = true;
  t.turn();
  EXPECT_TRUE(t.events.empty());
  EXPECT_FALSE(t.out.step_ready) << "nothing offered to a run that is not known";
  EXPECT_FALSE(t.link.attached());
  t.pass(1s);
  EXPECT_TRUE(t.log.empty());
  for (const LinkOutputs& o : t.outputs) EXPECT_FALSE(o.step_ready);
  EXPECT_FALSE(t.link.attached());

  // Task reports the run; the pins now hold its executor-call and number.
  t.in.call = 1;
  t.in.number = 7;
  t.in.interpreter_idle = false;
  t.turn();
  ASSERT_EQ(show(t.events), Lines({"tool_change T7"}))
      << "the request counts now, with this turn's pins";
  EXPECT_TRUE(t.link.attached());
  ASSERT_TRUE(t.out.step_ready);
  EXPECT_EQ(t.out.step.label, "safe Z");
  EXPECT_EQ(t.run_step().label, "safe Z");
  EXPECT_EQ(show(t.log), Lines({"tool_change T7", "in_position"}));
}

// ---------------------------------------------------------------- lost without drop

TEST(ExecutorLink, shouldReportExecutorLostOnceWhenTheCallerDoesNotDrop) {
  Timeline t;
  t.script = {move(StepKind::feed, axis_z, {0.0, 0.0, -80.0}, "slowly down", 1.0)};
  t.start_executor(1, 2);
  EXPECT_EQ(t.take().label, "slowly down");
  t.in.interpreter_idle = true;

  // Turns by hand: the Timeline's changer would drop() on executor_lost.
  std::vector<LinkEvent> all;
  const ExecutorLink::Time start = t.now;
  for (ExecutorLink::Time at = start; at <= start + 10s; at += kTurn) {
    const std::vector<LinkEvent> events = t.link.read(t.in, at);
    all.insert(all.end(), events.begin(), events.end());
    if (!events.empty()) {
      EXPECT_FALSE(t.link.attached()) << "right after the event";
    }
    EXPECT_FALSE(t.link.write(false).step_ready);
  }
  EXPECT_EQ(show(all), Lines({kAborted})) << "once, however long the interpreter stays idle";
  EXPECT_FALSE(t.link.attached());
}

// ---------------------------------------------------------------- active

TEST(ExecutorLink, shouldBeActiveWhileToolChangeIsHighWithNothingElseGoingOn) {
  Timeline t;
  t.changer_idle = false;
  t.turn();
  EXPECT_FALSE(t.link.active());
  t.in.tool_change = true;
  t.turn();
  EXPECT_TRUE(t.link.active()) << "iocontrol waits for tool-changed";
  EXPECT_FALSE(t.link.attached());
  t.changer_idle = true;
  t.turn();
  EXPECT_TRUE(t.out.changed);
  EXPECT_TRUE(t.link.active()) << "until tool-change falls";
  t.in.tool_change = false;
  t.turn();
  EXPECT_FALSE(t.out.changed);
  EXPECT_FALSE(t.link.active());
}

TEST(ExecutorLink, shouldNotBeActiveWhenOnlyAResyncWaitsAfterADropWithTheRequestHigh) {
  Timeline t;
  abort_with_request_high(t);
  // A resync waits for the next run, however long: no reason to hurry.
  for (int second = 0; second < 60; ++second) {
    ASSERT_TRUE(t.out.step_ready && t.out.step.kind == StepKind::resync) << "second " << second;
    ASSERT_FALSE(t.link.active()) << "second " << second;
    t.pass(1s);
  }
}

// ---------------------------------------------------------------- offered only to a run

TEST(ExecutorLink, shouldOfferAStepOnlyToAnAttachedRunWhenAStaleRequestIsHigh) {
  Timeline t;
  t.start_executor(1, 4);
  t.link.drop();  // the program was aborted with the request high
  ASSERT_TRUE(t.in.step_request);
  t.in.interpreter_idle = true;
  const std::size_t from = t.outputs.size();

  t.link.publish(rapid_z(50.0, "safe Z for the load"));
  t.pass(2s);
  for (std::size_t i = from; i < t.outputs.size(); ++i) {
    ASSERT_TRUE(t.outputs[i].step_ready) << "turn " << i;
    EXPECT_EQ(t.outputs[i].step.kind, StepKind::resync) << "turn " << i;
  }
  EXPECT_FALSE(t.link.attached());
  EXPECT_TRUE(t.link.needs_run(t.now)) << "the step waits for a run";
  EXPECT_EQ(show(t.log), Lines({"tool_change T4"}));
}

TEST(ExecutorLink, shouldOfferNoStepToALostRunWhoseRequestIsStillHighBeforeTheCallerDrops) {
  Timeline t;
  t.start_executor(1, 4);  // the request stays high: nothing was published yet
  t.in.interpreter_idle = true;
  std::vector<LinkEvent> events;
  for (ExecutorLink::Time at = t.now; events.empty() && at <= t.now + 1s; at += kTurn) {
    events = t.link.read(t.in, at);
  }
  ASSERT_EQ(show(events), Lines({kAborted}));

  t.link.publish(rapid_z(50.0, "safe Z for the load"));
  EXPECT_FALSE(t.link.write(false).step_ready) << "the request is the lost run's";
  EXPECT_TRUE(t.link.needs_run(t.now));
}

}  // namespace
}  // namespace fatc
