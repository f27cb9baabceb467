#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "../../config/config.hpp"
#include "../../config/measuring.hpp"
#include "../../motion/step.hpp"
#include "../../plan/routes.hpp"
#include "../../rack/geometry.hpp"
#include "../../rack/sensors.hpp"
#include "../../rack/tool_state.hpp"
#include "events.hpp"
#include "ports.hpp"
#include "prompt.hpp"
#include "rehearsal.hpp"
#include "step_gate.hpp"

namespace fatc {

/// The request being served.
struct RequestServed {
  int tool = 0;  ///< the tool the current request is about
  /// The flow under way runs inside a G-code program (M6, a chuck atom): the
  /// operator's answers hold the program, and only LinuxCNC's Stop ends a probe.
  bool in_program = false;
};

/// What LinuxCNC says of the machine; the adapter keeps it current.
struct MachineFacts {
  bool ready = false;           ///< latest Ready/NotReady
  bool spindle_stopped = true;  ///< LinuxCNC's spindle is off (`spindle-stopped`)
  /// Why task cannot run the executor over MDI now (a program runs, no NML), if it cannot.
  std::optional<std::string> task_busy;
  /// The running machine's soft limits, when the adapter knows them.
  std::optional<SoftLimits> limits;
  /// Where LinuxCNC says the spindle stands, when the adapter knows: a
  /// rehearsal starts there (a sequence of its own starts from nowhere
  /// known, begin_sequence, and is checked move by move as it goes).
  std::optional<Point> position;
};

/// The moves: where the published ones lead, and what each is checked with.
struct Motion {
  Point position;           ///< where the last published moves lead
  unsigned known_axes = 0;  ///< which axes of `position` are known
  Step step;                ///< the last published step
  /// Steps taken in the current sequence (moves, chuck actions, dwells),
  /// numbered as --plan prints them; 0 between sequences.
  int sequence_step = 0;
  /// Off only for planning (--check, --plan), which reports every violation of
  /// a whole sequence instead of stopping at the first.
  bool check_moves = true;
  /// The lengths every move is checked with: a tool the spindle holds hangs
  /// that far below the nose.
  ToolLengths keepout_lengths;
  /// Runs a request on a copy before it is taken, where set: its whole
  /// sequence is checked before anything moves.
  const Rehearsal* rehearsal = nullptr;
};

/// The outputs the changer drives, as last commanded.
struct Outputs {
  bool chuck_open = false;
  bool cover_open = false;    ///< the rack cover
  bool cover_settled = true;  ///< an unsensed cover has had `rack_cover.seconds` to move
  /// The changer commanded the cover closed after its last sequence and waits
  /// for its closed sensor (Operating's ComparingSensors clears it on exit).
  bool cover_closing = false;
  /// The speed the changer turns the spindle at (collet nut), signed; 0: it does not.
  double spindle_rpm = 0.0;
};

/// What the status view shows of the work under way, beside the machine's flags.
struct Activity {
  std::string dwell;                  ///< what the running timer waits for
  Prompt prompt;                      ///< the last question put to the operator
  /// The last length a probe measured, for the status: flows take it from
  /// their probing leg.
  std::optional<double> last_length;
  /// Why the changer is in fault: a flow's failure (FlowFailed), a refused
  /// step, a failed check, an abort.
  std::string fault_reason;
  /// Why a flow stopped early of its own, not as a fault (a touch that found
  /// nothing): its end makes the executor fail saying so.
  std::string stopped;
};

/// Events a part raises in the machine, each queued behind the current event
/// (the Engine sets them).
struct Raise {
  /// UnsafeStep: a move was refused.
  std::function<void(const std::string&)> unsafe_step;
  /// CheckFailed: a sensor check failed.
  std::function<void(const CheckFailed&)> check_failed;
  /// SensorReport: a state that waits for a sensor looks at it once on entry this way.
  std::function<void()> sensor_report;
};

/// What every state of the machine shares, in its parts: the validated
/// config, the ports to the world, the tool state, the request being served,
/// what LinuxCNC and the sensors say, the moves, the outputs and what the
/// status shows. An action names the part it touches.
class Context {
 public:
  Context(Config config, Ports& ports, ToolState tools)
      : config(std::move(config)), ports(ports), tools(std::move(tools)) {}

  /// The machine's own copy: only a ConfigChanged taken while idle replaces
  /// it (take_config), so nothing changes under a running flow.
  Config config;
  Ports& ports;
  ToolState tools;
  RequestServed request;
  MachineFacts machine;
  Sensors sensors{config.sensors};  ///< the optional sensors: what they read, what that means
  Motion motion;
  Outputs outputs;
  Activity activity;
  Raise raise;
  StepGate steps;  ///< step by step: what waits for Continue before it goes out
  /// The rack datum was checked or taught since the component started
  /// (rack_touch.check_at_start asks for it once each start).
  bool datum_checked = false;

  /// A taught config: the changer works with it from the next request on.
  void take_config(Config taught) {
    config = std::move(taught);
    ++configs_taken_;
  }
  /// ConfigChanged events taken since the start.
  unsigned configs_taken() const { return configs_taken_; }

