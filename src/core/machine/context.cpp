#include "context.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

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
    const auto problems = motion.check_moves
                              ? check_move(config, along, known_along, move, machine.limits, held_length)
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
    motion.known_axes &= ~static_cast<unsigned>(axis_z);  // the probe stops wherever it touches
  } else if (next.kind == StepKind::wait_operator || next.kind == StepKind::fail) {
    motion.known_axes = 0;  // the operator may jog; a failed sequence may stop anywhere
  }
  motion.step = published;
  motion.sequence_step += static_cast<int>(moves.size());
  ports.publish(published);
}

std::optional<std::string> Context::rehearse(
    const std::function<void(Changer&)>& request) const {
  return motion.rehearsal ? motion.rehearsal->why_not(*this, request) : std::nullopt;
}

void Context::walk(plan::Route route) {
  if (route.empty()) throw std::logic_error("a phase with no waypoints");
  route_ = plan::blended(
      config, plan::from_where_it_stands(config, std::move(route), motion.position, motion.known_axes),
      motion.position, motion.known_axes);
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

void Context::open_chuck() {
  ++motion.sequence_step;
  outputs.chuck_open = true;
  ports.set_chuck_open(true);
  blow_if_due();
}

void Context::close_chuck() {
  ++motion.sequence_step;
  outputs.chuck_open = false;
  blow_if_due();
  ports.set_chuck_open(false);
}

void Context::blow_if_due() {
  // The taper is cleaned only at a pocket: at `loading` the operator's hand
  // is at the spindle.
  const bool due = config.air_blast && outputs.chuck_open && tools.spindle == 0 && tools.in_progress &&
                   tools.in_progress->pocket != 0;
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
  outputs.cover_closing = config.rack_cover->closed_sensor;
  ++motion.sequence_step;
  ports.set_rack_cover_open(false);
}

bool Context::cover_reads_open() const {
  if (!config.rack_cover) return true;
  if (!outputs.cover_open) return false;
  return config.rack_cover->opened_sensor ? sensors.rack_cover_opened : outputs.cover_settled;
}

bool Context::cover_still_closing() const {
  // The cover's own disagreement is one of those disagreements() names.
  return outputs.cover_closing && config.rack_cover && config.rack_cover->closed_sensor && !outputs.cover_open &&
         !sensors.rack_cover_closed && disagreements().size() == 1;
}

void Context::wait(double seconds, std::string what) {
  activity.dwell = std::move(what);
  ++motion.sequence_step;
  ports.start_timer(seconds);
}

void Context::ask_operator(const Prompt& question) {
  activity.prompt = question;
  ports.ask(question);
}

void Context::begin_sequence(const std::string& sequence) {
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

bool Context::spindle_at_standstill() const {
  return machine.spindle_stopped && (!config.sensors.zero_speed || sensors.zero_speed);
}

bool Context::air_ok() const { return !config.sensors.air_pressure || sensors.air_pressure_ok; }

bool Context::drawbar_reads_open() const {
  return (!config.sensors.drawbar_open || sensors.drawbar_open) &&
         (!config.sensors.drawbar_closed || !sensors.drawbar_closed);
}

bool Context::drawbar_reads_closed() const {
  return (!config.sensors.drawbar_closed || sensors.drawbar_closed) &&
         (!config.sensors.drawbar_open || !sensors.drawbar_open);
}

bool Context::spindle_reads(bool holds) const {
  return !config.sensors.tool_present || sensors.tool_present == holds;
}

bool Context::pocket_reads(int pocket, bool occupied) const {
  return !config.sensors.pocket(pocket) || sensors.occupied(pocket) == occupied;
}

std::vector<std::string> Context::disagreements() const {
  // A released chuck holds nothing for certain: the operator may be taking
  // the tool out. tool-present is compared again once it is clamped.
  SensorConfig compared = config.sensors;
  if (outputs.chuck_open) compared.tool_present = false;
  auto found = sensor_disagreements(compared, sensors, tools);
  if (config.rack_cover && config.rack_cover->closed_sensor && !outputs.cover_open &&
      !sensors.rack_cover_closed) {
    found.push_back("the rack cover is not closed (rack-cover-closed off)");
  }
  return found;
}

std::string Context::drawbar_words() const {
  std::string words;
  if (config.sensors.drawbar_open)
    words = std::string("drawbar-open ") + (sensors.drawbar_open ? "on" : "off");
  if (config.sensors.drawbar_closed) {
    if (!words.empty()) words += ", ";
    words += std::string("drawbar-closed ") + (sensors.drawbar_closed ? "on" : "off");
  }
  return words;
}

void Context::await_sensor(double seconds, std::string what) {
  activity.dwell = std::move(what);
  ports.start_timer(seconds);
}

void Context::fail_check(std::string reason, bool uncertain) {
  raise.check_failed(CheckFailed{std::move(reason), uncertain});
}

namespace {

std::string tool_name(int tool) { return "tool " + std::to_string(tool); }

/// The tool in the spindle must be able to go home before anything else; a
/// manual tool only can when M6 may hand it out at `loading` (`manual_tools`).
std::optional<std::string> why_spindle_cannot_be_emptied(const Context& ctx, bool hand_out) {
  const int held = ctx.tools.spindle;
  if (held == 0) return std::nullopt;
  const auto pocket = ctx.return_pocket(held);
  if (!pocket) {
    if (hand_out) return std::nullopt;
    return tool_name(held) + " in the spindle has no pocket to go to; unload it first";
  }
  if (ctx.tools.holds(*pocket)) {
    return "pocket " + std::to_string(*pocket) + " is recorded full, yet " + tool_name(held) +
           " that belongs in it is in the spindle; check the rack";
  }
  return std::nullopt;
}

/// Every sequence opens the chuck: no air, no start (the legs check again
/// before each opening).
std::optional<std::string> why_no_air(const Context& ctx) {
  if (ctx.air_ok()) return std::nullopt;
  return std::string("air pressure is low (air-pressure-ok off): the chuck cannot open");
}

std::optional<std::string> why_not_ready(const Context& ctx) {
  if (!ctx.machine.ready) return std::string("the machine is not on and homed, or is in estop");
  if (ctx.tools.uncertain) return "the spindle contents are uncertain: " + ctx.whereabouts();
  return std::nullopt;
}

std::optional<std::string> why_not_busy(const Context& ctx) {
  if (auto not_ready = why_not_ready(ctx)) return not_ready;
  return why_chuck_held_open(ctx);
}

/// "X20.000 Y150.000 Z-10.000 mm", machine coordinates.
std::string position_words(const Config& config, const Point& at) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "X%.3f Y%.3f Z%.3f %s", at.x, at.y, at.z,
                units_name(config.units));
  return buffer;
}

}  // namespace

