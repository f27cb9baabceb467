#!/usr/bin/env python3
"""Checks one scenario of the long-tool run (integration_long_tool_run, issue
32): top-approach pockets with safe between two of them; T1 80 mm long in
LinuxCNC's tool table would drag its tip through the holders on the way back
to safe, so M6 T1 is refused before anything moves; T2 (30 mm) changes; T3,
whose Z is no length (-12), counts as the longest the config allows and
changes, the operator told so, and the guard gets that length.
   check_long_tool.py RESULTS.json CONFIG.json SCENARIO"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
from check import (fail, in_pockets, load_results, no_fault, nothing_moved, ok, said, scenario,  # noqa: E402
                   spindle_holds)


def chuck_never_opened(r):
    if any(s["fixed_atc_probe.chuck"] for s in r["samples"]):
        fail("the chuck opened")
    ok("the chuck never opened (%d samples)" % len(r["samples"]))


def check_refused(r):
    said(r, "M6 T1 refused: its step")
    said(r, "carries T1 (length 80.0000 mm) with its tip 35.0000 mm below the top of the holder")
    said(r, "nothing moved")
    no_fault(r)
    nothing_moved(r)
    chuck_never_opened(r)
    if any(s["tool_in_spindle"] != 0 for s in r["samples"]):
        fail("LinuxCNC's spindle held a tool")
    ok("the spindle stayed empty, as LinuxCNC reports it")
    if 1 not in in_pockets(r["state_file"]):
        fail("the state file no longer has T1 in pocket 1: %s" % r["state_file"])
    ok("T1 still in pocket 1 (state file)")
    if "t1" not in r.get("programs", {}):
        fail("the program did not end")
    ok("the program ended")


def check_short(r):
    no_fault(r)
    spindle_holds(r, 2, "after M6 T2")
    ok("T2 (30 mm) changed")


def check_no_length(r):
    no_fault(r)
    spindle_holds(r, 3, "after M6 T3")
    said(r, "T3: LinuxCNC's tool table gives Z-12.0000 mm, no length below the spindle nose; the "
            "rack keep-out counts it as 40.0000 mm (the longest tool the config allows)")
    last = r["samples"][-1]
    length = last["fixed_atc_probe.rack-keepout-tool-length"]
    if abs(length - 40.0) > 1e-6:
        fail("the guard's tool length is %g, not the 40 counted" % length)
    ok("the guard holds the volume 40 mm higher for T3, not 12 mm lower")


CHECKS = {"long_tool_refused": check_refused, "long_tool_short_changes": check_short,
          "long_tool_no_length": check_no_length}

if __name__ == "__main__":
    results_path, _, name = sys.argv[1:4]
    CHECKS[name](scenario(load_results(results_path, name), name))
