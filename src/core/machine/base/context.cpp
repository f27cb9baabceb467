#include "context.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "../../formatted.hpp"

namespace fatc {

void Context::publish(const Step& next) {
  // The second layer behind --check: every move, before it goes out.
  // A run of rapids (Step::before) is checked move by move.
  // What the spindle holds now is what every move of the step carries.
  Step published = next;
  published.held = tools.spindle;
  const std::vector<Step> moves = moves_of(published);
  const double held_length = motion.keepout_lengths.of(tools.spindle, tools.lengths).length;
  Point along = motion.position;
  unsigned known_along = motion.known_axes;
  for (const Step& move : moves) {
    const auto problems = motion.check_moves ? check_move(config, along, known_along, move,
                                                          machine.limits, held_length)
                                             : std::vector<std::string>{};
    if (!problems.empty()) {
      raise.unsafe_step("unsafe step not sent: " + describe(move) + ": " + problems.front());
      return;
    }
    if (move.kind == StepKind::rapid || move.kind == StepKind::feed) {
      along = moved_to(along, move);
      known_along |= move.axes;
    }
  }
  if (next.kind == StepKind::rapid || next.kind == StepKind::feed) {
    motion.position = along;
    motion.known_axes = known_along;
  } else if (next.kind == StepKind::probe) {
    // The probe stops wherever it touches, on its axis (the tool setter's: Z).
    motion.known_axes &= ~(next.axes != 0 ? next.axes : static_cast<unsigned>(axis_z));
  } else if (next.kind == StepKind::wait_operator || next.kind == StepKind::fail) {
    motion.known_axes = 0;  // the operator may jog; a failed sequence may stop anywhere
  }
  motion.step = published;
  const int first = motion.sequence_step + 1;
  motion.sequence_step += static_cast<int>(moves.size());
  if (steps.on() && is_motion(next.kind)) {
    for (std::size_t i = 0; i < moves.size(); ++i) {
      steps.rest.emplace_back(first + static_cast<int>(i), moves[i]);
      steps.rest.back().second.blend = 0.0;
    }
    hold_next_move();
    return;
  }
  ports.publish(published);
}

bool Context::hold_next_move() {
  if (steps.rest.empty()) return false;
  auto [number, move] = steps.rest.front();
  steps.rest.pop_front();
  char feed[48];
  std::snprintf(feed, sizeof feed, "%s at F%g to", step_kind_name(move.kind), move.feed);
  const std::string action =
      move.kind == StepKind::rapid ? std::string("rapid to") : std::string(feed);
  stop_before(number, action, move.label, move.target, move.axes,
              [this, move] { ports.publish(move); });
  return true;
}

bool Context::stop_before(int number, std::string action, std::string where, const Point& at,
                          unsigned axes, std::function<void()> go) {
  if (!steps.on()) return false;
  Prompt question;
  question.kind = Prompt::Kind::step;
  question.stop = number;
  question.sequence = tools.in_progress ? tools.in_progress->sequence : std::string("sequence");
  question.action = std::move(action);
  question.waypoint = std::move(where);
  question.at = at;
  question.known_axes = axes;
  const bool first = !steps.holding();
  steps.hold(question, std::move(go));
  if (first) ask_operator(question);
  return true;
}

bool Context::continue_step() {
  if (!steps.holding()) return false;
  steps.release();
  // A step held behind it (the phase after a chuck action) is asked now.
  if (steps.holding()) ask_operator(steps.question());
  return true;
}

std::optional<std::string> Context::rehearse(const std::function<void(Changer&)>& request) const {
  return motion.rehearsal ? motion.rehearsal->why_not(*this, request) : std::nullopt;
}

void Context::walk(plan::Route route) {
  if (route.empty()) throw std::logic_error("a phase with no waypoints");
  route_ = std::move(route);
  route_next_ = 1;
  publish(route_.front());
}

bool Context::next_waypoint() {
  if (route_next_ >= route_.size()) return false;
  // A copy: a refusal faults the machine at once, which drops the route.
  const Step next = route_[route_next_++];
  publish(next);
  return true;
}

void Context::stop_walking() {
  route_.clear();
  route_next_ = 0;
}

void Context::open_chuck() { chuck(true); }

void Context::close_chuck() { chuck(false); }

void Context::chuck(bool open) {
  ++motion.sequence_step;
  const auto go = [this, open] {
    outputs.chuck_open = open;
    // Opening: the blast follows the chuck; closing: it stops first.
    if (open) ports.set_chuck_open(true);
    blow_if_due();
    if (!open) ports.set_chuck_open(false);
  };
  const int pocket = sequence_pocket();
  const std::string where =
      pocket != 0 ? "at pocket " + std::to_string(pocket) : std::string("where the spindle stands");
  if (!stop_before(motion.sequence_step, open ? "open the chuck" : "close the chuck", where,
                   motion.position, motion.known_axes, go)) {
    go();
  }
}

void Context::turn_spindle(double rpm, std::string label) {
  const Step step = spindle_step(rpm, std::move(label), sequence_pocket());
  const auto go = [this, step] {
    outputs.spindle_rpm = step.value;
    publish(step);
  };
  const std::string action = formatted("turn the spindle %s at %.0f rpm",
                                       rpm > 0.0 ? "forward" : "in reverse", std::fabs(rpm));
  if (rpm == 0.0 || !stop_before(motion.sequence_step + 1, action, step.label, motion.position,
                                 motion.known_axes, go)) {
    go();
  }
}

void Context::release_spindle() {
  outputs.spindle_rpm = 0.0;
}

void Context::blow_if_due() {
  // The taper is cleaned only at a pocket: at `loading` the operator's hand
  // is at the spindle.
  const bool due = config.air_blast && outputs.chuck_open && tools.spindle == 0 &&
                   tools.in_progress && tools.in_progress->pocket != 0;
  if (due == blowing) return;
  blowing = due;
  ports.set_air_blast(due);
}

void Context::open_cover() {
  if (!config.rack_cover || outputs.cover_open) return;
  outputs.cover_open = true;
  outputs.cover_settled = false;
  outputs.cover_closing = false;
  ++motion.sequence_step;
  ports.set_rack_cover_open(true);
}

void Context::close_cover() {
  if (!config.rack_cover || !outputs.cover_open) return;
  outputs.cover_open = false;
  outputs.cover_closing = sensors.senses_cover_closed();
  ++motion.sequence_step;
  ports.set_rack_cover_open(false);
}

bool Context::cover_reads_open() const {
  if (!config.rack_cover) return true;
  if (!outputs.cover_open) return false;
  return sensors.senses_cover_opened() ? sensors.cover_reads_opened() : outputs.cover_settled;
}

bool Context::cover_still_closing() const {
  // The cover's own disagreement is one of those disagreements() names.
  return outputs.cover_closing && config.rack_cover && sensors.senses_cover_closed() &&
         !outputs.cover_open && !sensors.cover_reads_closed() && disagreements().size() == 1;
}

void Context::wait(double seconds, std::string what) {
  activity.dwell = std::move(what);
  ++motion.sequence_step;
  steps.then([this, seconds] { ports.start_timer(seconds); });
}

void Context::ask_operator(const Prompt& question) {
  activity.prompt = question;
  ports.ask(question);
}

void Context::begin_sequence(const std::string& sequence) {
  steps.begin();
  // Between sequences a program, MDI or a jog may have moved the machine.
  motion.known_axes = 0;
  motion.sequence_step = 0;
  tools.in_progress = InProgress{sequence, "starting", 0};
  ports.save(tools);
}

void Context::record_progress(const std::string& step, int pocket) {
  if (!tools.in_progress) return;
  tools.in_progress->step = step;
  tools.in_progress->pocket = pocket;
  ports.save(tools);
}

void Context::end_sequence() {
  release_spindle();
  motion.sequence_step = 0;
  if (!tools.in_progress) return;
  tools.in_progress.reset();
  ports.save(tools);
}

std::optional<int> Context::return_pocket(int tool) const {
  return fatc::return_pocket(tools, config, tool);
}

void Context::record_in_spindle(int tool) {
  tools.put_in_spindle(tool);
  ports.save(tools);
  blow_if_due();
}

void Context::record_in_pocket(int tool, int pocket) {
  if (tools.spindle == tool) tools.spindle = 0;
  if (const auto home = tools.home_of(tool); home && *home != pocket) tools.pockets[*home] = {};
  tools.pockets[pocket] = {tool, true};
  ports.save(tools);
  blow_if_due();
}

void Context::record_out_of_machine(int tool) {
  if (tools.spindle == tool) tools.spindle = 0;
  if (const auto home = tools.home_of(tool)) tools.pockets[*home] = {};
  ports.save(tools);
}

void Context::record_length(int tool, double length) {
  tools.lengths[tool] = length;
  activity.last_length = length;
  ports.save(tools);
}

std::string Context::whereabouts() const {
  std::string text = tools.spindle == 0
                         ? std::string("the spindle is empty")
                         : "tool " + std::to_string(tools.spindle) + " is in the spindle";
  if (tools.uncertain) text += " (last known; not certain)";
  if (tools.uncertain && tools.in_progress) {
    text += "; cut off during " + tools.in_progress->sequence + ", " + tools.in_progress->step;
    if (const int pocket = tools.in_progress->pocket; pocket != 0) {
      const int tool = tools.tool_of(pocket);
      text += "; pocket " + std::to_string(pocket) + " may or may not hold " +
              (tool != 0 ? "tool " + std::to_string(tool) : std::string("its tool"));
    }
  }
  return text;
}

std::vector<std::string> Context::disagreements() const {
  return sensors.disagreements(tools, outputs.chuck_open, outputs.cover_open);
}

void Context::await_sensor(double seconds, std::string what) {
  activity.dwell = std::move(what);
  ports.start_timer(seconds);
}

void Context::fail_check(std::string reason, bool uncertain) {
  raise.check_failed(CheckFailed{std::move(reason), uncertain});
}

}  // namespace fatc
