#!/usr/bin/env python3
"""Checks one scenario of the keep-out run (integration_keepout_run): a move
into the rack by MDI, a program line or a jog ends outside the rack's volume
(what LinuxCNC reports, every sample), with the component's message; a low
move beside the rack and motion over it run; a long tool raises the boundary;
M6 still changes tools; lifting the keep-out lets the spindle in.
   check_keepout.py RESULTS.json CONFIG.json SCENARIO"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
from check import fail, load_results, no_fault, ok, said, spindle_holds  # noqa: E402

TOLERANCE = 0.01  # mm: the sim follows its commands exactly


class Volume:
    """The rack's volume as src/core/rack/keepout.cpp makes it, for a rack of
    one row (the sim's: every pocket within a column's width of the next)."""

    def __init__(self, config):
        default = config.get("pocket_default", {})
        pockets = [{**default, **p} for p in config["pockets"].values()]
        side = config["pocket_side_offset"]
        m = config.get("rack_keepout_margin", math.hypot(side["x"], side["y"]) / 2)
        above = config.get("rack_keepout_above", 5.0)
        xs = sorted(p["x"] for p in pockets)
        if any(b - a > 4 * m for a, b in zip(xs, xs[1:])) or len({p["y"] for p in pockets}) != 1:
            fail("the checker knows the volume of a rack of one row only")
        self.low = (xs[0] - m, pockets[0]["y"] - m)
        self.high = (xs[-1] + m, pockets[0]["y"] + m)
        self.top = max(p["z"] for p in pockets) + config["pocket_above_chuck_offset_z"] + above

    def inside(self, pos, length):
        """The nose at `pos` with a tool `length` long: its tip inside (not on a face)."""
        return (self.low[0] + TOLERANCE < pos[0] < self.high[0] - TOLERANCE and
                self.low[1] + TOLERANCE < pos[1] < self.high[1] - TOLERANCE and
                pos[2] - length < self.top - TOLERANCE)


def length_of(r, tool):
    return r["tool_table"].get(str(tool), 0.0) if tool else 0.0


def never_entered(r, volume):
    """No sample of the whole scenario has the tool's tip in the rack's volume."""
    for s in r["samples"]:
        length = length_of(r, s["tool_in_spindle"])
        if s["fixed_atc_probe.rack-keepout"] == 1 and volume.inside(s["pos"], length):
            fail("at %.3f s the nose was at %s with T%d (length %g): inside the rack's volume "
                 "(top %g)" % (s["t"], s["pos"], s["tool_in_spindle"], length, volume.top))
    ok("never inside the rack's volume while armed (%d samples)" % len(r["samples"]))


def tripped(r):
    """Once: a jog's trip may end between two samples, its count stays."""
    counts = [s["fatc-rack-guard.trips"] for s in r["samples"]]
    if counts[-1] - counts[0] != 1:
        fail("fatc-rack-guard tripped %d times, not once" % (counts[-1] - counts[0]))
    ok("fatc-rack-guard tripped once")


def stopped_short(r, volume, tool, within):
    """Held outside the volume, yet not far out: within `within` mm above its
    boundary, the lowest Z from the trip until the driver's snapshot after it
    (before it, an M6 may have left the spindle at safe Z, lower)."""
    z = r["snapshots"]["stopped"]["pos"][2]
    boundary = volume.top + length_of(r, tool)
    first = r["samples"][0]["fatc-rack-guard.trips"]
    after = [s for s in r["samples"] if s["fatc-rack-guard.trips"] > first and
             s["t"] <= r["snapshots"]["stopped"]["t"]]
    lowest = min(s["pos"][2] for s in after + [{"pos": [0, 0, z]}])
    if lowest < boundary - TOLERANCE:
        fail("Z went down to %.3f, below the boundary %.3f" % (lowest, boundary))
    if lowest > boundary + within:
        fail("stopped at Z %.3f, more than %g above the boundary %.3f" % (lowest, within, boundary))
    ok("stopped at Z %.3f, %.3f above the boundary %.3f with T%d" % (lowest, lowest - boundary,
                                                                     boundary, tool))
    return z


