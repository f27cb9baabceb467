#pragma once

#include <array>
#include <chrono>
#include <optional>
#include <string>

#include "core/machine/base/ports.hpp"
#include "core/rack/io_check.hpp"
#include "io/status_file.hpp"

namespace fatc::linuxcnc {

struct HalPins;

/// The component's side of the I/O check (core/rack/io_check.hpp): the
/// `io-check-*` buttons drive an output once, each refused with the reason
/// where unsafe, and its sensor's answer is timed. The changer's outputs pass
/// through here (changer_sets), so that the pins show the I/O check's command
/// while it holds an output, and the changer's again as soon as it commands
/// one, starts a sequence, a program runs or the machine goes off. Meanwhile
/// the changer sees the sensors of a held output as they were (seen_by_changer):
/// nothing the I/O check does changes its belief or faults it.
class IoCheckDriver {
 public:
  using Clock = std::chrono::steady_clock;

  explicit IoCheckDriver(HalPins* pins) : pins_(pins) {}

  /// The changer commands `output`: it takes it back from the I/O check.
  void changer_sets(IoOutput output, bool on);
  /// What the changer may see of `read`: the sensors of a held output as they
  /// were when the I/O check took it.
  SensorReadings seen_by_changer(const SensorReadings& read);
  /// One poll: the buttons read, the outputs driven, the answers timed.
  /// `facts`: the changer's belief and the machine, the outputs left to this.
  void poll(Clock::time_point now, const Config& config, const SensorReadings& read, IoFacts facts,
            Ports& ports);
  /// The I/O check holds the chuck open: motion and the spindle are held
  /// as for a G-code release (`chuck-held`).
  bool holds_chuck_open() const {
    return outputs_[static_cast<std::size_t>(IoOutput::chuck)].held.value_or(false);
  }
  /// An output's answer is being timed: the next poll should come soon.
  bool timing() const { return timing_.has_value(); }
  /// What the status file shows of it.
  const io::StatusFile::IoCheckWords& words() const { return words_; }

 private:
  struct Output {
    bool changer = false;      ///< as the changer last commanded it
    std::optional<bool> held;  ///< as the I/O check commands it, while it holds it
  };
  /// An action driven, waiting for its sensors to answer.
  struct Timing {
    IoAction action;
    Clock::time_point began;
    std::optional<Clock::time_point> deadline;  ///< none: no wired sensor answers it
  };

  Output& output(IoOutput which) { return outputs_[static_cast<std::size_t>(which)]; }
  bool on(IoOutput which) const {
    const Output& o = outputs_[static_cast<std::size_t>(which)];
    return o.held.value_or(o.changer);
  }
  bool holds_any() const;
  void write_pins();
  void drive(IoAction action, Clock::time_point now, const Config& config,
             const SensorReadings& read, Ports& ports);
  /// Every held output back to the changer's command, saying why.
  void give_back(const std::string& why, Ports& ports);

  HalPins* pins_;
  std::array<Output, 3> outputs_{};
  std::array<bool, kIoActionCount> pressed_{};
  SensorReadings seen_;    ///< what the changer saw last
  SensorReadings frozen_;  ///< what it saw when the I/O check took each held output
  std::optional<Timing> timing_;
  std::optional<Clock::time_point> air_off_at_;
  io::StatusFile::IoCheckWords words_;
};

}  // namespace fatc::linuxcnc
