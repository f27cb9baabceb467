#include "sensors.hpp"

namespace fatc {
namespace {

std::string on_off(bool value) { return value ? "on" : "off"; }

}  // namespace

std::string pocket_pin(int pocket) { return "pocket-occupied-" + std::to_string(pocket); }

std::vector<std::string> sensor_disagreements(const SensorConfig& wired, const SensorReadings& read,
                                              const ToolState& tools) {
  std::vector<std::string> found;
  if (wired.tool_present && read.tool_present != (tools.spindle != 0)) {
    found.push_back(tools.spindle != 0
                        ? "tool " + std::to_string(tools.spindle) +
                              " is recorded in the spindle, but tool-present reads it empty (off)"
                        : std::string("the spindle is recorded empty, but tool-present reads a "
                                      "tool in it (on)"));
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
  return found;
}

std::vector<std::string> adopt_pocket_sensors(const SensorConfig& wired, const SensorReadings& read,
                                              int answered, ToolState& tools) {
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
