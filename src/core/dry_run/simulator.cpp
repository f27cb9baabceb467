#include "simulator.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>

#include "../formatted.hpp"
#include "../rack/geometry.hpp"

namespace fatc {

std::string describe(const Record& record) {
  switch (record.kind) {
    case Record::Kind::step:
      return describe(record.step);
    case Record::Kind::chuck:
      return record.chuck_open ? "chuck      open" : "chuck      close";
    case Record::Kind::cover:
      return record.on ? "rack cover open" : "rack cover close";
    case Record::Kind::blast:
      return record.on ? "air blast  on" : "air blast  off";
    case Record::Kind::dwell:
      return formatted("dwell      %.2f s", record.seconds);
    case Record::Kind::message:
      return "message    " + record.text;
    case Record::Kind::save:
      return "save       tool state";
  }
  return "";
}

void Simulator::publish(const Step& step) {
  // A run of rapids is recorded move by move, as --plan prints them.
  for (const Step& move : moves_of(step)) {
    Record record;
    record.step = move;
    records.push_back(record);
  }
  longest_wait = std::max(longest_wait, clock - waiting_since_);
  // done, fail and wait_operator end an executor run: nothing to finish. A
  // refused M6's fail goes to that M6's executor, not to the one running.
  if (is_motion(step.kind) || step.kind == StepKind::set_tool_length ||
      step.kind == StepKind::set_spindle_tool || step.kind == StepKind::spindle) {
    pending = step;
  }
}

void Simulator::record_output(Record::Kind kind, bool on) {
  Record record;
  record.kind = kind;
  record.chuck_open = kind == Record::Kind::chuck && on;
  record.on = on;
  records.push_back(record);
}

void Simulator::set_chuck_open(bool open) {
  record_output(Record::Kind::chuck, open);
  chuck_open = open;
  if (!rack.modelled || rack.drawbar_jammed || rack.drawbar_released == open) return;
  rack.drawbar_released = open;
  // The sensors follow the valve at once: the changer hears of it right after this event.
  struct ReportAfter {
    Simulator& sim;
    ~ReportAfter() {
      if (sim.changer_ && !sim.answers_late) sim.report_sensors(*sim.changer_);
    }
  } report{*this};
  const int pocket = rack.pocket_at(*config_);
  if (open && rack.spindle != 0 && !rack.tool_sticks) {
    // Into the pocket it is at, or out of the machine (it drops).
    if (pocket != 0 && rack.pockets[pocket] == 0) rack.pockets[pocket] = rack.spindle;
    rack.spindle = 0;
  } else if (!open && rack.spindle == 0 && pocket != 0 && rack.pockets[pocket] != 0) {
    if (rack.grips_failing > 0) {
      --rack.grips_failing;
    } else {
      rack.spindle = rack.pockets[pocket];
      rack.pockets[pocket] = 0;
    }
  }
}

void Simulator::set_rack_cover_open(bool open) {
  record_output(Record::Kind::cover, open);
  cover_open = open;
  if (!rack.modelled || rack.cover_jammed || rack.cover_open == open) return;
  rack.cover_open = open;
  if (changer_ && !answers_late && !rack.cover_slow) report_sensors(*changer_);
}

void Simulator::set_air_blast(bool on) {
  record_output(Record::Kind::blast, on);
  blowing = on;
}

void Simulator::model_rack(const Config& config, const ToolState& tools) {
  config_ = &config;
  rack = Rack{};
  rack.modelled = config.sensors.any();
  rack.spindle = tools.spindle;
  rack.zones = config.chuck.recognition;
  // Unmodelled, nothing reads the pockets: a rack of 200 is not copied at each plan.
  for (const auto& entry : config.pockets) {
    if (!rack.modelled) break;
    rack.pockets[entry.first] = tools.holds(entry.first) ? tools.tool_of(entry.first) : 0;
  }
  reported_.reset();
}

SensorReadings Simulator::readings() const {
  SensorReadings r;
  for (const SensorDeclaration& sensor : kSensors) {
    r.set(sensor.sensor, rack.holds(sensor.watches) == sensor.on_when);
  }
  for (const auto& [pocket, tool] : rack.pockets) r.pockets[pocket] = tool != 0;
  return r;
}

void Simulator::show(Fact fact) {
  const SensorReadings now = readings();
  for (const SensorDeclaration& sensor : kSensors) {
    if (sensor.watches == fact) shown_.set(sensor.sensor, now.reads(sensor.sensor));
  }
}

bool Simulator::report_sensors(Changer& changer) {
  if (!rack.modelled) return false;
  changer_ = &changer;
  const SensorReadings now = answers_late ? shown_ : readings();
  if (reported_ && *reported_ == now) return false;
  reported_ = now;
  changer.sensors(now);
  return true;
}

void Simulator::operator_obeys(const Changer& changer) {
  if (!rack.modelled || !asked || !changer.status().awaits_operator()) return;
  if (asked->kind == Prompt::Kind::insert_tool) rack.spindle = asked->tool;
  if (asked->kind == Prompt::Kind::remove_tool) rack.spindle = 0;
}

void Simulator::start_timer(double seconds) {
  Record record;
  record.kind = Record::Kind::dwell;
  record.seconds = seconds;
  records.push_back(record);
  timer_armed = true;
  armed_seconds_ = seconds;
  ++timers_started_;
}

void Simulator::cancel_timer() { timer_armed = false; }

void Simulator::tell(MessageKind kind, const std::string& text) {
  Record record;
  record.kind = Record::Kind::message;
  record.message_kind = kind;
  record.text = text;
  records.push_back(record);
}

void Simulator::ask(const Prompt& prompt) {
  asked = prompt;
  tell(MessageKind::prompt, words(prompt));
}

void Simulator::write_found(const std::vector<Found>& found, bool datum) {
  written.insert(written.end(), found.begin(), found.end());
  written_datum = datum;
}

void Simulator::save(const ToolState& state) {
  Record record;
  record.kind = Record::Kind::save;
  if (keeps_saved_states) record.saved = state;
  records.push_back(record);
  ++saves;
}

void Simulator::unexpected(const std::string& state, const std::string& event) {
  unexpected_events.push_back(event + " in " + state);
}

void Simulator::answer_late(Changer& changer) {
  answers_late = true;
  rack.spindle_still = false;
  spindle_turning_ = true;
  shown_ = readings();
  changer.spindle_stopped(false);
}

void Simulator::run_out_timer(Changer& changer, bool awaits_sensor) {
  clock += armed_seconds_;
  if (answers_late && awaits_sensor) {
    const int started = timers_started_;
    rack.air = true;
    rack.spindle_still = true;
    shown_ = readings();
    report_sensors(changer);
    if (spindle_turning_) {
      spindle_turning_ = false;
      changer.spindle_stopped(true);
    }
    // What it waited for came: the wait ended, or a new one began.
    if (!timer_armed || timers_started_ != started) return;
  }
  // A sensor that has not come by now never will: its time runs out.
  timer_armed = false;
  changer.timer_elapsed();
}

int Simulator::run(Changer& changer, int limit) {
  int fed = 0;
  for (; fed < limit; ++fed) {
    if (!answers_late && report_sensors(changer)) continue;
    const Awaiting awaiting = changer.status().awaiting;
    // A collet-nut changer waits for the spindle it turns on a timer too,
    // where no sensor says it got there (its ramps).
    const bool screws_nuts = config_ && config_->screws_nuts();
    const bool waits_on_time =
        awaiting == Awaiting::timer || awaiting == Awaiting::sensor ||
        (awaiting == Awaiting::spindle && (answers_late || screws_nuts));
    if (waits_on_time && timer_armed) {
      run_out_timer(changer, awaiting != Awaiting::timer);
    } else if (awaiting == Awaiting::probe && pending && pending->kind == StepKind::probe) {
      const Step probe = *pending;
      pending.reset();
      waiting_since_ = clock;
      if (touches) {
        const auto at = touches(probe);
        // The probe stops where it touched, or at its limit.
        const double limit = coordinate(probe.target, probe.axes);
        coordinate(rack.at, probe.axes) = at.value_or(limit);
        changer.probe_result(at.has_value(), at.value_or(limit));
        continue;
      }
      const bool touched = sensor_z && *sensor_z >= probe.target.z;
      changer.probe_result(touched, touched ? *sensor_z : probe.target.z);
    } else if (awaiting == Awaiting::motion && pending) {
      const bool moved = is_motion(pending->kind);
      if (moved) {
        // A run of rapids ends where its last move does, on every axis its moves moved.
        for (const Step& move : moves_of(*pending)) {
          rack.at = moved_to(rack.at, move);
          rack.known_axes |= move.axes;
          if (rack.modelled) rack.screw(*config_);
        }
      } else if (pending->kind == StepKind::spindle) {
        rack.spindle_rpm = pending->value;
        rack.screwed = false;
        rack.spindle_still = pending->value == 0.0;
        changer.spindle_stopped(rack.spindle_still);
        // Where a sensor says when the spindle got there, the changer waits
        // on it, not on a timer: the plan counts the ramp the spindle takes,
        // and its sensors say so before the executor's news. Answering late,
        // the wait's own timer is the worst case.
        const Sensor says = rack.spindle_still ? Sensor::zero_speed : Sensor::at_speed;
        if (!answers_late && config_ && config_->screws_nuts() && config_->sensors.wired(says)) {
          Record ramp;
          ramp.kind = Record::Kind::dwell;
          ramp.seconds = config_->chuck.spindle_ramp_seconds;
          records.push_back(ramp);
          clock += ramp.seconds;
        }
        if (!answers_late) report_sensors(changer);
      }
      pending.reset();
      waiting_since_ = clock;
      if (answers_late && moved) {
        // The air dips during the move: the chuck waits for it before it opens.
        rack.air = false;
        show(Fact::air);
        report_sensors(changer);
      }
      // The component reads its sensors before the executor's news in a poll:
      // what the spindle's arrival changed (the recognition beam) is known then.
      if (moved && !answers_late) report_sensors(changer);
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

ToolState with_in_spindle(const Config& config, int tool) {
  ToolState tools = ToolState::fresh(config);
  tools.put_in_spindle(tool);
  return tools;
}

namespace {

/// Runs an operator flow, pressing Continue at every wait.
void run_with_operator(Simulator& sim, Changer& changer) {
  for (int presses = 0; presses < 10; ++presses) {
    sim.run(changer);
    if (changer.status().awaiting != Awaiting::operator_choice) return;
    sim.operator_obeys(changer);
    sim.report_sensors(changer);
    changer.operator_continue();
  }
}

/// How a plan is run: where the sensor touches, and the worst case's faults.
struct Planning {
  std::optional<double> sensor_z;
  bool late = false;      ///< Simulator::answer_late
  int grips_failing = 0;  ///< Rack::grips_failing
  bool runs_down = false;  ///< the spindle turns at the request, stands once awaited
  bool saved_states = true;  ///< Simulator::keeps_saved_states
};

/// The records of `request` made of a ready changer with `tools`, the
/// spindle standing at `at` on the axes `known`.
Simulator planned(const Config& config, const ToolState& tools, const Planning& planning,
                  const std::function<void(Changer&)>& request, const Point& at = {},
                  unsigned known = 0) {
  Simulator sim;
  sim.sensor_z = planning.sensor_z;
  sim.keeps_saved_states = planning.saved_states;
  sim.model_rack(config, tools);
  sim.rack.grips_failing = planning.grips_failing;
  Changer changer(config, sim, tools);
  changer.plan_only();
  changer.start_at(at, known);
  sim.report_sensors(changer);
  changer.ready();
  if (planning.late) sim.answer_late(changer);
  if (planning.runs_down) changer.spindle_stopped(false);
  request(changer);
  if (planning.runs_down) {
    sim.run(changer);
    // The wait for the spindle is the run-down's own, no dwell of the change.
    if (!sim.records.empty() && sim.records.back().kind == Record::Kind::dwell) {
      sim.records.pop_back();
    }
    sim.spindle_stood = sim.records.size();
    changer.spindle_stopped(true);
  }
  run_with_operator(sim, changer);
  return sim;
}

/// `then` made of a changer whose change to `to` (from `tools`) has just
/// ended, answering late: the rack cover it closed reads closed only when
/// its time is up, so `then` waits for it before its flow starts.
Simulator planned_right_after(const Config& config, const ToolState& tools, int to,
                              const std::function<void(Changer&)>& then) {
  Simulator sim;
  sim.sensor_z = config.probe_limit.z;
  sim.model_rack(config, tools);
  Changer changer(config, sim, tools);
  changer.plan_only();
  sim.report_sensors(changer);
  changer.ready();
  sim.answer_late(changer);
  changer.tool_change(to);
  while (changer.status().busy() && sim.run(changer, 1) == 1) {
  }
  then(changer);
  run_with_operator(sim, changer);
  return sim;
}

}  // namespace

Simulator plan_change(const Config& config, int from, int to, double sensor_z) {
  return plan_change(config, with_in_spindle(config, from), to, sensor_z);
}

Simulator plan_change(const Config& config, const ToolState& tools, int to, double sensor_z) {
  return planned(config, tools, {sensor_z}, [to](Changer& c) { c.tool_change(to); });
}

Simulator plan_change_timed(const Config& config, const ToolState& tools, int to,
                            double sensor_z) {
  Planning timed{sensor_z};
  timed.saved_states = false;
  return planned(config, tools, timed, [to](Changer& c) { c.tool_change(to); });
}

Simulator plan_change_running_down(const Config& config, const ToolState& tools, int to,
                                   double sensor_z) {
  Planning running_down{sensor_z};
  running_down.runs_down = true;
  return planned(config, tools, running_down, [to](Changer& c) { c.tool_change(to); });
}

Simulator plan_load(const Config& config, int tool, int from, double sensor_z) {
  ToolState tools = with_in_spindle(config, from);
  // The tool to load is out of the machine: its pocket is free.
  if (const auto home = tools.home_of(tool); home && from != tool) tools.pockets[*home] = {};
  return plan_load(config, tools, tool, 0, sensor_z);
}

Simulator plan_load(const Config& config, const ToolState& tools, int tool, int pocket,
                    double sensor_z) {
  return planned(config, tools, {sensor_z}, [=](Changer& c) { c.load(tool, pocket); });
}

Simulator plan_unload(const Config& config, int tool, int from) {
  return plan_unload(config, with_in_spindle(config, from), tool);
}

Simulator plan_unload(const Config& config, const ToolState& tools, int tool) {
  return planned(config, tools, {}, [tool](Changer& c) { c.unload(tool); });
}

Simulator plan_from(const Config& config, const ToolState& tools, const Point& at, unsigned known,
                    const std::function<void(Changer&)>& request) {
  return planned(config, tools, {config.probe_limit.z}, request, at, known);
}

double longest_executor_wait(const Config& config) {
  if (config.pockets.empty()) return 0.0;
  const ToolState full = ToolState::fresh(config);
  const int first = full.tool_of(config.pockets.begin()->first);
  const int second =
      config.pockets.size() > 1 ? full.tool_of(std::next(config.pockets.begin())->first) : 0;
  const double z = config.probe_limit.z;
  double longest = 0.0;
  const auto late = [&](const ToolState& tools, int grips_failing,
                        const std::function<void(Changer&)>& request) {
    const Simulator sim = planned(config, tools, {z, true, grips_failing}, request);
    longest = std::max(longest, sim.longest_wait);
  };
  for (const int grips_failing : {0, 1}) {
    late(with_in_spindle(config, first), grips_failing, [=](Changer& c) { c.tool_change(second); });
    late(full, grips_failing, [=](Changer& c) { c.tool_change(first); });
  }
  ToolState free = with_in_spindle(config, 0);
  free.pockets[config.pockets.begin()->first] = {};
  late(free, 0, [=](Changer& c) { c.load(first, 0); });
  late(with_in_spindle(config, first), 0, [=](Changer& c) { c.unload(first); });
  if (Sensors(config.sensors).senses_cover_closed()) {
    // A program's next M6 waits for the cover the last one closed.
    const Simulator sim = planned_right_after(config, with_in_spindle(config, first), second,
                                              [=](Changer& c) { c.tool_change(first); });
    longest = std::max(longest, sim.longest_wait);
  }
  return longest;
}

}  // namespace fatc
