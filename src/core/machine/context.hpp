#pragma once

#include <optional>
#include <string>

#include "../config.hpp"
#include "../ports.hpp"
#include "../status.hpp"
#include "../tool_state.hpp"

namespace fatc {

/// What every state of the machine shares: the validated config, the ports
/// to the world, the tool state and the request being served.
class Context {
 public:
  Context(const Config& config, Ports& ports, ToolState tools)
      : config(config), ports(ports), tools(std::move(tools)) {}

  const Config& config;
  Ports& ports;
  ToolState tools;
  Status status;

  int requested_tool = 0;      ///< the tool the current request is about
  bool machine_ready = false;  ///< latest Ready/NotReady
  bool spindle_stopped = true; ///< latest spindle report
  int flush_pulses_done = 0;
  double first_touch_z = 0.0;  ///< where the fast probing stage touched
  double latched_z = 0.0;      ///< where the slow probing stage touched
  std::string fault_reason;
  std::string stop_reason;     ///< why an M6 stops its program without a fault
  Point position;              ///< where the last published moves lead
  unsigned known_axes = 0;     ///< which axes of `position` are known
  bool at_safe() const;

  void publish(const Step& step);
  void open_chuck(const std::string& where);
  void close_chuck();
  void wait(double seconds, const std::string& activity);
  void ask_operator(const std::string& prompt);
  void tell(MessageKind kind, const std::string& text) { ports.tell(kind, text); }

  void record_in_spindle(int tool);
  void record_in_pocket(int tool);
  void record_out_of_machine(int tool);
  void record_length(int tool, double length);

  /// Where the tools are, in words, for messages after a cancel or a fault.
  std::string whereabouts() const;
};

/// Why M6 to `tool` cannot start now, or nothing if it can.
std::optional<std::string> why_not_change(const Context& ctx, int tool);
/// Why loading tool `tool` by hand cannot start now, or nothing if it can.
std::optional<std::string> why_not_load(const Context& ctx, int tool);
/// Why unloading tool `tool` cannot start now, or nothing if it can.
std::optional<std::string> why_not_unload(const Context& ctx, int tool);

}  // namespace fatc
