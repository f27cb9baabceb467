#!/usr/bin/env python3
"""Prints the tool-change benchmark (scripts/bench_changes.sh): each change of
tests/bench/changes.ngc as LinuxCNC ran it on the prototype's path and on the
direct path, the model time of each path's plan, and the bound; ratios side
by side. Prints, never asserts.
   bench_changes.py WORKDIR BINARY
WORKDIR holds one run per path (prototype/, direct/: results.json, config.json,
sim.ini as run_sim.sh left them) and the idle run (idle/results.json).

The model time of a plan (`fixed_atc_probe --plan`): every move an exact stop
with a trapezoidal profile at the INI's velocities and accelerations (per axis,
along the move's direction, and [TRAJ]), feeds at their F, plus the dwells.
The bound is the model time of the direct path's plan: the waypoints the rack
requires, each reached as fast as the machine can without blending, and
nothing else (no handshake, no planner or task latency)."""
import configparser
import json
import math
import re
import statistics
import subprocess
import sys

from demo_report import intervals, stops

PATHS = ("prototype", "direct")
# tests/bench/changes.ngc: from, to.
CHANGES = [(0, 12), (12, 7), (7, 6), (6, 3), (3, 0)]
WHAT = {(0, 12): "empty -> pocket 1", (12, 7): "pocket 1 -> adjacent 2",
        (7, 6): "pocket 2 -> farthest 6", (6, 3): "side pocket 2 -> top pocket 4",
        (3, 0): "top pocket 4 -> empty"}


class Machine:
    """[TRAJ] and [AXIS_X/Y/Z] limits of the run's INI, in its units per second."""

    def __init__(self, ini_path):
        ini = configparser.ConfigParser(strict=False, interpolation=None, inline_comment_prefixes=("#",))
        ini.read_string(re.sub(r"^\s*#.*$", "", open(ini_path).read(), flags=re.M))
        self.velocity = [float(ini["AXIS_" + a]["MAX_VELOCITY"]) for a in "XYZ"]
        self.acceleration = [float(ini["AXIS_" + a]["MAX_ACCELERATION"]) for a in "XYZ"]
        self.linear_velocity = float(ini["TRAJ"]["MAX_LINEAR_VELOCITY"])
        self.linear_acceleration = float(ini["TRAJ"].get("MAX_LINEAR_ACCELERATION",
                                                         max(self.acceleration)))

    def move_seconds(self, a, b, feed_per_minute=None):
        d = math.dist(a, b)
        if d == 0.0:
            return 0.0
        direction = [abs(b[k] - a[k]) / d for k in range(3)]
        v = min([self.linear_velocity] + [self.velocity[k] / direction[k] for k in range(3) if direction[k]])
        acc = min([self.linear_acceleration] +
                  [self.acceleration[k] / direction[k] for k in range(3) if direction[k]])
        if feed_per_minute:
            v = min(v, feed_per_minute / 60.0)
        if d >= v * v / acc:
            return d / v + v / acc
        return 2.0 * math.sqrt(d / acc)


def plan_seconds(binary, config, ini, machine, start, frm, to):
    """The model time of `--plan --from frm --to to`, starting at `start`."""
    out = subprocess.run([binary, "--plan", "--config", config, "--ini", ini, "--from", str(frm),
                          "--to", str(to)], capture_output=True, text=True).stdout
    at, seconds = list(start), 0.0
    for line in out.splitlines():
        words = line.split()
        if len(words) < 2:
            continue
        if words[1] == "dwell":
            seconds += float(words[2])
        elif words[1] in ("rapid", "feed"):
            target = list(at)
            for axis, value in re.findall(r"\b([XYZ])=(-?[\d.]+)", line):
                target["XYZ".index(axis)] = float(value)
            feed = re.search(r"\bF([\d.]+)", line)
            seconds += machine.move_seconds(at, target, float(feed.group(1)) if words[1] == "feed" else None)
            at = target
    return seconds, at


def busy_spans(samples):
    return intervals(samples, "fixed_atc_probe.busy")


def handshake(samples):
    """Per step with no chuck action or dwell: how long the machine stood still
    between two moves (the executor's handshake and LinuxCNC's latency), as in
    demo_report.py."""
    edges = [samples[i]["t"] for i in range(1, len(samples))
             if samples[i]["fixed_atc_probe.chuck"] != samples[i - 1]["fixed_atc_probe.chuck"]]
    waits = []
    for a, b in busy_spans(samples):
        span = samples[a:b + 1]
        for first, last in stops(span):
            near_chuck = any(span[first]["t"] - 0.05 <= t <= span[last]["t"] + 0.05 for t in edges)
            if not near_chuck and 0 < first and last < len(span) - 1:
                waits.append(span[last + 1]["t"] - span[first]["t"])
    return waits


def print_idle(work):
    idle = json.load(open("%s/idle/results.json" % work))
    if idle["error"]:
        print("idle measurement failed: %s" % idle["error"])
        return
    print("idle for %.0f s: the component used %.3f %% of a core; resident %.1f MiB (peak %.1f MiB)"
          % (idle["seconds"], idle["cpu_share"] * 100, idle["rss_kib"] / 1024, idle["peak_kib"] / 1024))


def main():
    work, binary = sys.argv[1:3]
    print_idle(work)
    measured, model = {}, {}
    for path in PATHS:
        run = json.load(open("%s/%s/results.json" % (work, path)))
        if run["error"]:
            print("%s run failed: %s" % (path, run["error"]))
            sys.exit(1)
        samples = run["scenarios"][0]["samples"]
        spans = busy_spans(samples)
        if len(spans) != len(CHANGES):
            print("%s: %d changes seen, expected %d" % (path, len(spans), len(CHANGES)))
            sys.exit(1)
        measured[path] = [samples[b]["t"] - samples[a]["t"] for a, b in spans]
        config, ini = "%s/%s/config.json" % (work, path), "%s/%s/sim.ini" % (work, path)
        machine = Machine(ini)
        safe = json.load(open(config))["safe"]
        at = [safe["x"], safe["y"], safe["z"]]
        model[path] = []
        for frm, to in CHANGES:
            seconds, at = plan_seconds(binary, config, ini, machine, at, frm, to)
            model[path].append(seconds)
        waits = handshake(samples)
        if waits:
            print("%s path: standing still between two moves (handshake and latency): median %.1f ms, "
                  "max %.1f ms over %d steps"
                  % (path, statistics.median(waits) * 1000, max(waits) * 1000, len(waits)))
    print("\n%-32s %10s %10s %10s   %s" % ("change (tests/bench/changes.ngc)", "prototype", "direct",
                                          "bound", "ratios"))
    for i, change in enumerate(CHANGES):
        p, d, bound = measured["prototype"][i], measured["direct"][i], model["direct"][i]
        print("%-32s %9.2fs %9.2fs %9.2fs   direct/prototype %.2f, prototype ratio to bound %.2f, "
              "direct ratio to bound %.2f" % (WHAT[change], p, d, bound, d / p, p / bound, d / bound))
    p, d, bound = (sum(measured["prototype"]), sum(measured["direct"]), sum(model["direct"]))
    print("%-32s %9.2fs %9.2fs %9.2fs   direct/prototype %.2f, prototype ratio to bound %.2f, "
          "direct ratio to bound %.2f" % ("all five", p, d, bound, d / p, p / bound, d / bound))
    print("model time of the prototype's plan: %.2f s (%.2f of the bound)"
          % (sum(model["prototype"]), sum(model["prototype"]) / bound))


if __name__ == "__main__":
    main()
