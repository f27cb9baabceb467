#include "admission.hpp"

#include "../../formatted.hpp"

namespace fatc {

std::string tool_name(int tool) { return "tool " + std::to_string(tool); }

/// The tool in the spindle must be able to go home before anything else; a
/// manual tool only can when M6 may hand it out at `loading` (`manual_tools`).
std::optional<std::string> why_spindle_cannot_be_emptied(const Context& ctx, bool hand_out) {
  const int held = ctx.tools.spindle;
  if (held == 0) return std::nullopt;
  const auto pocket = ctx.return_pocket(held);
  if (!pocket) {
    if (hand_out) return std::nullopt;
    // A load whose probe missed leaves its tool so: loading it again measures
    // it into a pocket.
    return tool_name(held) + " in the spindle has no pocket to go to; unload it, or load " +
           tool_name(held) + " again to measure it into a pocket";
  }
  if (ctx.tools.holds(*pocket)) {
    return "pocket " + std::to_string(*pocket) + " is recorded full, yet " + tool_name(held) +
           " that belongs in it is in the spindle; check the rack";
  }
  return std::nullopt;
}

std::optional<std::string> why_spindle_turning(const Context& ctx) {
  if (ctx.spindle_at_standstill()) return std::nullopt;
  return std::string("the spindle is turning; stop it first");
}

/// Every sequence opens the chuck: no air, no start (the legs check again
/// before each opening).
std::optional<std::string> why_no_air(const Context& ctx) {
  if (ctx.sensors.air_ok()) return std::nullopt;
  return "air pressure is low (" + Sensors::air_pin() + " off): the chuck cannot open";
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
  return formatted("X%.3f Y%.3f Z%.3f %s", at.x, at.y, at.z, units_name(config.units));
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

std::optional<std::string> why_datum_refuses(const Context& ctx, int tool) {
  if (!ctx.config.rack_touch) return std::nullopt;
  const RackTouch& touch = *ctx.config.rack_touch;
  if (!ctx.tools.datum.drift.empty()) {
    return ctx.tools.datum.drift +
           "; M6 is refused until the datum is taught again (teach-datum) or the operator clears "
           "it (clear-datum-drift)";
  }
  if (tool != 0 && ctx.config.is_probe(tool)) return std::nullopt;
  const int every = touch.check_every_changes;
  if (every > 0 && ctx.tools.datum.changes >= every) {
    return "the rack datum check is due: " + std::to_string(ctx.tools.datum.changes) +
           " changes since the last (rack_touch.check_every_changes " + std::to_string(every) +
           "); put the probe in and run check-datum";
  }
  if (touch.check_at_start && !ctx.datum_checked) {
    return std::string(
        "the rack datum check is due at start (rack_touch.check_at_start): put the probe in and "
        "run check-datum");
  }
  return std::nullopt;
}

}  // namespace fatc
