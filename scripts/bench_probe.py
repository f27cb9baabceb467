#!/usr/bin/env python3
"""Prints the probe benchmark's figures from its results file.
   bench_probe.py RESULTS.json"""
import json
import statistics
import sys


def summary(name, runs, truth):
    lengths = [r["length"] for r in runs]
    seconds = [r["seconds"] for r in runs]
    errors = [abs(x - truth) for x in lengths]
    print("%-28s n=%2d  length mean %.4f  |error| mean %.4f max %.4f  sigma %.4f  time mean %.2f s (min %.2f, max %.2f)" % (
        name, len(runs), statistics.mean(lengths), statistics.mean(errors), max(errors),
        statistics.pstdev(lengths), statistics.mean(seconds), min(seconds), max(seconds)))
    return statistics.mean(seconds), max(errors), statistics.pstdev(lengths)


def main():
    r = json.load(open(sys.argv[1]))
    if r["error"]:
        print("benchmark failed: " + r["error"])
    if not r["two_stage"] or not r["stepping"]:
        return 1
    truth = r["truth"]
    print("simulated sensor at machine Z %.4f: true length %.4f mm; config %s" % (r["sensor_z"], truth, r["config"]))
    fast, fast_error, fast_sigma = summary("two-stage (fixed_atc_probe)", r["two_stage"], truth)
    slow, slow_error, slow_sigma = summary("0.2 mm steps (prototype)", r["stepping"], truth)
    print("speed: two-stage is %.1fx faster (goal 5x); error max %.4f mm (goal 0.005); sigma %.4f mm (goal 0.002)" % (
        slow / fast, fast_error, fast_sigma))
    if r.get("probe_approach") and r.get("probe_all_the_way"):
        approach, _, _ = summary("probe T3, approach (now)", r["probe_approach"], truth)
        before, _, _ = summary("probe T3, its feed all the way", r["probe_all_the_way"], truth)
        print("measuring time: a cutter %.2f s, a touch probe %.2f s; the probe at its own feed all the "
              "way down %.2f s: the approach takes x%.2f of that (goal under x0.33)" % (
                  fast, approach, before, approach / before))
    return 0 if not r["error"] else 1


if __name__ == "__main__":
    sys.exit(main())