std::optional<std::string> why_not_change(const Context& ctx, int tool) {
  if (tool < 0) return "T" + std::to_string(tool) + " is not a tool number";
  if (auto busy = why_not_busy(ctx)) return busy;
  if (tool == ctx.tools.spindle) return std::nullopt;
  if (auto air = why_no_air(ctx)) return air;
  const auto home = ctx.tools.home_of(tool);
  if (tool != 0 && !home && !ctx.config.manual_tools) {
    return tool_name(tool) + " is in no pocket of the rack (and manual_tools is off)";
  }
  if (tool != 0 && home && !ctx.tools.holds(*home)) {
    return tool_name(tool) + " belongs in pocket " + std::to_string(*home) +
           " but is not in it; load it first";
  }
  return why_spindle_cannot_be_emptied(ctx, ctx.config.manual_tools);
}

LoadPocket choose_load_pocket(const Context& ctx, int tool, int asked) {
  // The pocket the spindle's tool goes back to first is not free for this one.
  const int held = ctx.tools.spindle;
  const int taken = held != 0 && held != tool ? ctx.return_pocket(held).value_or(0) : 0;
  auto free_for_tool = [&](int pocket) {
    const int owner = ctx.tools.tool_of(pocket);
    return pocket != taken && (owner == 0 || owner == tool);
  };
  std::vector<int> free;
  for (const auto& [number, pocket] : ctx.config.pockets) {
    if (free_for_tool(number)) free.push_back(number);
  }
  const std::string free_words =
      free.empty() ? "every pocket holds a tool; unload one first" : "free: " + pocket_list(free);
  if (asked != 0) {
    if (!ctx.config.has_pocket(asked)) {
      return {0, "pocket " + std::to_string(asked) + " is not in the config (" + free_words + ")"};
    }
    if (!free_for_tool(asked)) {
      const int owner = asked == taken ? held : ctx.tools.tool_of(asked);
      return {0,
              "pocket " + std::to_string(asked) + " is " +
                  (asked == taken ? "where tool " + std::to_string(owner) + " in the spindle goes"
                                  : "tool " + std::to_string(owner) + "'s") +
                  " (" + free_words + ")"};
    }
    return {asked, ""};
  }
  if (const auto home = ctx.tools.home_of(tool); home && free_for_tool(*home)) return {*home, ""};
  if (const auto first = ctx.config.first_pocket_of(tool); first && free_for_tool(*first)) {
    return {*first, ""};
  }
  if (free.empty()) return {0, "no pocket for " + tool_name(tool) + ": " + free_words};
  const Point& loading = ctx.config.loading;
  const auto nearest = std::min_element(free.begin(), free.end(), [&](int a, int b) {
    const Point& pa = ctx.config.pockets.at(a).at;
    const Point& pb = ctx.config.pockets.at(b).at;
    return std::hypot(pa.x - loading.x, pa.y - loading.y) <
           std::hypot(pb.x - loading.x, pb.y - loading.y);
  });
  return {*nearest, ""};
}

