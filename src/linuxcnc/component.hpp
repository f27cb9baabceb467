#pragma once

#include <chrono>
#include <map>
#include <optional>
#include <string>

#include "core/changer.hpp"
#include "core/ports.hpp"

namespace fatc::linuxcnc {

struct HalPins;
class NmlLink;

/// The adapter between HAL and the changer: turns pin edges, the step
/// executor's handshake and the clock into events, and steps, chuck and
/// timers into pins. One poll() per loop turn.
class Component : public Ports {
 public:
  using Clock = std::chrono::steady_clock;

  /// `nml` may be null (no LinuxCNC task, as under halrun).
  Component(HalPins* pins, const Config& config, std::string state_path, NmlLink* nml);
  void attach(Changer* changer) {
    changer_ = changer;
    last_lengths_ = changer->tools().lengths;
  }
  /// `interpreter_idle`: LinuxCNC's interpreter state, when NML is available.
  void poll(Clock::time_point now, std::optional<bool> interpreter_idle);
  /// Whether the next poll should come soon: a sequence runs or a handshake is open.
  bool active() const;

  void publish(const Step& step) override;
  void set_chuck_open(bool open) override;
  void start_timer(double seconds) override;
  void cancel_timer() override;
  void tell(MessageKind kind, const std::string& text) override;
  void save(const ToolState& state) override;
  void unexpected(const std::string& state, const std::string& event) override;

 private:
  void serve_executor();
  void serve_operator();
  void start_executor_if_needed();
  /// Why task cannot run the executor over MDI now, or nothing if it can.
  std::optional<std::string> why_task_busy() const;
  void watch_for_abort(std::optional<bool> interpreter_idle);
  void abort(const std::string& reason);
  void drop_executor();
  void offer(const Step& step);
  void offer_pending_if_asked();
  void show_status();

  HalPins* pins_;
  NmlLink* nml_;
  std::string state_path_;
  Changer* changer_ = nullptr;
  Clock::time_point now_;
  std::optional<Clock::time_point> deadline_;
  std::optional<Step> pending_;    ///< published, not yet on the pins
  std::optional<Step> offered_;    ///< on the pins, step-ready high
  std::optional<Step> executing_;  ///< taken by the executor, not yet finished
  std::optional<bool> machine_ready_;
  bool last_request_ = false;
  bool last_abort_ = false;
  bool last_clear_ = false;
  std::optional<Clock::time_point> idle_since_;  ///< interpreter idle while a sequence runs
  std::optional<Clock::time_point> starting_until_;  ///< an MDI run of the executor was asked for
  bool executor_attached_ = false;  ///< an executor runs and expects more steps
  std::optional<bool> interpreter_idle_;
  bool last_load_ = false;
  bool last_unload_ = false;
  bool last_continue_ = false;
  bool last_cancel_ = false;
  std::map<int, double> last_lengths_;
};

}  // namespace fatc::linuxcnc
