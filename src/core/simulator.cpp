#include "simulator.hpp"

#include <cstdio>

namespace fatc {

std::string describe(const Record& record) {
  char buffer[96];
  switch (record.kind) {
    case Record::Kind::step:
      return describe(record.step);
    case Record::Kind::chuck:
      return record.chuck_open ? "chuck      open" : "chuck      close";
    case Record::Kind::dwell:
      std::snprintf(buffer, sizeof buffer, "dwell      %.2f s", record.seconds);
      return buffer;
    case Record::Kind::message:
      return "message    " + record.text;
    case Record::Kind::save:
      return "save       tool state";
  }
  return "";
}

void Simulator::publish(const Step& step) {
  Record record;
  record.step = step;
  records.push_back(record);
  // done, fail and wait_operator end an executor run: nothing to finish. A
  // refused M6's fail goes to that M6's executor, not to the one running.
  if (is_motion(step.kind) || step.kind == StepKind::set_tool_length ||
      step.kind == StepKind::set_spindle_tool) {
    pending = step;
  }
}

void Simulator::set_chuck_open(bool open) {
  Record record;
  record.kind = Record::Kind::chuck;
  record.chuck_open = open;
  records.push_back(record);
  chuck_open = open;
}

void Simulator::start_timer(double seconds) {
  Record record;
  record.kind = Record::Kind::dwell;
  record.seconds = seconds;
  records.push_back(record);
  timer_armed = true;
}

void Simulator::cancel_timer() { timer_armed = false; }

void Simulator::tell(MessageKind kind, const std::string& text) {
  Record record;
  record.kind = Record::Kind::message;
  record.message_kind = kind;
  record.text = text;
  records.push_back(record);
}

void Simulator::save(const ToolState& state) {
  Record record;
  record.kind = Record::Kind::save;
  record.saved = state;
  records.push_back(record);
  ++saves;
}

void Simulator::unexpected(const std::string& state, const std::string& event) {
  unexpected_events.push_back(event + " in " + state);
}

int Simulator::run(Changer& changer, int limit) {
  int fed = 0;
  for (; fed < limit; ++fed) {
    const Awaiting awaiting = changer.status().awaiting;
    if (awaiting == Awaiting::timer && timer_armed) {
      timer_armed = false;
      changer.timer_elapsed();
    } else if (awaiting == Awaiting::probe && pending && pending->kind == StepKind::probe) {
      const Step probe = *pending;
      pending.reset();
      const bool touched = sensor_z && *sensor_z >= probe.target.z;
      changer.probe_result(touched, touched ? *sensor_z : probe.target.z);
    } else if (awaiting == Awaiting::motion && pending) {
      const bool moved = is_motion(pending->kind);
      pending.reset();
      moved ? changer.in_position() : changer.command_done();
    } else {
      break;
    }
  }
  return fed;
}

std::vector<Step> Simulator::steps() const {
  std::vector<Step> result;
  for (const auto& record : records) {
    if (record.kind == Record::Kind::step) result.push_back(record.step);
  }
  return result;
}

std::vector<Step> Simulator::motion_steps() const {
  std::vector<Step> result;
  for (const auto& step : steps()) {
    if (is_motion(step.kind)) result.push_back(step);
  }
  return result;
}

std::vector<std::string> Simulator::messages(MessageKind kind) const {
  std::vector<std::string> result;
  for (const auto& record : records) {
    if (record.kind == Record::Kind::message && record.message_kind == kind) {
      result.push_back(record.text);
    }
  }
  return result;
}

}  // namespace fatc

namespace fatc {
namespace {

ToolState with_in_spindle(const Config& config, int tool) {
  ToolState tools = ToolState::fresh(config);
  tools.spindle = tool;
  tools.in_pocket.erase(tool);
  return tools;
}

/// Runs an operator flow, pressing Continue at every wait.
void run_with_operator(Simulator& sim, Changer& changer) {
  for (int presses = 0; presses < 10; ++presses) {
    sim.run(changer);
    if (changer.status().awaiting != Awaiting::operator_choice) return;
    changer.operator_continue();
  }
}

}  // namespace

Simulator plan_change(const Config& config, int from, int to, double sensor_z) {
  Simulator sim;
  sim.sensor_z = sensor_z;
  Changer changer(config, sim, with_in_spindle(config, from));
  changer.plan_only();
  changer.ready();
  changer.tool_change(to);
  run_with_operator(sim, changer);
  return sim;
}

Simulator plan_load(const Config& config, int tool, int from, double sensor_z) {
  Simulator sim;
  sim.sensor_z = sensor_z;
  ToolState tools = with_in_spindle(config, from);
  if (from != tool) tools.in_pocket.erase(tool);
  Changer changer(config, sim, tools);
  changer.plan_only();
  changer.ready();
  changer.load(tool);
  run_with_operator(sim, changer);
  return sim;
}

Simulator plan_unload(const Config& config, int tool, int from) {
  Simulator sim;
  Changer changer(config, sim, with_in_spindle(config, from));
  changer.plan_only();
  changer.ready();
  changer.unload(tool);
  run_with_operator(sim, changer);
  return sim;
}

}  // namespace fatc