  void publish(const Step& step);
  /// Why `request`, made of a copy of this changer, would break the keep-out
  /// or the soft limits on the way; nothing if it would not, or no rehearsal is set.
  std::optional<std::string> rehearse(const std::function<void(Changer&)>& request) const;
  /// Where the spindle stands, as plan::phase walks a route from there.
  plan::Standing standing() const { return {motion.position, motion.known_axes}; }
  /// A phase walks `route`, as plan::phase made it from where the spindle
  /// stands: its first waypoint is published now, each following one when
  /// the one before is reached (next_waypoint).
  void walk(plan::Route route);
  /// The waypoint under way was reached: publishes the next one of the route
  /// walked and says true; false when the route is done, or none is walked.
  bool next_waypoint();
  /// The phase ended early (a fault, an abort): the rest of its route is dropped.
  void stop_walking();
  /// The chuck; with `air_blast`, the blast follows: on while the chuck is
  /// open at a pocket with the spindle empty.
  void open_chuck();
  void close_chuck();
  /// A collet nut: the spindle at `rpm` over the pocket served (forward > 0,
  /// reverse < 0, 0 stopped), asked of LinuxCNC by the executor. A start is
  /// held for Continue step by step; a stop never is.
  void turn_spindle(double rpm, std::string label);
  /// The changer no longer asks for the spindle, with no step: a fault or the
  /// machine off, where LinuxCNC's abort stops it and the guard holds it.
  void release_spindle();
  void wait(double seconds, std::string what);
  void ask_operator(const Prompt& question);
  /// Step by step, Continue: the held step goes out; false when none is held.
  bool continue_step();
  /// Step by step: the next move of a run split into steps is held; false
  /// when the run is through (the executor's InPosition is then the run's).
  bool hold_next_move();
  void tell(MessageKind kind, const std::string& text) { ports.tell(kind, text); }

  /// A sequence starts: saved before anything moves, cleared when it ends,
  /// so that a restart after a crash knows it was cut off, and where.
  void begin_sequence(const std::string& sequence);
  void record_progress(const std::string& step, int pocket);
  void end_sequence();
  /// The pocket the sequence under way serves (its last progress), 0 if none.
  int sequence_pocket() const { return tools.in_progress ? tools.in_progress->pocket : 0; }

  /// What `tool`'s measuring rule asks, with the length the changer has of it or not.
  Measuring measuring(int tool) const {
    return measuring_of(config, tool, tools.lengths.count(tool) != 0);
  }

  /// The pocket the tool in the spindle goes back to: its own, or, for a tool
  /// from outside the rack, its first-start pocket if that is free.
  std::optional<int> return_pocket(int tool) const;

  void record_in_spindle(int tool);
  /// `tool` sits in `pocket` now, which is its pocket from now on.
  void record_in_pocket(int tool, int pocket);
  /// `tool` left the machine: its pocket is free.
  void record_out_of_machine(int tool);
  void record_length(int tool, double length);

  /// Where the tools are, in words, for messages after a cancel or a fault.
  std::string whereabouts() const;

  // What the sensors say of the other parts (Sensors asks nothing else).
  /// The spindle stands still: LinuxCNC has it off (`spindle-stopped`) and
  /// its own feedback agrees where wired.
  bool spindle_at_standstill() const { return machine.spindle_stopped && sensors.spindle_still(); }
  /// The rack cover (`rack_cover`): commanded open or closed. Closing is
  /// not waited for here: SensorsAgree waits for its closed sensor.
  void open_cover();
  void close_cover();
  /// No cover, or it is open: its opened sensor on where wired, else it
  /// has had its `seconds`.
  bool cover_reads_open() const;
  /// The only disagreement is the cover the changer itself commanded closed
  /// after its last sequence: it is still on its way (its closed sensor off,
  /// at most `rack_cover.timeout_seconds`). A request waits for it; a cover
  /// that reads open otherwise refuses requests.
  bool cover_still_closing() const;
  /// Where the sensors contradict the tool state (or the rack cover its
  /// command), one phrase each.
  std::vector<std::string> disagreements() const;
  /// Waits up to `seconds` for a sensor (TimerElapsed if it does not come);
  /// `what` is what the activity shows meanwhile.
  void await_sensor(double seconds, std::string what);
  /// A sensor check failed: the changer faults saying `reason` (once the
  /// current event is through); `uncertain`: what the spindle holds is no
  /// longer a fact.
  void fail_check(std::string reason, bool uncertain);

 private:
  void blow_if_due();
  /// Step by step: holds `go` (step `number`, `action` `where`, at `at` on
  /// `axes`) for Continue and says true; false when the mode is off.
  bool stop_before(int number, std::string action, std::string where, const Point& at,
                   unsigned axes, std::function<void()> go);
  /// A chuck action (open or close), held for Continue in step by step.
  void chuck(bool open);
  unsigned configs_taken_ = 0;
  plan::Route route_;           ///< the waypoints the phase under way walks
  std::size_t route_next_ = 0;  ///< the index of the waypoint to publish next
  bool blowing = false;
};

}  // namespace fatc
