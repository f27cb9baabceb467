// The executor link and the changer joined the way the component joins them,
// against a fake executor that follows nc_files/fixed_atc_probe_execute.ngc.
#pragma once

#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "core/machine/changer.hpp"
#include "core/protocol/executor_link.hpp"
#include "core/dry_run/simulator.hpp"

namespace fatc::test {

using namespace std::chrono_literals;

/// Ports as the component implements them: steps go to the link, the rest is logged.
struct LinkedPorts : Ports {
  ExecutorLink link;
  std::vector<std::string> log;
  std::optional<ExecutorLink::Time> deadline;
  ExecutorLink::Time now{};
  std::vector<std::string> unexpected_events;
  bool chuck_open = false;

  void publish(const Step& step) override {
    log.push_back("  changer: publish " + describe(step));
    link.publish(step);
  }
  void set_chuck_open(bool open) override {
    chuck_open = open;
    log.push_back(std::string("  changer: chuck ") + (open ? "open" : "close"));
  }
  void set_rack_cover_open(bool open) override {
    log.push_back(std::string("  changer: rack cover ") + (open ? "open" : "close"));
  }
  void set_air_blast(bool on) override {
    log.push_back(std::string("  changer: air blast ") + (on ? "on" : "off"));
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
  void ask(const Prompt& prompt) override { log.push_back("  changer: message " + words(prompt)); }
  void save(const ToolState&) override { log.push_back("  changer: save tool state"); }
  void write_found(const std::vector<Found>&, bool) override { log.push_back("  changer: write found"); }
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

inline std::string show(const LinkEvent& e) {
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
    case LinkEvent::Kind::chuck_release:
      return "chuck_release";
    case LinkEvent::Kind::chuck_clamp:
      return "chuck_clamp";
    case LinkEvent::Kind::refused_call:
      return "refused_call: " + e.reason;
  }
  return "?";
}

/// One component poll: read the link, hand its events to the changer (an
/// executor lost aborts it and drops the link, as the component does), run out
/// the timer, write the pins, and let the executor take its servo turn (unless
/// `executor_turn` is false: the cut falls between the write and the executor).
struct LinkRig {
  LinkedPorts& ports;
  Changer& changer;
  LinkInputs& in;
  FakeExecutor& executor;
  LinkInputs before{};
  LinkOutputs last{};

  void turn(bool executor_turn = true) {
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
        case LinkEvent::Kind::probe_result:
          changer.probe_result(e.touched, e.z, e.tripped_before);
          break;
        case LinkEvent::Kind::executor_lost:
          changer.abort(e.reason);
          ports.link.drop();
          break;
        case LinkEvent::Kind::chuck_release:
          changer.chuck(ChuckRequest::Action::release, std::nullopt);
          break;
        case LinkEvent::Kind::chuck_clamp:
          changer.chuck(ChuckRequest::Action::clamp, std::nullopt);
          break;
        case LinkEvent::Kind::refused_call:
          break;  // the component tells the operator; the link fails the run
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
    if (executor_turn) executor.turn(out);
  }

  /// The machine went off or into estop, as the component reacts: the
  /// changer hears of it, and the link forgets the executor's run (LinuxCNC
  /// ended the program with it).
  void machine_not_ready() {
    ports.log.push_back("  component: machine not ready");
    changer.not_ready();
    ports.link.drop();
  }
};

}  // namespace fatc::test
