#include "air_run.hpp"

#include <algorithm>
#include <cmath>

#include "../config/rack_volume.hpp"
#include "../rack/keepout.hpp"
#include "../formatted.hpp"
#include "simulator.hpp"

namespace fatc {
namespace {

/// The top of the rack part pocket `number` is in: how high its forks and the
/// keep-out above them reach.
std::optional<double> rack_top_at(const std::vector<RackPart>& volume, int number) {
  for (const RackPart& part : volume) {
    for (const auto& pocket : part.pockets) {
      if (pocket.number == number) return part.box.high.z;
    }
  }
  return std::nullopt;
}

/// The one move `move` becomes in the air.
Step in_the_air(const std::vector<RackPart>& volume, Step move, const AirSettings& air) {
  move.before.clear();
  move.blend = 0.0;
  move.kind = StepKind::feed;
  move.feed = air.feed;
  const auto top = move.pocket != 0 ? rack_top_at(volume, move.pocket) : std::nullopt;
  if (top && (move.axes & axis_z) && move.target.z < *top + air.height) {
    move.target.z = *top + air.height;
    move.label += " (in the air)";
  }
  return move;
}

}  // namespace

std::optional<std::string> why_not_air(const Config& config, const AirSettings& air) {
  const char* unit = units_name(config.units);
  if (!std::isfinite(air.height) || air.height <= 0.0) {
    return "air height " + formatted("%g", air.height) + ": expected a height above the rack in " +
           unit + ", more than 0";
  }
  if (!std::isfinite(air.feed) || air.feed < 0.0) {
    return "air feed " + formatted("%g", air.feed) + ": expected a feed in " + unit +
           "/min, more than 0 (0: the config's verify feed, " +
           formatted("F%g", config.dry_run_feed()) + ")";
  }
  return std::nullopt;
}

std::vector<Step> air_route(const Config& config, const std::vector<Step>& steps,
                      const AirSettings& air) {
  const std::vector<RackPart> volume = rack_volume(config);
  std::vector<Step> route;
  // Where the sequence itself goes, and the height its probing started at:
  // the moves around a probe (backing off the sensor, the retract) go below
  // that only because the probe went down first; they stay out with it.
  Point real;
  std::optional<double> probing_from;
  for (const Step& step : steps) {
    if (step.kind == StepKind::probe) {
      if (!probing_from) probing_from = real.z;
      real = moved_to(real, step);
      continue;
    }
    if (step.kind != StepKind::rapid && step.kind != StepKind::feed) continue;
    for (const Step& move : moves_of(step)) {
      real = moved_to(real, move);
      if (probing_from && real.z < *probing_from - 1e-9) continue;
      probing_from.reset();
      route.push_back(in_the_air(volume, move, air));
    }
  }
  return route;
}

AirPlan plan_air_run(const Config& config, const ToolState& tools, const Point& at, unsigned known,
                     const std::function<void(Changer&)>& request, const std::string& name,
                     const AirSettings& asked, int held, double held_length) {
  AirPlan result;
  AirSettings air = asked;
  if (air.feed == 0.0) air.feed = config.dry_run_feed();
  const std::string air_name = "air run of " + name + ", " + air_words(config, air);
  if (auto why = why_not_air(config, air)) {
    result.refused = air_name + " refused: " + *why;
    return result;
  }
  const Simulator planned = plan_from(config, tools, at, known, request);
  for (const Step& step : planned.steps()) {
    if (step.kind == StepKind::fail) {
      result.refused = air_name + " refused: " + step.label;
      return result;
    }
  }
  const auto errors = planned.messages(MessageKind::error);
  if (!errors.empty()) {
    // "unload of tool 9 refused: tool 9 is not in the rack": the reason, once.
    const std::string inner = name + " refused: ";
    const std::string& why = errors.front();
    result.refused =
        air_name + " refused: " + (why.rfind(inner, 0) == 0 ? why.substr(inner.size()) : why);
    return result;
  }
  AirRunRequest flown{air_name, air_route(config, planned.steps(), air)};
  // The keep-out lets a tool's tip into the pocket a move serves (a return);
  // in the air the spindle's own tool goes over every pocket, full or not.
  const bool over_the_rack = std::any_of(flown.route.begin(), flown.route.end(),
                                         [](const Step& move) { return move.pocket != 0; });
  if (held != 0 && over_the_rack && held_length > air.height + 1e-9) {
    result.refused = air_name + " refused: T" + std::to_string(held) + " in the spindle (" +
                     formatted("%g %s", held_length, units_name(config.units)) +
                     ") would hang " +
                     formatted("%g %s", held_length - air.height, units_name(config.units)) +
                     " below the rack's top: fly at least " +
                     formatted("%g %s", held_length, units_name(config.units)) +
                     " above it, or empty the spindle";
    return result;
  }
  result.request = std::move(flown);
  return result;
}

AirPlan plan_air_run(const Changer& changer, const AirAsk& ask, const std::optional<Point>& at) {
  const Config& config = changer.config();
  ToolState tools = changer.tools();
  const int held = tools.spindle;
  const double held_length = changer.keepout_lengths().of(held, tools.lengths).length;
  std::function<void(Changer&)> request;
  std::string name;
  const int tool = ask.tool;
  const int pocket = ask.pocket;
  switch (ask.what) {
    case AirAsk::What::change: {
      tools = as_if_holding(config, tools, ask.from.value_or(tools.spindle));
      request = [tool](Changer& c) { c.tool_change(tool); };
      name = "M6 T" + std::to_string(tool) + " with " +
             (tools.spindle == 0 ? std::string("an empty spindle")
                                 : "T" + std::to_string(tools.spindle));
      break;
    }
    case AirAsk::What::load:
      request = [tool, pocket](Changer& c) { c.load(tool, pocket); };
      name = "load of tool " + std::to_string(tool);
      break;
    case AirAsk::What::unload:
      request = [tool](Changer& c) { c.unload(tool); };
      name = "unload of tool " + std::to_string(tool);
      break;
    case AirAsk::What::verify:
      request = [pocket](Changer& c) { c.verify(pocket); };
      name = "verify of pocket " + std::to_string(pocket);
      break;
  }
  return plan_air_run(config, tools, at.value_or(Point{}), at ? axis_xyz : 0u, request, name,
                      ask.air, held, held_length);
}

ToolState as_if_holding(const Config& config, ToolState tools, int tool) {
  if (tools.spindle == tool) return tools;
  if (const auto home = return_pocket(tools, config, tools.spindle)) {
    tools.pockets[*home] = {tools.spindle, true};
  }
  tools.put_in_spindle(tool);
  return tools;
}

std::string air_words(const Config& config, const AirSettings& air) {
  return formatted("%g %s above the rack at F%g", air.height, units_name(config.units), air.feed);
}

}  // namespace fatc
