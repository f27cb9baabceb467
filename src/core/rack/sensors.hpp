#pragma once

#include <map>
#include <string>
#include <vector>

#include "../config/config.hpp"
#include "tool_state.hpp"

namespace fatc {

/// What the optional sensors read, as the adapter last saw their HAL inputs.
/// Only the ones the config says are wired mean anything.
struct SensorReadings {
  bool tool_present = false;            ///< `tool-present`
  bool drawbar_open = false;            ///< `drawbar-open`
  bool drawbar_closed = false;          ///< `drawbar-closed`
  bool air_pressure_ok = false;         ///< `air-pressure-ok`
  bool zero_speed = false;              ///< `zero-speed`: the spindle's zero-speed feedback
  std::map<int, bool> pocket_occupied;  ///< `pocket-occupied-N`, by pocket number
  bool rack_cover_opened = false;       ///< `rack-cover-opened`
  bool rack_cover_closed = false;       ///< `rack-cover-closed`

  bool occupied(int pocket) const {
    const auto found = pocket_occupied.find(pocket);
    return found != pocket_occupied.end() && found->second;
  }
  bool operator==(const SensorReadings& other) const {
    return tool_present == other.tool_present && drawbar_open == other.drawbar_open &&
           drawbar_closed == other.drawbar_closed && air_pressure_ok == other.air_pressure_ok &&
           zero_speed == other.zero_speed && pocket_occupied == other.pocket_occupied &&
           rack_cover_opened == other.rack_cover_opened &&
           rack_cover_closed == other.rack_cover_closed;
  }
  bool operator!=(const SensorReadings& other) const { return !(*this == other); }
};

/// Where the wired sensors contradict the tool state, one phrase each, e.g.
/// "pocket 5 reads empty (pocket-occupied-5 off), but tool 12 is recorded in it".
std::vector<std::string> sensor_disagreements(const SensorConfig& wired, const SensorReadings& read,
                                              const ToolState& tools);

/// The tool state as the operator's clearing of a fault leaves it, with the
/// wired pocket sensors taken at their word for every pocket the operator did
/// not answer about (`answered`, 0 none). Returns the phrases of what it
/// changed: "pocket 5 recorded empty, as pocket-occupied-5 reads".
std::vector<std::string> adopt_pocket_sensors(const SensorConfig& wired, const SensorReadings& read,
                                              int answered, ToolState& tools);

/// "pocket-occupied-5", the pin's name without the component.
std::string pocket_pin(int pocket);

}  // namespace fatc
