#!/usr/bin/env python3
"""Prints the collet-nut benchmark (scripts/bench_collet.sh): each change of
tests/bench/collet_changes.ngc, chip to chip, as LinuxCNC ran it on the
simulated magazine, against its physical bound: the moves of what
`fixed_atc_probe --plan` prints as the bound (the direct path's moves at the
INI's velocities and accelerations, each an exact stop) and the spindle's
ramps: each start to the plan's speed and each stop take
|speed| / [FIXED_ATC_PROBE]SIM_SPINDLE_RAMP seconds. The plan's own bound
counts each wait for the spindle (at-speed, zero-speed) as a dwell of
spindle_ramp_seconds: printed beside, not used.
Prints, never asserts.
   bench_collet.py RUNDIR BINARY
RUNDIR holds the run as run_sim.sh left it (results.json, config.json, sim.ini)."""
import configparser
import json
import re
import statistics
import sys

from bench_changes import bounds_in, change_seconds, handshake, plan_text

# tests/bench/collet_changes.ngc (tool N's nut in pocket N): from, to, what.
CHANGES = [(0, 1, "empty -> pocket 1"), (1, 2, "pocket 1 -> adjacent 2"),
           (2, 6, "pocket 2 -> farthest 6"), (6, 3, "pocket 6 -> 3"), (3, 0, "pocket 3 -> empty")]


def spindle_speeds(plan):
    """The signed speeds of the plan's spindle steps, in order (M5: 0)."""
    speeds = []
    for line in plan.splitlines():
        m = re.match(r"^\s*\d+\s+spindle\s+(M[345])(?: S(\d+))?", line)
        if m:
            speeds.append({"M3": 1, "M4": -1, "M5": 0}[m.group(1)] * float(m.group(2) or 0))
    return speeds


def dwells_seconds(plan):
    """The plan's dwells: on a collet-nut magazine, the waits for the spindle."""
    return sum(float(m.group(1)) for m in re.finditer(r"^\s*\d+\s+dwell\s+([\d.]+) s", plan, re.M))


def ramps_seconds(speeds, ramp):
    """Each change of speed at `ramp` rpm/s, from standing."""
    seconds, now = 0.0, 0.0
    for speed in speeds:
        seconds += abs(speed - now) / ramp
        now = speed
    return seconds


def spindle_on_seconds(samples, a, b):
    """How long LinuxCNC had the spindle on between two samples."""
    return sum(s2["t"] - s1["t"] for s1, s2 in zip(samples[a:b], samples[a + 1:b + 1])
               if s1["spindle.0.on"])


def main():
    run, binary = sys.argv[1:3]
    results = json.load(open(run + "/results.json"))
    if results["error"]:
        print("the run failed: %s" % results["error"])
        return
    samples = results["scenarios"][0]["samples"]
    real = change_seconds(samples)
    if len(real) != len(CHANGES):
        print("%d changes seen, expected %d (messages: %s)" % (
            len(real), len(CHANGES), results["scenarios"][0]["messages"][-4:]))
        return
    ini = configparser.ConfigParser(strict=False, interpolation=None)
    ini.read(run + "/sim.ini")
    ramp = float(ini["FIXED_ATC_PROBE"]["SIM_SPINDLE_RAMP"])
    config = json.load(open(run + "/config.json"))
    edges = [i for i in range(1, len(samples))
             if samples[i]["motion.digital-out-02"] != samples[i - 1]["motion.digital-out-02"]]
    axes = "axes %s mm/s, %s mm/s²" % (ini["AXIS_X"]["MAX_VELOCITY"], ini["AXIS_X"]["MAX_ACCELERATION"])
    print("collet nuts on the simulated magazine (%s, spindle ramp %.0f rpm/s, unload %s / load %s rpm, "
          "engage feed %s, %s tightening plunges)" % (
              axes, ramp, config["chuck"]["unload_rpm"], config["chuck"]["load_rpm"],
              config["chuck"]["engage_feed"], config["chuck"]["tighten_plunges"]))
    print("%-26s %8s %8s %8s %8s %7s %8s %8s" % ("tests/bench/collet_changes", "real", "moves",
                                                "ramps", "bound", "ratio", "spindle", "--plan"))
    print("%-26s %8s %8s %8s %8s %7s %8s %8s" % ("", "", "", "", "", "", "on", "bound"))
    totals = [0.0] * 6
    for i, (frm, to, what) in enumerate(CHANGES):
        plan = plan_text(binary, run + "/config.json", run + "/sim.ini", frm, to)
        planned = bounds_in(plan)[0]
        moves = planned - dwells_seconds(plan)
        ramps = ramps_seconds(spindle_speeds(plan), ramp)
        bound = moves + ramps
        on = spindle_on_seconds(samples, edges[i], edges[i + 1])
        row = (real[i], moves, ramps, bound, on, planned)
        print("%-26s %7.2fs %7.2fs %7.2fs %7.2fs %7.2f %7.2fs %7.2fs" % (
            (what,) + row[:4] + (real[i] / bound if bound else 0.0,) + row[4:]))
        totals = [t + v for t, v in zip(totals, row)]
    print("%-26s %7.2fs %7.2fs %7.2fs %7.2fs %7.2f %7.2fs %7.2fs" % (
        ("all five",) + tuple(totals[:4]) + (totals[0] / totals[3],) + tuple(totals[4:])))
    steps = handshake(samples)
    if steps:
        print("standing still between two moves (handshake and latency): median %.1f ms over %d steps"
              % (statistics.median(steps) * 1000, len(steps)))


if __name__ == "__main__":
    main()
