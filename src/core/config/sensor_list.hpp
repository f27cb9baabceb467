#pragma once

// The optional sensors, declared once: the config key that wires each, its
// HAL pin, what it says, and the fact of the machine it reports. The config
// reader, the references (docs/config.md, docs/pins.md, the man page), the
// HAL adapter, --check's list of wired sensors and the dry run's simulated
// rack all take them from here; rack/sensors.cpp alone gives each its
// meaning in the sequences, and keys.cpp places each key in the reference.

#include <bitset>
#include <cstddef>
#include <iterator>
#include <set>
#include <string>

namespace fatc {

/// The sensors of one bit each, in the order of kSensors.
enum class Sensor {
  zero_speed,
  tool_present,
  drawbar_open,
  drawbar_closed,
  air_pressure,
  rack_cover_opened,
  rack_cover_closed,
  at_speed,
  nut_seen,
};

/// What a sensor watches: a fact of the machine, which the dry run's
/// simulated rack (dry_run/simulator.cpp) holds true or false.
enum class Fact {
  spindle_still,
  tool_in_spindle,
  drawbar_released,
  air,
  cover_open,
  spindle_at_speed,
  nut_in_beam,  ///< a nut on the spindle cuts the tool-recognition beam where the nose stands
};

/// A sensor in the words of the config, the pins and their references.
struct SensorWords {
  const char* key;       ///< the config key that wires it: "sensors.zero_speed"
  const char* pin;       ///< its HAL input after `fixed_atc_probe.`
  const char* says;      ///< what it says when on, one line; `backticks` name keys and pins
  const char* pin_note;  ///< what the pin reference adds to that
};

struct SensorDeclaration {
  Sensor sensor;
  SensorWords words;
  Fact watches;
  bool on_when;  ///< it reads on while that fact holds (true) or while it does not
};

// clang-format off
/// In the order of their pins.
inline constexpr SensorDeclaration kSensors[] = {
  {Sensor::zero_speed,
   {"sensors.zero_speed", "zero-speed", "the spindle's zero-speed feedback",
    "; the chuck opens only with it on"},
   Fact::spindle_still, true},
  {Sensor::tool_present,
   {"sensors.tool_present", "tool-present", "a tool is clamped in the spindle", ""},
   Fact::tool_in_spindle, true},
  {Sensor::drawbar_open,
   {"sensors.drawbar_open", "drawbar-open", "the drawbar is released", ""},
   Fact::drawbar_released, true},
  {Sensor::drawbar_closed,
   {"sensors.drawbar_closed", "drawbar-closed", "the drawbar is clamped", ""},
   Fact::drawbar_released, false},
  {Sensor::air_pressure,
   {"sensors.air_pressure", "air-pressure-ok", "the drawbar has its air", ""},
   Fact::air, true},
  {Sensor::rack_cover_opened,
   {"rack_cover.opened_sensor", "rack-cover-opened", "the cover is open", ""},
   Fact::cover_open, true},
  {Sensor::rack_cover_closed,
   {"rack_cover.closed_sensor", "rack-cover-closed", "the cover is closed", ""},
   Fact::cover_open, false},
  {Sensor::at_speed,
   {"sensors.at_speed", "spindle-at-speed", "the spindle turns at the speed asked for",
    " (net it with the signal of `spindle.0.at-speed`); a collet-nut changer plunges only with "
    "it on, else after `chuck.spindle_ramp_seconds`"},
   Fact::spindle_at_speed, true},
  {Sensor::nut_seen,
   {"chuck.recognition", "nut-seen", "the tool-recognition sensor's beam is cut by a nut",
    " (a beam that reads on when clear: its driver's `-not` pin); read at `chuck.recognition`'s "
    "two heights"},
   Fact::nut_in_beam, true},
};

/// One sensor for each pocket `sensors.pocket_occupancy` names, N its number.
inline constexpr SensorWords kPocketSensor = {
  "sensors.pocket_occupancy", "pocket-occupied-N", "pocket N holds a tool",
  "; one pin per pocket of `pockets`, N the pocket's number (not its tool's)"};
// clang-format on

inline constexpr std::size_t kSensorCount = std::size(kSensors);

constexpr std::size_t index(Sensor sensor) { return static_cast<std::size_t>(sensor); }

constexpr bool in_enum_order() {
  for (std::size_t i = 0; i < kSensorCount; ++i) {
    if (index(kSensors[i].sensor) != i) return false;
  }
  return true;
}
static_assert(in_enum_order(), "kSensors is indexed by Sensor");

constexpr const SensorDeclaration& declared(Sensor sensor) { return kSensors[index(sensor)]; }

/// The sensor's key lies in the config object `object` ("sensors", "rack_cover").
inline bool keyed_in(const SensorDeclaration& sensor, const std::string& object) {
  return std::string(sensor.words.key).rfind(object + ".", 0) == 0;
}

/// "pocket-occupied-5": the pin of pocket `pocket`'s sensor without the
/// component; "1 2 5" names several, for a message.
inline std::string pocket_pin(const std::string& pocket) {
  std::string pin = kPocketSensor.pin;
  return pin.replace(pin.size() - 1, 1, pocket);
}
inline std::string pocket_pin(int pocket) { return pocket_pin(std::to_string(pocket)); }

/// Which optional sensors are wired (config.json's `sensors` and
/// `rack_cover`); each is read from its HAL input only when it is.
struct SensorConfig {
  std::bitset<kSensorCount> bits;  ///< by Sensor
  std::set<int> pocket_occupancy;  ///< pockets with a sensor of their own

  bool wired(Sensor sensor) const { return bits.test(index(sensor)); }
  void wire(Sensor sensor, bool on) { bits.set(index(sensor), on); }
  bool any() const { return bits.any() || !pocket_occupancy.empty(); }
  bool pocket(int number) const { return pocket_occupancy.count(number) != 0; }
};

}  // namespace fatc
