#pragma once

#include <memory>
#include <optional>
#include <string>

#include "../config/config.hpp"
#include "../rack/geometry.hpp"
#include "../rack/sensors.hpp"
#include "../rack/tool_state.hpp"
#include "base/events.hpp"
#include "base/ports.hpp"
#include "base/rehearsal.hpp"
#include "base/status.hpp"
#include "flows/flows.hpp"

namespace fatc {

namespace machine {
class Engine;
}

/// The tool changer: a Boost.MSM state machine behind plain calls, one per
/// event; every decision is a row of its tables. It never touches the world
/// except through Ports.
class Changer {
 public:
  Changer(const Config& config, Ports& ports, ToolState tools);
  ~Changer();
  Changer(const Changer&) = delete;
  Changer& operator=(const Changer&) = delete;

  void ready();
  void not_ready();
  /// The running machine's soft limits: every move is checked against them
  /// and the rack keep-out before it is published.
  void soft_limits(std::optional<SoftLimits> limits);
  /// Planning only: publish every move, safe or not, so that a plan shows all.
  void plan_only();
  /// Planning only: the spindle stands at `at`, on the axes `known`.
  void start_at(const Point& at, unsigned known);
  /// The tool lengths every move is checked with (LinuxCNC's tool table,
  /// the longest the config allows).
  void keepout_lengths(ToolLengths lengths);
  const ToolLengths& keepout_lengths() const;
  /// Every request the changer could take is first run on a copy by
  /// `rehearsal` (which must outlive the changer), and refused where a move
  /// of its sequence would break the keep-out or the soft limits.
  void rehearse_with(const Rehearsal* rehearsal);
  /// Where LinuxCNC says the spindle stands (none: not known); a rehearsal starts there.
  void machine_at(std::optional<Point> at);
  /// Step by step (the step-by-step pin): from the next sequence on, each
  /// move and each chuck action waits for Continue before it goes out;
  /// Cancel there aborts the sequence.
  void step_by_step(bool on);
  /// Whether task could run the executor over MDI now; `why_busy` says why not.
  void task_availability(std::optional<std::string> why_busy);
  /// The spindle started (false) or stopped (true) turning.
  void spindle_stopped(bool stopped);
  /// What the optional sensors read now; only the wired ones are looked at.
  void sensors(const SensorReadings& readings);
  void tool_change(int tool);
  /// Load `tool` by hand into `pocket` (0: its own, else the nearest free one).
  void load(int tool, int pocket = 0);
  void unload(int tool);
  /// Measure all: fetch, measure and put back each of `tools` in the rack, in order.
  void measure_all(std::vector<int> tools);
  /// A dry run through pocket `pocket`'s approach, held at each waypoint.
  void verify(int pocket);
  /// A chuck atom from G-code; `at`: where the machine stands, if known.
  void chuck(ChuckRequest::Action action, std::optional<Point> at);
  /// Any flow's request, as the calls above make it.
  void request(const machine::FlowRequest& request);
  void in_position();
  void command_done();
  void probe_result(bool touched, double machine_z, bool tripped_before = false);
  void timer_elapsed();
  void operator_continue();
  void operator_cancel();
  void abort(const std::string& reason);
  /// Why teaching cannot start now, in the words after "teach T refused: ",
  /// or nothing if it can: only while idle and accepting (task free, the
  /// chuck clamped), with LinuxCNC's status read (`linuxcnc_status`) and a
  /// machine position (`at`) in it.
  std::optional<std::string> why_not_teach(bool linuxcnc_status,
                                           const std::optional<Point>& at) const;
  /// A taught config (ConfigChanged): the changer works with it from the next
  /// request on. Taken only while idle; otherwise refused with one message
  /// naming `request` ("teach safe"). Says whether it was taken.
  bool reconfigure(Config config, std::string request);
  /// The operator's confirmation after a fault: what the spindle holds and,
  /// if a sequence was cut off at a pocket, whether that pocket holds its tool.
  void clear_fault(int spindle_tool, std::optional<bool> pocket_holds_tool = std::nullopt);
  /// The operator checked the rack by other means and lifts the datum's
  /// refusal (clear-datum-drift): the drift found and the changes counted are
  /// forgotten, the pockets keep their positions. Why it cannot, if it cannot.
  std::optional<std::string> clear_datum_drift();
  /// Why the rack datum refuses M6 now (a drift found, a check due), if it does.
  std::optional<std::string> datum_refusal() const;
  /// What was under way when the changer last stopped or faulted, if anything.
  const std::optional<InProgress>& cut_off() const;

  /// Computed from the machine's flags on each call.
  Status status() const;
  const ToolState& tools() const;
  /// The config the changer works with (its own copy).
  const Config& config() const;
  /// How many taught configs it has taken since it started.
  unsigned configs_taken() const;

  /// The state machine as Graphviz, generated from the transition tables.
  static std::string dot();

 private:
  std::unique_ptr<machine::Engine> engine_;
};

}  // namespace fatc
