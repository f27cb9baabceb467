#!/usr/bin/env python3
"""Checks the rack run's air runs (scenario rack_air, issue 44): with T3 (40 mm)
in the spindle, M6 T12, the unload of T7 and the verify of pocket 4 (T3's,
empty), each flown 45 mm above the rack at F12000; one at 10 mm (refused: T3
would hang into the rack) and one at 0; then, T7 unloaded for real, the load
of T30 into pocket 2 flown the same way.
Read back from LinuxCNC: every sampled position over the rack's row no lower
than its top (holders' top plus rack_keepout_above) plus 45 mm, the keep-out
armed throughout (never lifted for the changer), the chuck and the air blast
off, LinuxCNC's tool 3 throughout, no move faster than F12000, and the state
file and tool table byte for byte as they were.
   check_air.py RESULTS.json CONFIG.json
Prints what it checked; exits 1 on the first failed expectation."""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
from check import Rack, distinct, fail, load_results, no_fault, ok, said, scenario  # noqa: E402

HEIGHT = 45.0
FEED = 12000.0  # a tenth of the fast axes' 2000 mm/s: the cap still bites
STATE = "fixed_atc_probe.state"
AIR_RUN = 9


def air_runs(samples):
    """The sample ranges where the state pin read air run, in order."""
    runs, first = [], None
    for i, s in enumerate(samples):
        if s[STATE] == AIR_RUN and first is None:
            first = i
        elif s[STATE] != AIR_RUN and first is not None:
            runs.append((first, i))
            first = None
    return runs


def rack_row(rack):
    """The rack's row as the keep-out holds it: XY around every pocket's column,
    and the floor of an air run over it."""
    margin = rack.keepout_margin()
    xs = [rack.pocket(n)[0] for n in rack.pockets]
    ys = [rack.pocket(n)[1] for n in rack.pockets]
    tops = [rack.pocket(n)[2] + rack.c["pocket_above_chuck_offset_z"] for n in rack.pockets]
    top = max(tops) + rack.c.get("rack_keepout_above", 5.0)
    return (min(xs) - margin, max(xs) + margin, min(ys) - margin, max(ys) + margin), top + HEIGHT


def main():
    results = load_results(sys.argv[1], "rack_air")
    rack = Rack(json.load(open(sys.argv[2])))
    r = scenario(results, "rack_air")
    no_fault(r)
    samples = r["samples"]
    runs = air_runs(samples)
    if len(runs) != 4:
        fail("the state pin read air run (9) in %d runs, expected 4" % len(runs))
    (x0, x1, y0, y1), floor = rack_row(rack)
    over, lowest = 0, None
    for first, last in runs:
        for s in samples[first:last]:
            x, y, z = s["pos"]
            if x0 < x < x1 and y0 < y < y1:
                over += 1
                lowest = z if lowest is None else min(lowest, z)
                if z < floor - 1e-3:
                    fail("at X%.3f Y%.3f the spindle was at Z%.3f, below the air floor Z%.3f" %
                         (x, y, z, floor))
            for pin in ("fixed_atc_probe.chuck", "fatc-chuck-guard.chuck", "fixed_atc_probe.air-blast"):
                if s[pin]:
                    fail("%s went on during an air run" % pin)
            if s["fixed_atc_probe.rack-keepout"] != 1:
                fail("the keep-out read %s during an air run, expected 1 (armed)" %
                     s["fixed_atc_probe.rack-keepout"])
        fastest = max(s["vel"] for s in samples[first:last]) * 60.0
        if fastest > FEED * 1.02:
            fail("an air run moved at F%.0f, faster than its F%.0f" % (fastest, FEED))
    if over == 0:
        fail("no sample over the rack's row: the air runs never went over it")
    ok("%d samples over the rack's row (X %.0f..%.0f Y %.0f..%.0f), the lowest at Z%.3f, none "
       "below the floor Z%.3f (the rack's top plus %.0f)" % (over, x0, x1, y0, y1, lowest, floor, HEIGHT))
    ok("the chuck and the air blast off, the keep-out armed, no move faster than F%.0f" % FEED)
    for (first, last), tool in zip(runs, (3, 3, 3, 0)):
        if distinct(samples[first:last], "tool_in_spindle") != [tool]:
            fail("LinuxCNC's tool in spindle went %s during an air run, expected %d throughout" %
                 (distinct(samples[first:last], "tool_in_spindle"), tool))
    ok("LinuxCNC's tool in spindle 3 throughout the first three air runs, 0 (after the real "
       "unload of T7) throughout the load")
    trips = distinct([s for first, last in runs for s in samples[first:last]], "fatc-rack-guard.trips")
    if len(trips) != 1:
        fail("the rack guard tripped during the air runs: trips went %s" % trips)
    ok("the rack guard never tripped")
    said(r, "refused")
    said(r, "air height 0: expected a height above the rack")
    files = r["files"]
    for first, then in (("before_air", "after_air"), ("before_air_load", "after_air_load")):
        for key, what in (("state", "the state file"), ("table", "the tool table")):
            before, after = files[first][key], files[then][key]
            if before is None or before != after:
                fail("%s changed from %s to %s:\n%s\n---\n%s" % (what, first, then, before, after))
            ok("%s from %s to %s byte for byte the same (%d bytes)" % (what, first, then, len(before)))


if __name__ == "__main__":
    main()
