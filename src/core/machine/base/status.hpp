#pragma once

#include <optional>
#include <string>

namespace fatc {

/// Which flow the changer is in; the value of the `state` pin.
enum class Phase {
  not_ready = 0,
  idle = 1,
  changing = 2,
  loading = 3,
  unloading = 4,
  fault = 5,
  measuring = 6,  ///< measure all
  verifying = 7,  ///< a dry run through one pocket's approach
  chuck = 8,      ///< a chuck atom from G-code releases or clamps the chuck
  air_run = 9,    ///< a sequence flown above the rack, nothing taken or recorded
  touching = 10,  ///< the probe in the spindle touches the rack: teaching by touch, the datum
};

/// The phase in words ("changing"), as the status file shows it.
const char* phase_word(Phase phase);

/// What the changer waits for now; the value of the `awaiting` pin.
enum class Awaiting {
  nothing = 0,
  motion = 1,  ///< the executor performs a move or a command
  probe = 2,
  timer = 3,
  spindle = 4,
  operator_choice = 5,
  sensor = 6,  ///< a wired sensor must confirm a change (drawbar, tool, air, the rack at rest)
};

/// What the changer shows the world. Computed from the state machine's flags
/// each time it is asked for, never stored, so it cannot drift from the machine.
struct Status {
  Phase phase = Phase::not_ready;
  Awaiting awaiting = Awaiting::nothing;
  std::string activity;            ///< what it is doing, in the machinist's words
  /// An operator wait inside M6, or a step held step by step: the executor holds the program.
  bool holds_program = false;
  bool probe_cancellable = false;  ///< a load-flow probe runs over MDI: Cancel stops it
  /// The flow under way is an operator's (load, unload, measure all, verify):
  /// its executor runs over MDI, started by the adapter, not inside a program.
  bool over_mdi = false;
  bool accepting = false;  ///< idle, and task is free for a load or unload
  /// A chuck atom released the chuck and it stays open: motion and the
  /// spindle must wait for the clamp (the `chuck-held` pin).
  bool chuck_held = false;
  /// The changer turns the spindle for the step under way (a collet nut
  /// screwed over its pocket): `changer-spindle`, the only time the spindle
  /// guard lets it turn while the changer is busy.
  bool turns_spindle = false;
  std::optional<double> last_length;  ///< the last tool length measured
  int step_number = 0;  ///< the step of the sequence under way, as --plan numbers it; 0 none
  int pocket = 0;       ///< the pocket being served, 0 none
  int batch_done = 0;   ///< measure all: tools measured (or tried) so far
  int batch_total = 0;  ///< measure all: tools it measures; 0 when none runs
  /// A probe (`tools.N.kind`) that is, or after a cut-off sequence may be, in
  /// the spindle: the spindle is held (`probe-in-spindle`); 0 none.
  int spindle_probe = 0;
  /// The tool the change is about (else the spindle's) and its rule, for the
  /// panel: "T3 checked ±0.05", "T99 probe, spindle held, measured if new"; empty: none.
  std::string rule;

  /// A flow runs: every phase but these three is a flow's.
  bool busy() const {
    return phase != Phase::not_ready && phase != Phase::idle && phase != Phase::fault;
  }
  bool awaits_operator() const { return awaiting == Awaiting::operator_choice; }
  /// The changer's own moves run into the rack: the keep-out of every motion
  /// is lifted for them. Not for an air run, which stays out of the rack as
  /// any motion does.
  bool moves_into_rack() const { return busy() && phase != Phase::air_run; }
};

}  // namespace fatc