std::optional<std::string> why_not_load(const Context& ctx, int tool, int pocket) {
  if (ctx.machine.task_busy) return ctx.machine.task_busy;
  if (tool <= 0) return "load needs a tool number above 0, got " + std::to_string(tool);
  if (pocket < 0)
    return "pocket-number must be 0 (chosen) or a pocket, got " + std::to_string(pocket);
  if (auto busy = why_not_busy(ctx)) return busy;
  if (!ctx.spindle_at_standstill()) return std::string("the spindle is turning; stop it first");
  if (auto air = why_no_air(ctx)) return air;
  if (const auto in_rack = ctx.tools.pocket_holding(tool)) {
    return tool_name(tool) + " is already in pocket " + std::to_string(*in_rack) +
           "; unload it first";
  }
  const LoadPocket chosen = choose_load_pocket(ctx, tool, pocket);
  if (chosen.pocket == 0) return chosen.why;
  if (ctx.tools.spindle == tool) return std::nullopt;
  return why_spindle_cannot_be_emptied(ctx, false);
}

std::vector<int> measurable_tools(const Context& ctx, const std::vector<int>& asked,
                                  std::string& skipped) {
  std::vector<int> tools;
  for (const int tool : asked) {
    if (std::find(tools.begin(), tools.end(), tool) != tools.end()) continue;
    const bool in_spindle = tool != 0 && tool == ctx.tools.spindle && ctx.return_pocket(tool);
    if (ctx.tools.pocket_holding(tool) || in_spindle) {
      tools.push_back(tool);
    } else if (tool != 0) {
      skipped += (skipped.empty() ? "" : ", ") + ("T" + std::to_string(tool));
    }
  }
  return tools;
}

std::optional<std::string> why_not_measure(const Context& ctx, const std::vector<int>& asked) {
  if (ctx.machine.task_busy) return ctx.machine.task_busy;
  if (auto busy = why_not_busy(ctx)) return busy;
  if (!ctx.spindle_at_standstill()) return std::string("the spindle is turning; stop it first");
  if (auto air = why_no_air(ctx)) return air;
  std::string skipped;
  if (measurable_tools(ctx, asked, skipped).empty()) {
    return "no tool to measure in the rack" +
           (skipped.empty() ? std::string() : " (not in the rack: " + skipped + ")");
  }
  return why_spindle_cannot_be_emptied(ctx, false);
}

