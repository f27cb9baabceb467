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
    const bool recorded = tools.in_pocket.count(pocket) != 0;
    if (read.occupied(pocket) == recorded) continue;
    const std::string where =
        tools.spindle == pocket ? "in the spindle" : std::string("out of the machine");
    found.push_back(
        recorded ? "pocket " + std::to_string(pocket) + " reads empty (" + pocket_pin(pocket) +
                       " off), but tool " + std::to_string(pocket) + " is recorded in it"
                 : "pocket " + std::to_string(pocket) + " reads occupied (" + pocket_pin(pocket) +
                       " on), but tool " + std::to_string(pocket) + " is recorded " + where);
  }
  return found;
}

std::vector<std::string> adopt_pocket_sensors(const SensorConfig& wired, const SensorReadings& read,
                                              int answered, ToolState& tools) {
  std::vector<std::string> changed;
  for (const int pocket : wired.pocket_occupancy) {
    if (pocket == answered || pocket == tools.spindle) continue;
    const bool occupied = read.occupied(pocket);
    if ((tools.in_pocket.count(pocket) != 0) == occupied) continue;
    if (occupied) {
      tools.in_pocket.insert(pocket);
    } else {
      tools.in_pocket.erase(pocket);
    }
    changed.push_back("pocket " + std::to_string(pocket) + " recorded " +
                      (occupied ? "full" : "empty") + ", as " + pocket_pin(pocket) + " reads (" +
                      on_off(occupied) + ")");
  }
  return changed;
}

}  // namespace fatc
