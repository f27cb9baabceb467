#!/usr/bin/env python3
"""Prints the tool-change benchmark (scripts/bench_changes.sh): each change,
chip to chip, as LinuxCNC ran it, side by side with the bound and ratios.
Prints, never asserts.
   bench_changes.py WORKDIR BINARY
WORKDIR holds the runs as run_sim.sh left them (results.json, config.json,
sim.ini): prototype/ and direct/ (tests/bench/changes.ngc on the rack of
rack_config.json), row_prototype/, row_direct/ and row_peer/
(tests/bench/peer_changes.ngc on rack_y.json; the peer is LinuxCNC's
rack-toolchange example), blended/ and row_blended/ (the direct path
with blend_tolerance 10 and 15), row_rapid_entry/ (row_blended with
pocket_feed at the mill's rapid, the example's terms), demo_prototype/ and demo_direct/ (the demo
program), spindown_true/ and spindown_false/ (tests/bench/spindown.ngc,
moving while the spindle runs down and not), and the idle run
(idle/results.json).

The bound is what `fixed_atc_probe --plan` prints as such: the direct
path's moves at the INI's velocities and accelerations, each an exact stop
with a trapezoidal profile, plus the dwells; no handshake, no latency."""
import json
import re
import statistics
import subprocess
import sys

from demo_report import change_seconds as change_seconds_of
from demo_report import intervals, stops

PATHS = ("prototype", "direct")
MARK = "motion.digital-out-02"  # toggled between two changes by the programs
# tests/bench/changes.ngc on rack_config.json: from, to, what.
CHANGES = [(0, 12, "empty -> pocket 1"), (12, 7, "pocket 1 -> adjacent 2"),
           (7, 6, "pocket 2 -> farthest 6"), (6, 3, "side pocket 2 -> top pocket 4"),
           (3, 0, "top pocket 4 -> empty")]
# tests/bench/peer_changes.ngc on rack_y.json (tool N in pocket N).
ROW_CHANGES = [(0, 1, "empty -> pocket 1"), (1, 2, "pocket 1 -> adjacent 2"),
               (2, 6, "pocket 2 -> farthest 6"), (6, 6, "the same tool 6 again"),
               (6, 0, "pocket 6 -> empty")]


SPIN_DOWN = 3.0  # s: S12000 at the 4000 rpm/s of the spin-down runs


def spin_down_bound(binary, config, ini, frm, to):
    """(the bound with the spindle running down for SPIN_DOWN: the longer of it
    and the moves --plan says may go meanwhile, plus the rest at the bound;
    the bound standing until it stops: SPIN_DOWN plus the change's bound)."""
    out = plan_text(binary, config, ini, frm, to)
    whole = bounds_in(out)[0]
    parts = re.search(r"^while the spindle runs down: ([\d.]+) s .* the rest ([\d.]+) s", out, re.M)
    if not whole or not parts:
        return 0.0, 0.0
    meanwhile, rest = float(parts.group(1)), float(parts.group(2))
    return max(SPIN_DOWN, meanwhile) + rest, SPIN_DOWN + whole


def print_spin_down(work, binary):
    """tests/bench/spindown.ngc, T1 to T2, moving while the spindle runs down
    and standing until it stops: each change's time, the spin-down measured
    (M5 to zero-speed) and the bounds."""
    seconds, measured = {}, None
    for overlap in ("true", "false"):
        scenario, times = load(work, "spindown_" + overlap, [(1, 2, "pocket 1 -> 2")])
        seconds[overlap] = times[0]
        samples = scenario["samples"]
        if overlap == "true":
            off = next((b["t"] for a, b in zip(samples, samples[1:]) if a["spindle.0.on"] and not b["spindle.0.on"]),
                       None)
            stood = next((s["t"] for s in samples if off is not None and s["t"] >= off
                          and s["fixed_atc_probe.zero-speed"]), None)
            measured = stood - off if off is not None and stood is not None else None
    overlapped, stop_first = spin_down_bound(binary, "%s/spindown_true/config.json" % work,
                                             "%s/spindown_true/sim.ini" % work, 1, 2)
    print("\nspin-down %.1f s: overlapped %.2f s, stop first %.2f s, bound %.2f s (overlapped ratio to bound "
          "%.2f; stop first's bound %.2f s, ratio %.2f; the spin-down measured from M5 to zero-speed: %s)"
          % (SPIN_DOWN, seconds["true"], seconds["false"], overlapped,
             seconds["true"] / overlapped if overlapped else 0.0, stop_first,
             seconds["false"] / stop_first if stop_first else 0.0,
             "%.2f s" % measured if measured is not None else "not seen"))


