#pragma once

// The I/O check of a newly wired machine: each sensor beside what it should
// read now and why, each output the changer drives driven once by the
// operator (or refused, with the reason), and how long its sensor took to
// answer. A rule of words: it reads the changer's belief and changes nothing;
// the component drives the outputs and times them (linuxcnc/live/io_check_driver).

#include <cstddef>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "../config/config.hpp"
#include "../motion/point.hpp"
#include "sensors.hpp"
#include "tool_state.hpp"

namespace fatc {

/// An output the I/O check drives once.
enum class IoAction { chuck_release, chuck_clamp, cover_open, cover_close, air_blast };

/// The outputs the changer drives: `chuck`, `rack-cover-open`, `air-blast`.
enum class IoOutput { chuck, cover, air_blast };

struct IoActionDeclaration {
  IoAction action;
  const char* name;  ///< `--operator io:NAME`
  const char* pin;   ///< its button, after `fixed_atc_probe.`
  IoOutput output;   ///< the output it drives
  bool on;           ///< to on (open, blowing) or off
};

// clang-format off
/// In the order of their pins (linuxcnc/live/pin_list.hpp).
inline constexpr IoActionDeclaration kIoActions[] = {
  {IoAction::chuck_release, "chuck-release", "io-check-chuck-release", IoOutput::chuck,     true},
  {IoAction::chuck_clamp,   "chuck-clamp",   "io-check-chuck-clamp",   IoOutput::chuck,     false},
  {IoAction::cover_open,    "cover-open",    "io-check-cover-open",    IoOutput::cover,     true},
  {IoAction::cover_close,   "cover-close",   "io-check-cover-close",   IoOutput::cover,     false},
  {IoAction::air_blast,     "air-blast",     "io-check-air-blast",     IoOutput::air_blast, true},
};
// clang-format on
inline constexpr std::size_t kIoActionCount = std::size(kIoActions);

constexpr bool io_actions_in_enum_order() {
  for (std::size_t i = 0; i < kIoActionCount; ++i) {
    if (static_cast<std::size_t>(kIoActions[i].action) != i) return false;
  }
  return true;
}
static_assert(io_actions_in_enum_order(), "kIoActions is indexed by IoAction");

constexpr const IoActionDeclaration& declared(IoAction action) {
  return kIoActions[static_cast<std::size_t>(action)];
}

/// The sensors that watch `output`: what the changer must not see move while
/// the I/O check holds it otherwise than the changer commanded (its belief
/// stays its own). The air blast may dip the drawbar's air.
std::vector<Sensor> io_sensors_watching(IoOutput output);

/// How long the I/O check's air blast lasts: no sensor answers it, the
/// operator hears and feels it at the taper, which takes about a second.
inline constexpr double kIoAirBlastSeconds = 1.0;

/// The action `name` names ("chuck-release"), if any.
std::optional<IoAction> io_action_named(const std::string& name);
const char* io_action_name(IoAction action);

/// What the I/O check judges by: the changer's belief, the outputs as last
/// commanded (by the changer or by the I/O check), and what LinuxCNC says.
struct IoFacts {
  ToolState tools;              ///< the changer's belief; never changed here
  bool chuck_open = false;      ///< the `chuck` output as last commanded
  bool cover_open = false;      ///< `rack-cover-open` as last commanded
  bool air_blast = false;       ///< `air-blast` as last commanded
  bool spindle_stopped = true;  ///< LinuxCNC has the spindle off (`spindle-stopped`)
  bool machine_on = false;      ///< `machine-on`
  bool homed = false;           ///< `all-homed`: where the spindle stands is known
  /// Why nothing may be driven now for the changer's sake: a program or MDI
  /// runs, a sequence is under way, a G-code release holds the chuck.
  std::optional<std::string> busy;
  std::optional<Point> nose;  ///< where the spindle nose stands, machine coordinates
  double tool_length = 0.0;   ///< how far the spindle's tool hangs below the nose
  bool holding_tool = false;  ///< the operator holds the tool in the spindle and says so
};

/// One sensor as the I/O check shows it.
struct IoSensorLine {
  std::string pin;               ///< after `fixed_atc_probe.`
  bool value = false;            ///< what it reads
  std::optional<bool> expected;  ///< unset: either is right now
  std::string why;               ///< why it should read that: "the chuck is clamped"
  bool agrees() const { return !expected || *expected == value; }
  /// "drawbar-closed: on, expected on (the chuck is clamped)".
  std::string words() const;
};

/// Each wired sensor, in the order of kSensors, then the pocket sensors.
std::vector<IoSensorLine> io_sensor_lines(const Config& config, const SensorReadings& read,
                                          const IoFacts& facts);

/// Why `action` may not be driven now, or nothing.
std::optional<std::string> io_refusal(IoAction action, const Config& config,
                                      const SensorReadings& read, const IoFacts& facts);

/// The spindle (with its tool) stands in the rack's volume, where the cover
/// closes: the part's pocket nearest to it, else 0.
int io_pocket_under_spindle(const Config& config, const Point& nose, double tool_length);

/// How long `action`'s sensors may take to answer, and the key that says so.
struct IoTimeout {
  double seconds = 0.0;
  std::string key;
};
/// Nothing when no wired sensor answers `action`.
std::optional<IoTimeout> io_timeout(IoAction action, const Config& config);
/// `action`'s sensors read what it drove: the drawbar open, the cover closed.
bool io_answered(IoAction action, const Config& config, const SensorReadings& read);

/// A wait this much of its timeout earns a warning: the valve or the cover
/// has less margin left than a cold morning or a low compressor takes away.
inline constexpr double kIoSlowShare = 0.5;

/// How the output answered: `seconds` its sensor took, unset when it did not
/// answer within its timeout. "drawbar opened in 0.18 s; your timeout 1.0 s
/// (sensor_timeout_seconds)", with a warning past kIoSlowShare of it; for an
/// output no wired sensor answers, what was driven and that nothing timed it.
std::string io_timing_words(IoAction action, const Config& config, std::optional<double> seconds,
                            const SensorReadings& read);

}  // namespace fatc