std::optional<std::string> why_not_unload(const Context& ctx, int tool) {
  if (ctx.machine.task_busy) return ctx.machine.task_busy;
  if (tool <= 0) return "unload needs a tool number above 0, got " + std::to_string(tool);
  if (auto busy = why_not_busy(ctx)) return busy;
  if (!ctx.spindle_at_standstill()) return std::string("the spindle is turning; stop it first");
  if (auto air = why_no_air(ctx)) return air;
  if (ctx.tools.spindle == tool) return std::nullopt;
  if (!ctx.tools.pocket_holding(tool)) return tool_name(tool) + " is not in the rack";
  return why_spindle_cannot_be_emptied(ctx, false);
}

std::optional<std::string> why_not_verify(const Context& ctx, int pocket) {
  if (ctx.machine.task_busy) return ctx.machine.task_busy;
  std::vector<int> numbers;
  for (const auto& [number, entry] : ctx.config.pockets) numbers.push_back(number);
  if (!ctx.config.has_pocket(pocket)) {
    return "pocket-number " + std::to_string(pocket) + " is not a pocket of the config (" +
           pocket_list(numbers) + ")";
  }
  if (auto busy = why_not_busy(ctx)) return busy;
  if (!ctx.spindle_at_standstill()) return std::string("the spindle is turning; stop it first");
  // The spindle goes where the tool would sit: only an empty pocket can be
  // driven into (a wired pocket sensor that disagrees stops all work before this).
  if (ctx.tools.holds(pocket)) {
    const std::string tool = std::to_string(ctx.tools.tool_of(pocket));
    return "pocket " + std::to_string(pocket) + " holds tool " + tool + "; fetch it first (M6 T" +
           tool + ") to verify with it in the spindle";
  }
  return std::nullopt;
}

std::optional<std::string> why_chuck_held_open(const Context& ctx) {
  if (!ctx.outputs.chuck_open) return std::nullopt;
  return std::string(
      "the chuck is open (released from G-code); clamp it first (o<fixed_atc_probe_chuck_clamp> "
      "call, or the M-code the INI remaps to it)");
}

double loading_tolerance(const Config& config) {
  return config.units == Units::inch ? 0.002 : 0.05;
}

std::optional<std::string> why_not_chuck(const Context& ctx, const ChuckRequest& request) {
  if (auto not_ready = why_not_ready(ctx)) return not_ready;
  if (request.action == ChuckRequest::Action::clamp) return std::nullopt;
  if (!ctx.machine.spindle_stopped) return std::string("the spindle is on; stop it first (M5)");
  if (auto air = why_no_air(ctx)) return air;
  const int held = ctx.tools.spindle;
  if (held == 0) return std::nullopt;
  const Point& loading = ctx.config.loading;
  const std::string why = tool_name(held) +
                          " is in the spindle and would drop; release it only at loading (" +
                          position_words(ctx.config, loading) + ") or with the spindle empty";
  if (!request.at) return why + " (LinuxCNC does not say where the machine is)";
  const Point& at = *request.at;
  const double tolerance = loading_tolerance(ctx.config);
  if (std::abs(at.x - loading.x) > tolerance || std::abs(at.y - loading.y) > tolerance ||
      std::abs(at.z - loading.z) > tolerance) {
    return why + "; the machine is at " + position_words(ctx.config, at);
  }
  return std::nullopt;
}

std::optional<std::string> why_not_reconfigure(const Context& ctx, bool idle,
                                               bool comparing_sensors) {
  // A position taken while a program or MDI moves the machine is nowhere in particular.
  if (!idle) return std::string("only while the changer is idle");
  if (ctx.machine.task_busy) {
    return std::string("a program or MDI command is running; teach once it stopped");
  }
  if (comparing_sensors) return ctx.activity.dwell;
  return why_chuck_held_open(ctx);
}

}  // namespace fatc