def plan_text(binary, config, ini, frm, to):
    """What --plan prints for M6 T`to` with T`frm`."""
    return subprocess.run([binary, "--plan", "--config", config, "--ini", ini, "--from", str(frm),
                           "--to", str(to)], capture_output=True, text=True).stdout


def plan_bounds(binary, config, ini, frm, to):
    """(the bound, the prototype path's time at the same limits, the direct
    path's with each run of rapids as one move) of --plan."""
    return bounds_in(plan_text(binary, config, ini, frm, to))


def bounds_in(out):
    """plan_bounds of --plan's text."""
    line = re.search(r"^bound (.*)$", out, re.M)
    if not line:
        return 0.0, 0.0, 0.0
    times = re.findall(r"(?:(\d+) min )?([\d.]+) s", line.group(1))
    return tuple(int(m or 0) * 60 + float(s) for m, s in times[:3])


def mark_edges(samples):
    """The indexes where MARK toggled: after the move to safe and after each M6."""
    return [i for i in range(1, len(samples)) if samples[i][MARK] != samples[i - 1][MARK]]


def change_seconds(samples):
    """Each change's time, chip to chip: from one toggle of MARK to the next."""
    edges = mark_edges(samples)
    return [samples[b]["t"] - samples[a]["t"] for a, b in zip(edges, edges[1:])]


def handshake(samples):
    """Per step with no chuck action or dwell: how long the machine stood still
    between two moves (the executor's handshake and LinuxCNC's latency), as in
    demo_report.py."""
    edges = [samples[i]["t"] for i in range(1, len(samples))
             if samples[i]["fixed_atc_probe.chuck"] != samples[i - 1]["fixed_atc_probe.chuck"]]
    waits = []
    for a, b in intervals(samples, "fixed_atc_probe.busy"):
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


def load(work, name, changes):
    """The run's scenario, its change times; exits when the run failed."""
    run = json.load(open("%s/%s/results.json" % (work, name)))
    if run["error"]:
        print("%s run failed: %s" % (name, run["error"]))
        sys.exit(1)
    scenario = run["scenarios"][0]
    seconds = change_seconds(scenario["samples"])
    if len(seconds) != len(changes):
        print("%s: %d changes seen, expected %d" % (name, len(seconds), len(changes)))
        sys.exit(1)
    return scenario, seconds


def bound(work, name, binary, changes, which=0):
    """Each change's bound (which=1: the prototype path's plan at the same limits,
    2: the direct path's with each run of rapids as one move)."""
    config, ini = "%s/%s/config.json" % (work, name), "%s/%s/sim.ini" % (work, name)
    return [plan_bounds(binary, config, ini, frm, to)[which] for frm, to, _ in changes]


def print_usage(name, scenario):
    before, after = scenario.get("usage_before"), scenario.get("usage_after")
    if before and after:
        print("%s: during the changes (%.0f s) the component used %.2f %% of a core; peak resident %.1f MiB"
              % (name, scenario["duration"], 100 * (after["cpu_seconds"] - before["cpu_seconds"])
                 / scenario["duration"], after["peak_kib"] / 1024))


def first_motion(samples):
    """Per change: from the end of the one before (the mark) to the first move
    the change commands: the latency of M6 up to its first motion."""
    edges = mark_edges(samples)
    out = []
    for a, b in zip(edges, edges[1:]):
        moved = next((j for j in range(a + 1, b) if samples[j]["cmd"] != samples[a]["cmd"]), None)
        if moved is not None:
            out.append(samples[moved]["t"] - samples[a]["t"])
    return out


def print_latency(name, scenario):
    waits = first_motion(scenario["samples"])
    if waits:
        print("%s: from the end of a change to the first motion of the next: median %.0f ms, max %.0f ms"
              % (name, statistics.median(waits) * 1000, max(waits) * 1000))


def print_handshake(name, scenario):
    waits = handshake(scenario["samples"])
    if waits:
        print("%s: standing still between two moves (handshake and latency): median %.1f ms, "
              "max %.1f ms over %d steps" % (name, statistics.median(waits) * 1000, max(waits) * 1000, len(waits)))


