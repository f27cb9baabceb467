#pragma once

#include "../motion/point.hpp"

namespace fatc {

class Simulator;

/// What the machine's motion can do, in the config's units: per second
/// ([AXIS_x]MAX_VELOCITY, [TRAJ]MAX_LINEAR_VELOCITY) and per second squared
/// (MAX_ACCELERATION, [TRAJ]MAX_LINEAR_ACCELERATION).
struct MotionLimits {
  Point velocity;
  Point acceleration;
  double linear_velocity = 0.0;
  double linear_acceleration = 0.0;
};

// What the changer and LinuxCNC add to a change besides its moves and dwells,
// measured on the real LinuxCNC (linuxcnc-uspace 2.9, [TASK]CYCLE_TIME 1 ms)
// by four runs of scripts/bench_estimate.sh: tests/bench/changes.ngc, chip to
// chip, on the simulated mill on both paths, slowed to the gantry sample's
// limits, and with [EMCIO]CYCLE_TIME 0.01 s; 60 changes, 746 steps.

/// What the changer adds to each step its executor performs, in seconds: the
/// handshake (request, step published, taken back) and LinuxCNC's queue
/// running dry before it (M66 waits for motion to end). Measured as the
/// machine's standing still between two moves with nothing between them:
/// median 16.8 ms over the 746 steps (scripts/bench_changes.sh: 16 ms).
constexpr double kStepSeconds = 0.017;

/// iocontrol's cycles in a change, each [EMCIO]CYCLE_TIME long: T's prepare
/// and M6's change, each waiting for iocontrol to take it and to answer.
/// Measured: the changes took 0.41 s less each with CYCLE_TIME 0.01 s than
/// with 0.1 s (the medians of what they took beyond their moves, dwells and
/// steps: 0.12 s over 5 changes, 0.53 s over 55), 4.5 cycles of 0.09 s.
constexpr double kIocontrolCycles = 4.5;

/// [EMCIO]CYCLE_TIME where the INI gives none: LinuxCNC's default, in seconds.
constexpr double kIocontrolCycleSeconds = 0.1;

/// What else a change costs, in seconds: the remap's entry (M5, M70, the
/// sync, the executor's call) and exit (M72, G43). Measured: what the changes
/// took beyond their moves, dwells, steps and iocontrol's cycles, 0.074 s at
/// CYCLE_TIME 0.01 s and 0.076 s at 0.1 s (medians as above).
constexpr double kChangeSeconds = 0.075;

/// Standing still to standing still over `distance`: accelerate, cruise,
/// decelerate; a triangle when it never reaches `velocity`. 0 for no
/// distance, and for a velocity or acceleration that is not positive.
double trapezoid_seconds(double distance, double velocity, double acceleration);

/// The least time a straight move takes that starts and ends standing
/// still: a trapezoidal profile at the slowest of the limits of the axes it
/// moves (along its direction) and the linear ones, and at most
/// `feed_per_minute` (0: a rapid, no feed).
double move_seconds(const Point& from, const Point& to, double feed_per_minute,
                    const MotionLimits& limits);

/// The limits LinuxCNC's trajectory planner (linuxcnc-uspace 2.9) gives the
/// executor's moves, each an exact stop (G61.1): the velocities and the
/// axes' full accelerations. [TRAJ]MAX_LINEAR_ACCELERATION bounds no
/// straight move (canon takes the axes' alone). Under G64, LinuxCNC's
/// default, a move that may blend gets half of each (tc.c,
/// tcGetOverallMaxAccel), though nothing follows it: measured on the
/// simulated mill before the executor took G61.1, 20 mm along Z in 0.285 s
/// (half of 2000 mm/s²: 0.283 s) and 80 mm along X with 60 along Y in
/// 0.661 s (half of X's 2000 / 0.8: 0.660 s).
MotionLimits planner_limits(const MotionLimits& limits);

/// The plan's steps at `limits`: every move an exact stop as move_seconds
/// has it, plus the dwells; no handshake, no latency, no blending. At the
/// machine's limits and of the direct path's plan, the bound of a change.
double limits_seconds(const Simulator& plan, const Point& start, const MotionLimits& limits);

/// As limits_seconds, but each run of rapids with nothing between them (no
/// chuck, dwell or command) as fast as its axes allow if they never stopped:
/// the slowest of each axis covering its travel and the path its length, from
/// standing to standing. Less than any blending of the corners could reach,
/// so what blending is worth at most.
double blended_seconds(const Simulator& plan, const Point& start, const MotionLimits& limits);

/// Of limits_seconds, the part made before the spindle stood
/// (plan_change_running_down: the records before Simulator::spindle_stood).
double limits_seconds_while_running_down(const Simulator& plan, const Point& start,
                                         const MotionLimits& limits);

/// What an estimate needs of the machine: its motion limits and
/// [EMCIO]CYCLE_TIME, in seconds.
struct MachineTiming {
  MotionLimits limits;
  double iocontrol_cycle_seconds = kIocontrolCycleSeconds;
};

/// How long a change takes on the machine, by parts, in seconds.
struct ChangeTime {
  double moves = 0.0;      ///< every move at planner_limits
  double dwells = 0.0;     ///< the changer's own waits (chuck, flush)
  int steps = 0;           ///< the steps the executor performs, kStepSeconds each
  double iocontrol = 0.0;  ///< kIocontrolCycles of [EMCIO]CYCLE_TIME
  int operator_waits = 0;  ///< prompts: the operator's time, not counted
  double seconds() const {
    return moves + dwells + steps * kStepSeconds + iocontrol + kChangeSeconds;
  }
};

/// The estimate of a change planned from `start` (plan_change) on `machine`:
/// its moves as LinuxCNC plans them, its dwells, and what the changer and
/// LinuxCNC add per step and per change. What --plan and --lint print.
ChangeTime change_time(const Simulator& plan, const Point& start, const MachineTiming& machine);

}  // namespace fatc
