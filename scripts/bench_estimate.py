#!/usr/bin/env python3
"""Prints the change-time estimate against the real LinuxCNC
(scripts/bench_estimate.sh): for each change of tests/bench/changes.ngc, what
it took chip to chip and what `fixed_atc_probe --lint` estimated, and the
costs the estimate adds per step and per change as this run measured them.
Prints, never asserts.
   bench_estimate.py WORKDIR BINARY [OLD_BINARY]
WORKDIR holds the runs as run_sim.sh left them (results.json, config.json,
sim.ini): mill_direct/, mill_prototype/, slow_direct/ and usual_io_direct/. OLD_BINARY, when
given, is a fixed_atc_probe from before the estimate counted acceleration and
the changer's costs: its estimate is printed beside."""
import json
import os
import re
import statistics
import subprocess
import sys

from bench_changes import CHANGES, change_seconds, first_motion, handshake

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RUNS = [("mill_direct", "the simulated mill (200 mm/s, 2000 mm/s²), direct path"),
        ("mill_prototype", "the simulated mill, prototype path"),
        ("slow_direct", "the slow machine (gantry_mm.ini's 30 mm/s, 200 mm/s²), direct path"),
        ("usual_io_direct", "the simulated mill with [EMCIO]CYCLE_TIME 0.1 s (LinuxCNC's usual), direct path")]
TIME = r"(?:(\d+) min )?([\d.]+) s"


def seconds_of(text):
    m = re.fullmatch(TIME, text.strip())
    return int(m.group(1) or 0) * 60 + float(m.group(2)) if m else None


def lint_rows(binary, run):
    """The estimate of each change as --lint prints it, in the program's order."""
    out = subprocess.run([binary, "--lint", os.path.join(ROOT, "tests/bench/changes.ngc"),
                          "--config", run + "/config.json", "--ini", run + "/sim.ini",
                          "--state", run + "/no_state_yet.json",
                          "--tool-table", os.path.join(ROOT, "tests/integration/rack/rack.tbl")],
                         capture_output=True, text=True).stdout
    rows = [line for line in out.splitlines() if re.match(r"^\s+\d+\s+\d+\s+M6", line)]
    return [seconds_of(re.search(TIME + "$", row).group(0)) for row in rows]


def plan_parts(binary, run, frm, to):
    """(moves, dwells, steps, what a change costs besides) of --plan's
    estimate of M6 T`to` with T`frm`."""
    out = subprocess.run([binary, "--plan", "--config", run + "/config.json", "--ini",
                          run + "/sim.ini", "--from", str(frm), "--to", str(to)],
                         capture_output=True, text=True).stdout
    parts = re.search(r"\(moves ([\d.]+) s, dwells ([\d.]+) s, (\d+) steps?\)", out)
    change = re.search(r"([\d.]+) s a change", out)
    return (float(parts.group(1)), float(parts.group(2)), int(parts.group(3)), float(change.group(1)))


def step_cost(binary):
    """kStepSeconds as the binary prints it."""
    out = subprocess.run([binary, "--plan", "--config", os.path.join(ROOT, "config/config.json"),
                          "--from", "1", "--to", "2"], capture_output=True, text=True).stdout
    return float(re.search(r"(\d+) ms a step", out).group(1)) / 1000


def main():
    work, binary = sys.argv[1:3]
    old = sys.argv[3] if len(sys.argv) > 3 else None
    k_step = step_cost(binary)
    handshakes = []
    for name, what in RUNS:
        run = os.path.join(work, name)
        results = json.load(open(run + "/results.json"))
        if results["error"]:
            print("%s: the run failed: %s" % (name, results["error"]))
            continue
        samples = results["scenarios"][0]["samples"]
        real = change_seconds(samples)
        if len(real) != len(CHANGES):
            print("%s: %d changes seen, expected %d" % (name, len(real), len(CHANGES)))
            continue
        estimate = lint_rows(binary, run)
        before = lint_rows(old, run) if old else None
        steps = handshake(samples)
        handshakes += steps
        print("\n%s" % what)
        print("%-32s %9s %9s %7s%s   %s" % ("tests/bench/changes.ngc", "real", "--lint", "ratio",
                                          " %9s %7s" % ("before", "ratio") if old else "",
                                          "beyond moves, dwells and steps"))
        beyonds = []
        for i, (frm, to, label) in enumerate(CHANGES):
            moves, dwells, count, per_change = plan_parts(binary, run, frm, to)
            beyond = real[i] - moves - dwells - count * k_step
            beyonds.append(beyond)
            print("%-32s %8.2fs %8.1fs %7.2f%s   %.2f s (%d steps)" % (
                label, real[i], estimate[i], estimate[i] / real[i],
                " %8.1fs %7.2f" % (before[i], before[i] / real[i]) if old else "", beyond, count))
        print("%-32s %8.2fs %8.1fs %7.2f%s" % (
            "all five", sum(real), sum(estimate), sum(estimate) / sum(real),
            " %8.1fs %7.2f" % (sum(before), sum(before) / sum(real)) if old else ""))
        print("a change beyond its moves, dwells and steps: median %.2f s (the estimate counts %.2f s)"
              % (statistics.median(beyonds), per_change))
        if steps:
            print("standing still between two moves with nothing between them (a step's cost): "
                  "median %.1f ms over %d steps" % (statistics.median(steps) * 1000, len(steps)))
        entry = first_motion(samples)
        if entry:
            print("from the end of one change to the first motion of the next: median %.0f ms"
                  % (statistics.median(entry) * 1000))
    if handshakes:
        print("\nover every run: a step's cost %.1f ms (median over %d; the estimate counts %.0f ms)"
              % (statistics.median(handshakes) * 1000, len(handshakes), k_step * 1000))


if __name__ == "__main__":
    main()
