#include "io_check.hpp"

#include <algorithm>

#include "../config/rack_volume.hpp"
#include "../formatted.hpp"

namespace fatc {
namespace {

const char* on_off(bool value) { return value ? "on" : "off"; }

std::string pin(Sensor sensor) { return declared(sensor).words.pin; }

bool wired(const Config& config, Sensor sensor) { return config.sensors.wired(sensor); }

/// What `sensor` should read with these facts, and why; unset where either is right.
IoSensorLine expected(Sensor sensor, const IoFacts& f) {
  IoSensorLine line;
  const std::string chuck = f.chuck_open ? "the chuck is released" : "the chuck is clamped";
  const std::string cover =
      f.cover_open ? "the cover is commanded open" : "the cover is commanded closed";
  switch (sensor) {
    case Sensor::zero_speed:
      line.expected = f.spindle_stopped;
      line.why = f.spindle_stopped ? "LinuxCNC has the spindle off" : "LinuxCNC has the spindle on";
      break;
    case Sensor::tool_present:
      if (f.chuck_open) {
        line.why = "the chuck is released: a tool may be in it or not";
      } else if (f.tools.uncertain) {
        line.why = "what the spindle holds is not certain since a sequence was cut off";
      } else {
        line.expected = f.tools.spindle != 0;
        line.why = f.tools.spindle != 0
                       ? "tool " + std::to_string(f.tools.spindle) + " is in the spindle"
                       : "the spindle is empty";
      }
      break;
    case Sensor::drawbar_open:
      line.expected = f.chuck_open;
      line.why = chuck;
      break;
    case Sensor::drawbar_closed:
      line.expected = !f.chuck_open;
      line.why = chuck;
      break;
    case Sensor::air_pressure:
      line.expected = true;
      line.why = "the drawbar needs its air";
      break;
    case Sensor::rack_cover_opened:
      line.expected = f.cover_open;
      line.why = cover;
      break;
    case Sensor::rack_cover_closed:
      line.expected = !f.cover_open;
      line.why = cover;
      break;
    case Sensor::at_speed:
      if (f.spindle_stopped) {
        line.expected = false;
        line.why = "LinuxCNC has the spindle off";
      } else {
        line.why = "the spindle turns: at speed once its ramp is through";
      }
      break;
    case Sensor::nut_seen:
      line.why = "it reads a nut only where the nose stands at a recognition zone";
      break;
  }
  return line;
}

bool spindle_may_hold_tool(const Config& config, const SensorReadings& read, const IoFacts& f) {
  return f.tools.spindle != 0 || f.tools.uncertain ||
         (wired(config, Sensor::tool_present) && read.reads(Sensor::tool_present));
}

std::string what_spindle_holds(const SensorReadings& read, const IoFacts& f) {
  if (f.tools.spindle != 0 && !f.tools.uncertain) {
    return "tool " + std::to_string(f.tools.spindle) + " is in the spindle";
  }
  if (read.reads(Sensor::tool_present))
    return "a tool is in the spindle (" + pin(Sensor::tool_present) + " on)";
  return "the spindle may hold a tool (a sequence was cut off)";
}

/// The spindle turns, in words; empty when it stands.
std::string turning(const Config& config, const SensorReadings& read, const IoFacts& f) {
  if (!f.spindle_stopped) return "the spindle is on (spindle-stopped off)";
  if (wired(config, Sensor::zero_speed) && !read.reads(Sensor::zero_speed)) {
    return "the spindle still turns (" + pin(Sensor::zero_speed) + " off)";
  }
  return "";
}

/// What answers each action: its sensor, and what it reads once it answered.
struct Answer {
  Sensor sensor;
  bool reads;
};
std::vector<Answer> answers(IoAction action) {
  switch (action) {
    case IoAction::chuck_release:
      return {{Sensor::drawbar_open, true}, {Sensor::drawbar_closed, false}};
    case IoAction::chuck_clamp:
      return {{Sensor::drawbar_closed, true}, {Sensor::drawbar_open, false}};
    case IoAction::cover_open:
      return {{Sensor::rack_cover_opened, true}};
    case IoAction::cover_close:
      return {{Sensor::rack_cover_closed, true}};
    case IoAction::air_blast:
      return {};
  }
  return {};
}

/// "drawbar opened", "rack cover closed": what happened once it answered.
const char* happened(IoAction action) {
  switch (action) {
    case IoAction::chuck_release:
      return "drawbar opened";
    case IoAction::chuck_clamp:
      return "drawbar closed";
    case IoAction::cover_open:
      return "rack cover opened";
    case IoAction::cover_close:
      return "rack cover closed";
    case IoAction::air_blast:
      return "air blast";
  }
  return "";
}

/// The driven output, for an output no wired sensor answers.
const char* driven(IoAction action) {
  switch (action) {
    case IoAction::chuck_release:
      return "chuck released; no drawbar sensor is wired to time it (sensors.drawbar_open, "
             "sensors.drawbar_closed)";
    case IoAction::chuck_clamp:
      return "chuck clamped; no drawbar sensor is wired to time it (sensors.drawbar_open, "
             "sensors.drawbar_closed)";
    case IoAction::cover_open:
      return "rack cover commanded open; no rack_cover.opened_sensor to time it";
    case IoAction::cover_close:
      return "rack cover commanded closed; no rack_cover.closed_sensor to time it";
    case IoAction::air_blast:
      return "air blast on for 1.0 s; no sensor answers it: listen and feel at the spindle's taper";
  }
  return "";
}

}  // namespace

std::optional<IoAction> io_action_named(const std::string& name) {
  for (const IoActionDeclaration& a : kIoActions) {
    if (name == a.name) return a.action;
  }
  return std::nullopt;
}

const char* io_action_name(IoAction action) { return declared(action).name; }

std::vector<Sensor> io_sensors_watching(IoOutput output) {
  switch (output) {
    case IoOutput::chuck:
      return {Sensor::drawbar_open, Sensor::drawbar_closed, Sensor::tool_present};
    case IoOutput::cover:
      return {Sensor::rack_cover_opened, Sensor::rack_cover_closed};
    case IoOutput::air_blast:
      return {Sensor::air_pressure};
  }
  return {};
}

std::string IoSensorLine::words() const {
  std::string text = pin + ": " + on_off(value);
  if (!expected) return text + ", either is right (" + why + ")";
  text += std::string(", expected ") + on_off(*expected) + " (" + why + ")";
  return agrees() ? text : text + ": NOT as expected, check its wiring";
}

std::vector<IoSensorLine> io_sensor_lines(const Config& config, const SensorReadings& read,
                                          const IoFacts& facts) {
  std::vector<IoSensorLine> lines;
  for (const SensorDeclaration& s : kSensors) {
    if (!wired(config, s.sensor)) continue;
    IoSensorLine line = expected(s.sensor, facts);
    line.pin = s.words.pin;
    line.value = read.reads(s.sensor);
    lines.push_back(std::move(line));
  }
  for (const int pocket : config.sensors.pocket_occupancy) {
    IoSensorLine line;
    line.pin = pocket_pin(pocket);
    line.value = read.occupied(pocket);
    const int tool = facts.tools.tool_of(pocket);
    if (facts.tools.uncertain && facts.tools.in_progress &&
        facts.tools.in_progress->pocket == pocket) {
      line.why = "a sequence was cut off at this pocket";
    } else {
      line.expected = facts.tools.holds(pocket);
      line.why = *line.expected ? "tool " + std::to_string(tool) + " is recorded in it"
                 : tool != 0    ? "its tool " + std::to_string(tool) + " is recorded elsewhere"
                                : "it is recorded free";
    }
    lines.push_back(std::move(line));
  }
  return lines;
}

int io_pocket_under_spindle(const Config& config, const Point& nose, double tool_length) {
  for (const RackPart& part : rack_volume(config)) {
    const Box& b = part.box;
    const bool over =
        nose.x > b.low.x && nose.x < b.high.x && nose.y > b.low.y && nose.y < b.high.y;
    if (over && nose.z - tool_length < b.high.z) return nearest_pocket(part, nose);
  }
  return 0;
}

std::optional<std::string> io_refusal(IoAction action, const Config& config,
                                      const SensorReadings& read, const IoFacts& f) {
  if (!f.machine_on) return "the machine is off (machine-on off): turn it on first";
  if (f.busy) return *f.busy;
  switch (action) {
    case IoAction::chuck_release: {
      if (const std::string spinning = turning(config, read, f); !spinning.empty()) {
        return spinning + ": the chuck opens only on a spindle that stands";
      }
      if (wired(config, Sensor::air_pressure) && !read.reads(Sensor::air_pressure)) {
        return "no air (" + pin(Sensor::air_pressure) + " off): the drawbar cannot open";
      }
      if (!f.holding_tool && spindle_may_hold_tool(config, read, f)) {
        return what_spindle_holds(read, f) +
               ": it drops when the chuck opens; hold it and say so (io-check-holding-tool, "
               "--holding-tool)";
      }
      return std::nullopt;
    }
    case IoAction::chuck_clamp:
      return std::nullopt;
    case IoAction::cover_open:
    case IoAction::cover_close: {
      if (!config.rack_cover)
        return std::string("config.json has no rack_cover: there is none to drive");
      if (action == IoAction::cover_open) return std::nullopt;
      if (!f.homed || !f.nose) {
        return std::string(
            "where the spindle stands is not known (not homed): the cover could close on it");
      }
      if (const int pocket = io_pocket_under_spindle(config, *f.nose, f.tool_length)) {
        return formatted(
            "the spindle is in the rack (X%.3f Y%.3f Z%.3f, by pocket %d): the "
            "cover would close on it; move it up out of the rack first",
            f.nose->x, f.nose->y, f.nose->z, pocket);
      }
      return std::nullopt;
    }
    case IoAction::air_blast:
      if (!config.air_blast)
        return std::string("config.json's air_blast is off: the changer drives no air blast");
      return std::nullopt;
  }
  return std::nullopt;
}

std::optional<IoTimeout> io_timeout(IoAction action, const Config& config) {
  const auto answered_by = answers(action);
  const bool any = std::any_of(answered_by.begin(), answered_by.end(),
                               [&](const Answer& a) { return wired(config, a.sensor); });
  if (!any) return std::nullopt;
  if (action == IoAction::cover_open) {
    return IoTimeout{config.rack_cover->timeout_seconds, "rack_cover.timeout_seconds"};
  }
  if (action == IoAction::cover_close) {
    // As the changer waits for it after a sequence (Operating's ComparingSensors).
    return config.rack_cover->timeout_seconds >= config.sensor_timeout_seconds
               ? IoTimeout{config.rack_cover->timeout_seconds, "rack_cover.timeout_seconds"}
               : IoTimeout{config.sensor_timeout_seconds, "sensor_timeout_seconds"};
  }
  return IoTimeout{config.sensor_timeout_seconds, "sensor_timeout_seconds"};
}

bool io_answered(IoAction action, const Config& config, const SensorReadings& read) {
  for (const Answer& a : answers(action)) {
    if (wired(config, a.sensor) && read.reads(a.sensor) != a.reads) return false;
  }
  return true;
}

std::string io_timing_words(IoAction action, const Config& config, std::optional<double> seconds,
                            const SensorReadings& read) {
  const auto timeout = io_timeout(action, config);
  if (!timeout) return driven(action);
  const std::string yours = formatted("your timeout %g s (", timeout->seconds) + timeout->key + ")";
  if (!seconds) {
    std::string reads;
    for (const Answer& a : answers(action)) {
      if (!wired(config, a.sensor)) continue;
      reads += (reads.empty() ? "" : ", ") + pin(a.sensor) + " " + on_off(read.reads(a.sensor));
    }
    return std::string(happened(action)) + ": NO answer within " + yours + "; it reads " + reads +
           ": check the sensor, its wiring and the output";
  }
  std::string words = std::string(happened(action)) + formatted(" in %.2f s; ", *seconds) + yours;
  if (*seconds > kIoSlowShare * timeout->seconds) {
    words += formatted(
        ": slow, over %.0f%% of the timeout; a change may time out on a cold "
        "morning or with less air",
        kIoSlowShare * 100);
  }
  return words;
}

}  // namespace fatc
