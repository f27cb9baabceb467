#pragma once

#include <optional>
#include <string>
#include <vector>

#include "changer.hpp"

namespace fatc {

/// One thing the changer did, in order: a step, a chuck change, a dwell, a message.
struct Record {
  enum class Kind { step, chuck, dwell, message, save } kind = Kind::step;
  Step step;
  bool chuck_open = false;
  double seconds = 0.0;
  MessageKind message_kind = MessageKind::info;
  std::string text;
  ToolState saved;  ///< for a save
};

std::string describe(const Record& record);

/// Ports that record everything and an executor that finishes every step at
/// once: what `--plan` prints and what the unit tests read. Probe moves touch
/// at `sensor_z` (or miss when it is unset); operator waits are answered by
/// the caller.
class Simulator : public Ports {
 public:
  std::vector<Record> records;
  std::optional<double> sensor_z;
  bool chuck_open = false;
  bool timer_armed = false;
  std::optional<Step> pending;  ///< last published step not yet finished
  std::vector<std::string> unexpected_events;

  void publish(const Step& step) override;
  void set_chuck_open(bool open) override;
  void start_timer(double seconds) override;
  void cancel_timer() override;
  void tell(MessageKind kind, const std::string& text) override;
  void save(const ToolState& state) override;
  void unexpected(const std::string& state, const std::string& event) override;

  /// Finishes steps and runs out timers until the changer waits for something
  /// else (operator, spindle) or a sequence ends. Returns how many events it fed.
  int run(Changer& changer, int limit = 1000);

  std::vector<Step> steps() const;
  std::vector<Step> motion_steps() const;
  std::vector<std::string> messages(MessageKind kind) const;
  int saves = 0;
};

}  // namespace fatc

namespace fatc {

/// The records of M6 T`to` with `from` in the spindle, every other pocket full;
/// the operator continues at every wait (manual tools) and the sensor, when
/// `probe_after_change` asks for it, touches at `sensor_z`.
Simulator plan_change(const Config& config, int from, int to, double sensor_z);
/// The records of loading `tool` by hand with `from` in the spindle; the operator
/// continues at every wait and the sensor touches at `sensor_z`.
Simulator plan_load(const Config& config, int tool, int from, double sensor_z);
/// The records of unloading `tool` with `from` in the spindle; the operator continues.
Simulator plan_unload(const Config& config, int tool, int from);

}  // namespace fatc
