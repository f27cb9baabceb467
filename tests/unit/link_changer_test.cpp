// The executor link and the changer together, the way the component joins
// them, against a fake executor that follows nc_files/fixed_atc_probe_execute.ngc.
// Prints the timeline of one M6 (pins in, events, what the changer does, pins
// out) so that the handshake can be read as it happens.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "core/changer.hpp"
#include "core/executor_link.hpp"
#include "core/simulator.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using namespace std::chrono_literals;

/// Ports as the component implements them: steps go to the link, the rest is logged.
struct LinkedPorts : Ports {
  ExecutorLink link;
  std::vector<std::string> log;
  std::optional<ExecutorLink::Time> deadline;
  ExecutorLink::Time now{};
  std::vector<std::string> unexpected_events;

  void publish(const Step& step) override {
    log.push_back("  changer: publish " + describe(step));
    link.publish(step);
  }
  void set_chuck_open(bool open) override {
    log.push_back(std::string("  changer: chuck ") + (open ? "open" : "close"));
  }
  void start_timer(double seconds) override {
    char text[48];
    std::snprintf(text, sizeof text, "  changer: timer %.2f s", seconds);
    log.push_back(text);
    deadline = now + std::chrono::duration_cast<ExecutorLink::Time::duration>(
                         std::chrono::duration<double>(seconds));
  }
  void cancel_timer() override { deadline.reset(); }
  void tell(MessageKind, const std::string& text) override {
    log.push_back("  changer: message " + text);
  }
  void save(const ToolState&) override { log.push_back("  changer: save tool state"); }
  void unexpected(const std::string& state, const std::string& event) override {
    unexpected_events.push_back(event + " in " + state);
  }
};

/// The NGC executor's side of the handshake; every step is performed at once.
struct FakeExecutor {
  explicit FakeExecutor(LinkInputs& inputs) : in(inputs) {}
  LinkInputs& in;
  std::optional<Step> taken;
  bool running = false;
  std::vector<Step> performed;

  void call(ExecutorCall how) {
    in.call = static_cast<int>(how);  // M68 before the first M64
    in.step_request = true;
    running = true;
  }
  /// One servo turn after the component wrote `out`.
  void turn(const LinkOutputs& out) {
    if (!running) return;
    if (in.step_request && out.step_ready) {
      taken = out.step;  // read the step pins, then M65
      in.step_request = false;
    } else if (!in.step_request && !out.step_ready && taken) {
      performed.push_back(*taken);
      const StepKind kind = taken->kind;
      taken.reset();
      if (kind == StepKind::done || kind == StepKind::fail || kind == StepKind::wait_operator) {
        running = false;  // the executor returns
      } else {
        in.step_request = true;  // M64: the step is done, next please
      }
    }
  }
};

std::string show(const LinkEvent& e) {
  switch (e.kind) {
    case LinkEvent::Kind::tool_change:
      return "tool_change T" + std::to_string(e.tool);
    case LinkEvent::Kind::in_position:
      return "in_position";
    case LinkEvent::Kind::command_done:
      return "command_done";
    case LinkEvent::Kind::probe_result:
      return e.touched ? "probe touched" : "probe missed";
    case LinkEvent::Kind::executor_lost:
      return "executor_lost: " + e.reason;
  }
  return "?";
}

TEST(LinkWithChanger, shouldPerformThePlannedStepsInOrderAndAnswerIocontrolWhenOneM6Runs) {
  const Config config = test::valid_config();
  LinkedPorts ports;
  Changer changer(config, ports, ToolState::fresh(config));
  changer.ready();
  changer.spindle_stopped(true);
  LinkInputs in;
  in.interpreter_idle = false;  // a program runs
  in.number = 2;                // T2 prepared
  FakeExecutor executor(in);
  executor.call(ExecutorCall::tool_change);

  LinkInputs before;
  LinkOutputs last;
  for (int turn = 0; turn < 2000 && executor.running; ++turn) {
    ports.now += 1ms;
    char stamp[32];
    std::snprintf(stamp, sizeof stamp, "t=%7.3f s",
                  std::chrono::duration<double>(ports.now.time_since_epoch()).count());
    if (in.step_request != before.step_request || in.call != before.call) {
      ports.log.push_back(std::string(stamp) + " in:  step-request " +
                          std::to_string(in.step_request) + ", executor-call " +
                          std::to_string(in.call));
    }
    before = in;
    for (const LinkEvent& e : ports.link.read(in, ports.now)) {
      ports.log.push_back("  event: " + show(e));
      switch (e.kind) {
        case LinkEvent::Kind::tool_change:
          changer.tool_change(e.tool);
          break;
        case LinkEvent::Kind::in_position:
          changer.in_position();
          break;
        case LinkEvent::Kind::command_done:
          changer.command_done();
          break;
        default:
          FAIL() << show(e);
      }
    }
    if (ports.deadline && ports.now >= *ports.deadline) {
      ports.deadline.reset();
      ports.log.push_back(std::string(stamp) + " timer elapsed");
      changer.timer_elapsed();
    }
    const LinkOutputs out = ports.link.write(changer.status().phase == Phase::idle);
    if (out.step_ready != last.step_ready) {
      ports.log.push_back(std::string(stamp) + " out: step-ready " +
                          std::to_string(out.step_ready) +
                          (out.step_ready ? ", step " + describe(out.step) : ""));
    }
    last = out;
    executor.turn(out);
  }

  // The builtin M6 at the end of the remap: iocontrol's level handshake.
  in.tool_change = true;
  ports.link.read(in, ports.now);
  const bool changed = ports.link.write(changer.status().phase == Phase::idle).changed;
  ports.log.push_back("in: tool-change 1 -> out: changed " + std::to_string(changed));
  in.tool_change = false;
  ports.link.read(in, ports.now);
  const bool dropped = !ports.link.write(true).changed;
  ports.log.push_back("in: tool-change 0 -> out: changed " + std::to_string(!dropped));

  for (const auto& line : ports.log) std::cout << line << "\n";

  std::vector<std::string> planned;
  for (const Step& step : plan_change(config, 0, 2, 0.0).steps()) planned.push_back(describe(step));
  std::vector<std::string> performed;
  for (const Step& step : executor.performed) performed.push_back(describe(step));
  EXPECT_EQ(performed, planned);
  EXPECT_FALSE(executor.running);
  EXPECT_EQ(changer.tools().spindle, 2);
  EXPECT_TRUE(changed);
  EXPECT_TRUE(dropped);
  EXPECT_TRUE(ports.unexpected_events.empty());
}

}  // namespace
}  // namespace fatc
