#!/usr/bin/env python3
"""Prints what the demo run did, from what LinuxCNC reported: each tool change
with its duration and the waypoints the machine stopped at, and the figures
of the benchmark (handshake overhead per step, time to first motion,
chip-to-chip time); with a second run of the same program on the other path,
both paths' change times.   demo_report.py RESULTS.json [OTHER_PATH_RESULTS.json]"""
import json
import statistics
import sys


def intervals(samples, pin):
    spans, start = [], None
    for i, s in enumerate(samples):
        if s[pin] and start is None:
            start = i
        elif not s[pin] and start is not None:
            spans.append((start, i))
            start = None
    return spans


def stops(samples):
    """Stretches where the commanded position stands still: (first index, last index)."""
    out, start = [], 0
    for i in range(1, len(samples) + 1):
        if i == len(samples) or samples[i]["cmd"] != samples[start]["cmd"]:
            # Two equal samples can be a status update skipped, not a stop.
            if i - start >= 2 and samples[i - 1]["t"] - samples[start]["t"] >= 0.005:
                out.append((start, i - 1))
            start = i
    return out


def main():
    results = json.load(open(sys.argv[1]))
    if results["error"]:
        print("demo failed: " + results["error"])
        sys.exit(1)
    run = results["scenarios"][0]
    samples = run["samples"]
    chuck_edges = [samples[i]["t"] for i in range(1, len(samples))
                   if samples[i]["fixed_atc_probe.chuck"] != samples[i - 1]["fixed_atc_probe.chuck"]]
    overheads, to_first_motion = [], []
    previous_tool = samples[0]["tool_in_spindle"]
    print("tool changes of nc_files/demo.ngc on the simulated mill:")
    for number, (a, b) in enumerate(intervals(samples, "fixed_atc_probe.busy"), 1):
        span = samples[a:b + 1]
        tool = samples[b - 1]["fixed_atc_probe.tool-in-spindle"]
        print("\nchange %d: T%d -> T%d, %.2f s" % (number, previous_tool, tool, span[-1]["t"] - span[0]["t"]))
        previous_tool = tool
        moving = [i for i in range(1, len(span)) if span[i]["cmd"] != span[i - 1]["cmd"]]
        if moving:
            to_first_motion.append(span[moving[0]]["t"] - span[0]["t"])
        for first, last in stops(span):
            p = span[first]["cmd"]
            print("  stop at X%8.3f Y%8.3f Z%8.3f for %.3f s%s" % (
                p[0], p[1], p[2], span[last]["t"] - span[first]["t"],
                "  (chuck)" if any(span[first]["t"] - 0.05 <= t <= span[last]["t"] + 0.05 for t in chuck_edges) else ""))
            pure = not any(span[first]["t"] - 0.05 <= t <= span[last]["t"] + 0.05 for t in chuck_edges)
            if pure and 0 < first and last < len(span) - 1:
                overheads.append(span[last + 1]["t"] - span[first]["t"])
    spindle = intervals(samples, "spindle.0.on")
    chip_to_chip = [samples[spindle[i + 1][0]]["t"] - samples[spindle[i][1]]["t"] for i in range(len(spindle) - 1)]
    period = statistics.median(samples[i + 1]["t"] - samples[i]["t"] for i in range(len(samples) - 1))
    print("\nbenchmark (sampled every %.1f ms by the driver):" % (period * 1000))
    if overheads:
        print("  handshake overhead per step, stop to next start: median %.1f ms, max %.1f ms over %d steps"
              % (statistics.median(overheads) * 1000, max(overheads) * 1000, len(overheads)))
    if to_first_motion:
        print("  from the M6 request to first motion: median %.1f ms, max %.1f ms"
              % (statistics.median(to_first_motion) * 1000, max(to_first_motion) * 1000))
    for i, seconds in enumerate(chip_to_chip, 1):
        print("  chip-to-chip %d (spindle off to on again): %.2f s" % (i, seconds))
    print("\nprogram: %.1f s, final tool in spindle T%d" % (run["duration"], samples[-1]["tool_in_spindle"]))
    if len(sys.argv) > 2:
        other = json.load(open(sys.argv[2]))
        if other["error"]:
            print("the run on the other path failed: " + other["error"])
            sys.exit(1)
        print_paths({"direct": run, "prototype": other["scenarios"][0]})


def change_seconds(run):
    """Each change's time: the changer busy."""
    samples = run["samples"]
    return [samples[b]["t"] - samples[a]["t"] for a, b in intervals(samples, "fixed_atc_probe.busy")]


def print_paths(runs):
    """The change times of the same program on both paths, side by side."""
    times = {path: change_seconds(run) for path, run in runs.items()}
    print("\nthe changes on both paths (config.json's \"path\"):")
    for path, seconds in times.items():
        print("  %-9s %s: %.2f s in all, the program %.1f s" % (
            path, ", ".join("%.2f" % s for s in seconds), sum(seconds), runs[path]["duration"]))
    if sum(times["prototype"]) > 0:
        print("  the direct path takes %.2f of the prototype path's time" % (
            sum(times["direct"]) / sum(times["prototype"])))


if __name__ == "__main__":
    main()
