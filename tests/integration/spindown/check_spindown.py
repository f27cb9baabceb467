#!/usr/bin/env python3
"""Checks one scenario of the spin-down run (scenarios_spindown.json: the
simulated spindle ramps at 4000 rpm per second and reports zero-speed, which
config.json reads) against what LinuxCNC reported: M6 moved while the spindle
ran down, only up to safe Z and across at safe Z with the chuck closed, and
went lower only once the spindle stood; a spindle that does not stand in time
faults the change with nothing entered.
   check_spindown.py RESULTS.json CONFIG.json SCENARIO
Prints what it checked; exits 1 on the first failed expectation."""
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
from check import TOLERANCE, fail, load_results, near, ok, said, scenario  # noqa: E402

ZERO = "fixed_atc_probe.zero-speed"
DID_NOT_STOP = "the spindle did not stop within spindle_stop_timeout_seconds (zero-speed off)"


def spindle_off(samples):
    """The sample where M6's M5 turned LinuxCNC's spindle off."""
    for a, b in zip(samples, samples[1:]):
        if a["spindle.0.on"] and not b["spindle.0.on"]:
            return b
    fail("LinuxCNC's spindle never went off")


def only_at_safe_z(samples, safe_z):
    """While the spindle turned: Z only rose, XY moved only at safe Z, the chuck
    stayed closed."""
    lowest = samples[0]["pos"][2]
    for a, b in zip(samples, samples[1:]):
        if b["pos"][2] < lowest - TOLERANCE:
            fail("Z went down to %.3f at %.2f s while the spindle turned" % (b["pos"][2], b["t"]))
        lowest = max(lowest, b["pos"][2])
        across = math.dist(a["pos"][:2], b["pos"][:2]) > TOLERANCE
        if across and abs(a["pos"][2] - safe_z) > TOLERANCE:
            fail("XY moved at Z %.3f (safe Z %.3f) at %.2f s while the spindle turned"
                 % (a["pos"][2], safe_z, a["t"]))
        if b["fatc-chuck-guard.chuck"] or b["fixed_atc_probe.chuck"]:
            fail("the chuck opened at %.2f s while the spindle turned" % b["t"])


def check_spindown(r, config):
    samples = r["samples"]
    off = spindle_off(samples)
    after = [s for s in samples if s["t"] >= off["t"]]
    stood = next((s for s in after if s[ZERO]), None)
    if stood is None:
        fail("zero-speed never came after the spindle went off at %.2f s" % off["t"])
    moved = next((s for s in after if not near(s["pos"], off["pos"])), None)
    if moved is None or moved["t"] >= stood["t"]:
        fail("nothing moved before the spindle stood at %.2f s (first move at %s)"
             % (stood["t"], moved and moved["t"]))
    turning = [s for s in after if s["t"] < stood["t"]]
    only_at_safe_z(turning, config["safe"]["z"])
    ok("M5 at %.2f s; the first move at %.2f s; zero-speed at %.2f s: %.2f s of the run-down moved, "
       "only up to safe Z and across at it, the chuck closed"
       % (off["t"], moved["t"], stood["t"], stood["t"] - moved["t"]))
    reached = turning[-1]["pos"]
    ok("where the spindle stood: %s, at safe Z" % [round(v, 3) for v in reached])
    last = samples[-1]
    if last["tool_in_spindle"] != 2 or last["fixed_atc_probe.tool-in-spindle"] != 2:
        fail("LinuxCNC has T%d in the spindle, the changer T%d, expected T2"
             % (last["tool_in_spindle"], last["fixed_atc_probe.tool-in-spindle"]))
    if any(s["fixed_atc_probe.fault"] for s in samples):
        fail("the changer faulted")
    ok("the change went on from there: T2 in the spindle, LinuxCNC agrees, no fault")


def check_spindown_timeout(r, config):
    samples = r["samples"]
    off = spindle_off(samples)
    faulted = next((s for s in samples if s["t"] >= off["t"] and s["fixed_atc_probe.fault"]), None)
    if faulted is None:
        fail("no fault after the spindle went off at %.2f s" % off["t"])
    if faulted[ZERO]:
        fail("zero-speed was on at the fault (%.2f s): the spindle stood" % faulted["t"])
    said(r, DID_NOT_STOP)
    after = [s for s in samples if s["t"] >= off["t"]]
    only_at_safe_z(after, config["safe"]["z"])
    ok("from M5 (%.2f s) to the fault (%.2f s) and after: nothing below safe Z, the chuck closed"
       % (off["t"], faulted["t"]))
    last = samples[-1]
    if last["interp"] != 1 or last["tool_in_spindle"] != 2 or last["fixed_atc_probe.tool-in-spindle"] != 2:
        fail("the program should have stopped with T2 still in the spindle: %s" % last)
    if r["state_file"].get("uncertain"):
        fail("the state file marks the spindle uncertain, though nothing entered: %s" % r["state_file"])
    ok("the program stopped; T2 still in the spindle for LinuxCNC and the changer; nothing uncertain")


def main():
    results_path, config_path, name = sys.argv[1:4]
    results = load_results(results_path, name)
    if results.get("error"):
        fail("the run failed: %s" % results["error"])
    globals()["check_" + name](scenario(results, name), json.load(open(config_path)))


if __name__ == "__main__":
    main()
