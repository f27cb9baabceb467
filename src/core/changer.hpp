#pragma once

#include <memory>
#include <string>

#include "config.hpp"
#include "ports.hpp"
#include "status.hpp"
#include "tool_state.hpp"

namespace fatc {

namespace machine {
class Engine;
}

/// The tool changer: a Boost.MSM state machine behind plain calls, one per
/// event. It never touches the world except through Ports.
class Changer {
 public:
  Changer(const Config& config, Ports& ports, ToolState tools);
  ~Changer();
  Changer(const Changer&) = delete;
  Changer& operator=(const Changer&) = delete;

  void ready();
  void not_ready();
  void tool_change(int tool);
  void load(int tool);
  void unload(int tool);
  void in_position();
  void probe_result(bool touched, double machine_z, bool tripped_before = false);
  void timer_elapsed();
  /// Level: whether the spindle stands still now.
  void spindle_stopped(bool stopped);
  void operator_continue();
  void operator_cancel();
  void abort(const std::string& reason);
  void clear_fault(int spindle_tool);

  const Status& status() const;
  const ToolState& tools() const;
  bool is_machine_ready() const;

  /// The state machine as Graphviz, generated from the transition tables.
  static std::string dot();

 private:
  std::unique_ptr<machine::Engine> engine_;
};

}  // namespace fatc
