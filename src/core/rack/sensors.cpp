#include "sensors.hpp"

namespace fatc {
namespace {

std::string on_off(bool value) { return value ? "on" : "off"; }

std::string pin(Sensor sensor) { return declared(sensor).words.pin; }

}  // namespace

bool Sensors::spindle_still() const {
  return !wired.wired(Sensor::zero_speed) || read.reads(Sensor::zero_speed);
}

std::string Sensors::turning_words() const {
  return spindle_still() ? "" : pin(Sensor::zero_speed) + " off";
}

bool Sensors::at_speed() const { return !senses_at_speed() || read.reads(Sensor::at_speed); }
bool Sensors::senses_at_speed() const { return wired.wired(Sensor::at_speed); }

bool Sensors::nut_reads(bool seen) const {
  return !wired.wired(Sensor::nut_seen) || read.reads(Sensor::nut_seen) == seen;
}

bool Sensors::air_ok() const {
  return !wired.wired(Sensor::air_pressure) || read.reads(Sensor::air_pressure);
}

bool Sensors::drawbar_reads_open() const {
  return (!wired.wired(Sensor::drawbar_open) || read.reads(Sensor::drawbar_open)) &&
         (!wired.wired(Sensor::drawbar_closed) || !read.reads(Sensor::drawbar_closed));
}

bool Sensors::drawbar_reads_closed() const {
  return (!wired.wired(Sensor::drawbar_closed) || read.reads(Sensor::drawbar_closed)) &&
         (!wired.wired(Sensor::drawbar_open) || !read.reads(Sensor::drawbar_open));
}

std::string Sensors::drawbar_words() const {
  std::string words;
  for (const Sensor sensor : {Sensor::drawbar_open, Sensor::drawbar_closed}) {
    if (!wired.wired(sensor)) continue;
    words += (words.empty() ? "" : ", ") + pin(sensor) + " " + on_off(read.reads(sensor));
  }
  return words;
}

bool Sensors::spindle_reads(bool holds) const {
  return !wired.wired(Sensor::tool_present) || read.reads(Sensor::tool_present) == holds;
}

bool Sensors::pocket_reads(int pocket, bool occupied) const {
  return !wired.pocket(pocket) || read.occupied(pocket) == occupied;
}

bool Sensors::senses_cover_opened() const { return wired.wired(Sensor::rack_cover_opened); }
bool Sensors::senses_cover_closed() const { return wired.wired(Sensor::rack_cover_closed); }
bool Sensors::cover_reads_opened() const { return read.reads(Sensor::rack_cover_opened); }
bool Sensors::cover_reads_closed() const { return read.reads(Sensor::rack_cover_closed); }

std::string Sensors::tool_pin() { return pin(Sensor::tool_present); }
std::string Sensors::air_pin() { return pin(Sensor::air_pressure); }
std::string Sensors::cover_opened_pin() { return pin(Sensor::rack_cover_opened); }
std::string Sensors::at_speed_pin() { return pin(Sensor::at_speed); }
std::string Sensors::nut_pin() { return pin(Sensor::nut_seen); }

std::vector<std::string> Sensors::disagreements(const ToolState& tools, bool chuck_open,
                                                bool cover_open) const {
  std::vector<std::string> found;
  // A released chuck holds nothing for certain: the operator may be taking
  // the tool out. The spindle is compared again once it is clamped.
  if (!chuck_open && !spindle_reads(tools.spindle != 0)) {
    found.push_back(
        tools.spindle != 0
            ? "tool " + std::to_string(tools.spindle) + " is recorded in the spindle, but " +
                  tool_pin() + " reads it empty (off)"
            : "the spindle is recorded empty, but " + tool_pin() + " reads a tool in it (on)");
  }
  for (const int pocket : wired.pocket_occupancy) {
    const bool recorded = tools.holds(pocket);
    if (read.occupied(pocket) == recorded) continue;
    const std::string p = "pocket " + std::to_string(pocket);
    const int tool = tools.tool_of(pocket);
    const std::string t = "tool " + std::to_string(tool);
    if (recorded) {
      found.push_back(p + " reads empty (" + pocket_pin(pocket) + " off), but " + t +
                      " is recorded in it");
    } else if (tool == 0) {
      found.push_back(p + " reads occupied (" + pocket_pin(pocket) +
                      " on), but it is recorded free; take the tool out, or load it there");
    } else {
      found.push_back(p + " reads occupied (" + pocket_pin(pocket) + " on), but " + t +
                      " is recorded " +
                      (tools.spindle == tool ? "in the spindle" : "out of the machine"));
    }
  }
  if (senses_cover_closed() && !cover_open && !cover_reads_closed()) {
    found.push_back("the rack cover is not closed (" + pin(Sensor::rack_cover_closed) + " off)");
  }
  return found;
}

std::vector<std::string> Sensors::adopt_pocket_sensors(int answered, ToolState& tools) const {
  std::vector<std::string> changed;
  for (const int pocket : wired.pocket_occupancy) {
    // Only a pocket some tool (not the spindle's) belongs in says which tool it holds.
    const int tool = tools.tool_of(pocket);
    if (pocket == answered || tool == 0 || tool == tools.spindle) continue;
    const bool occupied = read.occupied(pocket);
    if (tools.holds(pocket) == occupied) continue;
    tools.pockets[pocket].holds = occupied;
    changed.push_back("pocket " + std::to_string(pocket) + " recorded " +
                      (occupied ? "full" : "empty") + ", as " + pocket_pin(pocket) + " reads (" +
                      on_off(occupied) + ")");
  }
  return changed;
}

}  // namespace fatc