def at(r, name, want):
    pos = r["snapshots"][name]["pos"]
    if math.dist(pos, want) > TOLERANCE:
        fail("%s: the machine is at %s, not %s" % (name, pos, want))
    ok("%s: at %s" % (name, want))


def keepout_pin(r, name, want):
    got = r["snapshots"][name]["pins"]["fixed_atc_probe.rack-keepout"]
    if got != want:
        fail("%s: rack-keepout is %s, not %d" % (name, got, want))
    ok("%s: rack-keepout %d" % (name, want))


def main():
    results = load_results(sys.argv[1], sys.argv[3])
    config = json.load(open(sys.argv[2]))
    name = sys.argv[3]
    found = [s for s in results["scenarios"] if s["name"] == name]
    if not found:
        fail("scenario %s did not run: %s" % (name, results["error"]))
    r = found[0]
    volume = Volume(config)
    no_fault(r)
    if name == "keepout_armed":
        keepout_pin(r, "armed", 1)
        words = r["snapshots"]["armed"]["status_file"].get("keepout")
        if words != "rack keep-out armed":
            fail("the status file says %r of the keep-out" % words)
        ok("the status file says: %s" % words)
        spindle_holds(r, 1, "after T1 M6")
    elif name == "keepout_mdi_down":
        never_entered(r, volume)
        tripped(r)
        stopped_short(r, volume, 1, 5.0)
        said(r, "an MDI command would have entered the rack at pocket 3 with T1 (length 30")
    elif name == "keepout_mdi_sideways":
        at(r, "beside", [300.0, 50.0, -80.0])
        never_entered(r, volume)
        tripped(r)
        said(r, "an MDI command would have entered the rack at pocket 6 with T1")
    elif name == "keepout_program":
        never_entered(r, volume)
        tripped(r)
        stopped_short(r, volume, 1, 5.0)
        said(r, "program line 3 would have entered the rack at pocket 4 with T1")
    elif name == "keepout_jog":
        never_entered(r, volume)
        tripped(r)
        stopped_short(r, volume, 1, 5.0)
        said(r, "a jog would have entered the rack at pocket 5 with T1")
    elif name == "keepout_long_tool":
        at(r, "over_the_rack", [150.0, 20.0, 0.0])
        never_entered(r, volume)
        tripped(r)
        stopped_short(r, volume, 6, 5.0)
        said(r, "an MDI command would have entered the rack at pocket 3 with T6 (length 50")
    elif name == "keepout_g53_after_m6":
        # T2 M6 leaves G43 with 35 mm in force; G53 Z-20 is the nose's Z all the same.
        spindle_holds(r, 2, "after T2 M6")
        at(r, "after_g53", [120.0, 80.0, -20.0])
    elif name == "keepout_offsets_after_m6":
        # G20, G55 turned 90 degrees, and the M6's G43 with 35 mm: where the lint puts the nose.
        spindle_holds(r, 2, "after T2 M6")
        at(r, "after_offsets", [101.6, 76.2, -28.5])
    elif name == "keepout_m6_after":
        spindle_holds(r, 1, "after T1 M6 following the stopped moves")
        at(r, "low_over_the_rack", [150.0, 20.0, -20.0])
        never_entered(r, volume)
    elif name == "keepout_lifted":
        keepout_pin(r, "in_the_column", 3)
        at(r, "in_the_column", [150.0, 20.0, -40.0])
        if r["samples"][-1]["fixed_atc_probe.rack-keepout"] != 1:
            fail("the keep-out was not armed again once the lift fell")
        ok("armed again once the lift fell")
    else:
        fail("unknown scenario %s" % name)


if __name__ == "__main__":
    main()
