#pragma once

#include <bitset>
#include <map>
#include <string>
#include <vector>

#include "../config/config.hpp"
#include "tool_state.hpp"

namespace fatc {

/// What the optional sensors read, as the adapter last saw their HAL inputs.
/// Only the ones the config says are wired mean anything.
struct SensorReadings {
  std::bitset<kSensorCount> bits;  ///< by Sensor
  std::map<int, bool> pockets;     ///< the pocket sensors, by pocket number

  bool reads(Sensor sensor) const { return bits.test(index(sensor)); }
  void set(Sensor sensor, bool on) { bits.set(index(sensor), on); }
  bool occupied(int pocket) const {
    const auto found = pockets.find(pocket);
    return found != pockets.end() && found->second;
  }
  bool operator==(const SensorReadings& other) const {
    return bits == other.bits && pockets == other.pockets;
  }
  bool operator!=(const SensorReadings& other) const { return !(*this == other); }
};

/// The optional sensors as the sequences see them: which are wired, what
/// they read, and what that means. Each check passes where its sensor is not
/// wired. What gives a sensor its meaning: the state machine asks these and
/// names no sensor itself.
class Sensors {
 public:
  /// `wired`: its machine's config's, read where it lies, so a taught config
  /// the machine takes is the one asked. Not copied: a copy would still read
  /// the config it was made from.
  explicit Sensors(const SensorConfig& wired) : wired(wired) {}
  Sensors(const Sensors&) = delete;
  Sensors& operator=(const Sensors&) = delete;

  const SensorConfig& wired;
  SensorReadings read;

  /// The spindle's own feedback says it stands still (LinuxCNC's word is
  /// the machine's: Context::spindle_at_standstill).
  bool spindle_still() const;
  /// The spindle's own feedback where it says the spindle still turns, for a
  /// message: its pin and "off"; else nothing.
  std::string turning_words() const;
  /// The spindle turns at the speed asked for (`spindle-at-speed`), where wired.
  bool at_speed() const;
  bool senses_at_speed() const;
  /// The tool-recognition beam reads a nut (`seen`) or none, where wired.
  bool nut_reads(bool seen) const;
  /// The drawbar has the air to open.
  bool air_ok() const;
  /// The drawbar reads released: its open sensor on, its closed one off.
  bool drawbar_reads_open() const;
  /// The drawbar reads clamped: its closed sensor on, its open one off.
  bool drawbar_reads_closed() const;
  /// What the drawbar's sensors read, for a message: each one's pin, "on" or "off".
  std::string drawbar_words() const;
  /// A tool in the spindle reads there (`holds`), or none.
  bool spindle_reads(bool holds) const;
  /// Pocket `pocket`'s sensor reads `occupied`.
  bool pocket_reads(int pocket, bool occupied) const;
  /// The rack cover's sensors: wired, and what they read.
  bool senses_cover_opened() const;
  bool senses_cover_closed() const;
  bool cover_reads_opened() const;
  bool cover_reads_closed() const;

  /// Where the sensors contradict the tool state, or the rack cover its
  /// command (`cover_open`), one phrase each: "pocket 5 reads empty
  /// (pocket-occupied-5 off), but tool 12 is recorded in it". A released
  /// chuck (`chuck_open`) holds nothing for certain.
  std::vector<std::string> disagreements(const ToolState& tools, bool chuck_open,
                                         bool cover_open) const;
  /// The tool state as the operator's clearing of a fault leaves it, with the
  /// pocket sensors taken at their word for every pocket the operator did not
  /// answer about (`answered`, 0 none). Returns the phrases of what it
  /// changed: "pocket 5 recorded empty, as pocket-occupied-5 reads (off)".
  std::vector<std::string> adopt_pocket_sensors(int answered, ToolState& tools) const;

  /// The pins the sequences' messages name: the spindle's, the air's, the
  /// rack cover's opened sensor.
  static std::string tool_pin();
  static std::string air_pin();
  static std::string cover_opened_pin();
  static std::string at_speed_pin();
  static std::string nut_pin();
};

}  // namespace fatc