def print_table(title, columns, rows, changes):
    """rows: {column: [seconds per change]}; ratios of the first columns to the last ones."""
    print("\n%-32s %s   ratios" % (title, " ".join("%10s" % c for c in columns)))
    for i in list(range(len(changes))) + [None]:
        what = changes[i][2] if i is not None else "all five"
        value = {c: (rows[c][i] if i is not None else sum(rows[c])) for c in columns}
        ratios = []
        for a, b in RATIOS:
            if a in value and b in value and value[b] > 0:
                ratios.append("%s ratio to %s %.2f" % (a, b, value[a] / value[b]))
        print("%-32s %s   %s" % (what, " ".join("%9.2fs" % value[c] for c in columns), ", ".join(ratios)))


RATIOS = [("direct", "prototype"), ("direct", "bound"), ("prototype", "bound"), ("direct", "peer"),
          ("prototype", "peer"), ("blended", "direct"), ("blended", "bound"), ("blended", "peer"),
          ("rapid_entry", "peer")]


def print_demo(work, binary):
    """The demo program on both paths: its time in all, its changes' (the
    changer busy) and their bounds from safe."""
    runs = {}
    for path in PATHS:
        run = json.load(open("%s/demo_%s/results.json" % (work, path)))
        if run["error"]:
            print("demo on the %s path failed: %s" % (path, run["error"]))
            return
        runs[path] = run["scenarios"][0]
    samples = runs["direct"]["samples"]
    tools = [samples[0]["tool_in_spindle"]] + [b["tool_in_spindle"] for a, b in zip(samples, samples[1:])
                                               if a["tool_in_spindle"] != b["tool_in_spindle"]]
    changes = [(a, b, "") for a, b in zip(tools, tools[1:])]
    bounds = bound(work, "demo_direct", binary, changes)
    busy = {p: sum(change_seconds_of(r)) for p, r in runs.items()}
    print("\nnc_files/demo.ngc (tools %s): the program %.2f s on the prototype path, %.2f s on the "
          "direct path (ratio %.2f); its changes %.2f s and %.2f s (ratio %.2f), bound %.2f s from safe%s"
          % (" > ".join("T%d" % t for t in tools), runs["prototype"]["duration"], runs["direct"]["duration"],
             runs["direct"]["duration"] / runs["prototype"]["duration"], busy["prototype"], busy["direct"],
             busy["direct"] / busy["prototype"], sum(bounds),
             " (direct ratio to bound %.2f)" % (busy["direct"] / sum(bounds)) if sum(bounds) > 0 else ""))


def main():
    work, binary = sys.argv[1:3]
    print_idle(work)
    rack, row = {}, {}
    for path in PATHS:
        scenario, rack[path] = load(work, path, CHANGES)
        print_handshake("%s path" % path, scenario)
        print_usage("%s path" % path, scenario)
        print_latency("%s path" % path, scenario)
        row[path] = load(work, "row_" + path, ROW_CHANGES)[1]
    scenario, rack["blended"] = load(work, "blended", CHANGES)
    print_handshake("direct path, blended", scenario)
    row["blended"] = load(work, "row_blended", ROW_CHANGES)[1]
    row["rapid_entry"] = load(work, "row_rapid_entry", ROW_CHANGES)[1]
    peer, row["peer"] = load(work, "row_peer", ROW_CHANGES)
    print_latency("LinuxCNC's rack-toolchange example", peer)
    rack["bound"] = bound(work, "direct", binary, CHANGES)
    row["bound"] = bound(work, "row_direct", binary, ROW_CHANGES)
    print_table("tests/bench/changes.ngc", ("prototype", "direct", "blended", "bound"), rack, CHANGES)
    prototype = sum(bound(work, "direct", binary, CHANGES, which=1))
    blended = sum(bound(work, "direct", binary, CHANGES, which=2))
    if sum(rack["bound"]) > 0:
        print("the prototype's plan at the same limits: %.2f s (%.2f of the bound); the direct path "
              "with each run of rapids unstopped (more than blending could save): %.2f s (%.2f of the "
              "bound)" % (prototype, prototype / sum(rack["bound"]), blended, blended / sum(rack["bound"])))
    print_table("peer_changes.ngc, top pockets",
                ("prototype", "direct", "blended", "rapid_entry", "peer", "bound"), row, ROW_CHANGES)
    print_demo(work, binary)
    print_spin_down(work, binary)


if __name__ == "__main__":
    main()
