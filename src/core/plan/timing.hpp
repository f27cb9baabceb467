#pragma once

#include "../rack/point.hpp"

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

/// What the changer adds to each step its executor performs, in seconds: the
/// handshake (request, step published, taken back) and LinuxCNC's queue
/// running dry before it (M66 waits for motion to end). Measured on the real
/// LinuxCNC (linuxcnc-uspace 2.9, [TASK]CYCLE_TIME 1 ms) as the machine's
/// standing still between two moves with nothing between them: median 16.4 ms
/// over 350 steps of two runs of scripts/bench_estimate.sh (the simulated
/// mill on both paths and slowed to the gantry's limits); scripts/bench_changes.sh
/// measured 16 ms.
constexpr double kStepSeconds = 0.016;

/// What a change costs besides its steps, in seconds: LinuxCNC's T and M6
/// through iocontrol (its [EMCIO]CYCLE_TIME of 0.1 s, a cycle for each and
/// for its answer), the remap's entry (M5, M70, the sync, the executor's
/// call) and exit (M72, G43). Measured on the real LinuxCNC as what each
/// change of scripts/bench_estimate.sh took chip to chip beyond its moves
/// (planner_limits), dwells and kStepSeconds a step: median 0.54 s over the 25
/// changes of two runs (0.39 to 0.66 s), of it about 0.25 s from the end of
/// one change to the first motion of the next.
constexpr double kChangeSeconds = 0.54;

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

/// The limits LinuxCNC's trajectory planner (linuxcnc-uspace 2.9) gives a
/// move that ends standing still: the velocities, and half the axes'
/// accelerations. Blending (G64, the interpreter's default, which the
/// executor leaves as the program set it) keeps half of each for the next
/// move (tp.c, tpGetScaledAccel), though the executor's moves never blend:
/// each waits for the next step. [TRAJ]MAX_LINEAR_ACCELERATION bounds no
/// straight move (canon takes the axes' alone). Measured on the simulated
/// mill (scripts/bench_estimate.sh): 20 mm along Z in 0.285 s at 141 mm/s
/// at most (half of 2000 mm/s²: 0.283 s, 141 mm/s); 80 mm along X with 60
/// along Y in 0.661 s (half of X's 2000 / 0.8: 0.660 s).
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

/// How long a change takes on the machine, by parts, in seconds.
struct ChangeTime {
  double moves = 0.0;   ///< every move at planner_limits
  double dwells = 0.0;  ///< the changer's own waits (chuck, flush)
  int steps = 0;        ///< the steps the executor performs, kStepSeconds each
  int operator_waits = 0;  ///< prompts: the operator's time, not counted
  double seconds() const { return moves + dwells + steps * kStepSeconds + kChangeSeconds; }
};

/// The estimate of a change planned from `start` (plan_change) on a machine
/// with `limits`: its moves as LinuxCNC plans them, its dwells, and what the
/// changer adds per step and per change. What --plan and --lint print.
ChangeTime change_time(const Simulator& plan, const Point& start, const MotionLimits& limits);

}  // namespace fatc
