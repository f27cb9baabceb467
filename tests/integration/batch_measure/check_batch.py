#!/usr/bin/env python3
"""Checks one scenario of the measure-all run (integration_batch_run) against
what LinuxCNC reported: its tool table (in memory and the file it wrote), its
tool in spindle through the batch, the sampled positions, the component's
batch-done / batch-total / state pins, its messages, its state and status files.
   check_batch.py RESULTS.json CONFIG.json SCENARIO
CONFIG.json is the run's config (three pockets, T1 to T3)."""
import json
import math
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
from check import (Rack, distinct, load_results, fail, measured_to_truth, no_fault, ok, said, scenario,  # noqa: E402
                   sensor_truth, spindle_holds, tool_table_length, visits_in_order)

P = "fixed_atc_probe."
# The lengths each scenario sets by G10 L1 before its batch: what a tool keeps
# when the batch leaves it alone.
BEFORE = {1: 30.0, 2: 35.0, 3: 40.0}
AWAY = 1.0  # mm: farther than this from a pocket, the spindle never went there


def batch_samples(r):
    return [s for s in r["samples"] if s[P + "batch-total"]]


def measured(r, rack, tools, what):
    """Each of `tools` has the sensor's length in LinuxCNC's tool table (the file
    and stat agree); every other tool kept the length it had before the batch."""
    for tool in tools:
        length = measured_to_truth(r, rack.c, tool, what)
        if abs(r["tool_table"][str(tool)] - length) > 1e-6:
            fail("LinuxCNC holds %.4f for tool %d, its file %.4f" % (r["tool_table"][str(tool)], tool, length))
    for tool, before in BEFORE.items():
        if tool in tools:
            continue
        for where, length in (("file", tool_table_length(r, tool)),
                              ("stat", r["tool_table"][str(tool)])):
            if abs(length - before) > 1e-6:
                fail("%s: tool %d was not to be measured, LinuxCNC's %s has %.4f (was %.4f)" % (
                    what, tool, where, length, before))
        ok("%s: tool %d left alone, still %.4f in LinuxCNC's tool table (file and stat)" % (what, tool, before))


def fetched_and_returned(r, rack, tools):
    """In order, each tool fetched out of its pocket and put back (every waypoint of
    both legs from the config); LinuxCNC's tool in spindle 0, T, 0, T', ... 0."""
    route = []
    for tool in tools:
        route += rack.retrieve_waypoints(tool) + rack.return_waypoints(tool)
    visits_in_order(r["samples"], route)
    ok("fetched and returned, in order: %s" % tools)
    wanted = [0]
    for tool in tools:
        wanted += [tool, 0]
    went = distinct(r["samples"], "tool_in_spindle")
    if went != wanted:
        fail("LinuxCNC's tool in spindle went %s, expected %s" % (went, wanted))
    ok("LinuxCNC's tool in spindle went %s" % went)


def never_near(r, rack, tools):
    for tool in tools:
        for name, target in (("pocket", rack.pocket(tool)), ("side of pocket", rack.side(tool))):
            closest = min(r["samples"], key=lambda s: math.dist(s["pos"], target))
            if math.dist(closest["pos"], target) < AWAY:
                fail("the spindle went to %s %d %s (t=%.3f: %s)" % (name, tool, target, closest["t"],
                                                                   closest["pos"]))
        ok("never near pocket %d (tool %d not fetched)" % (tool, tool))


def progress(r, total, wanted_done):
    """batch-done while batch-total is set, state 6 meanwhile, total 0 again at the end."""
    during = batch_samples(r)
    if not during:
        fail("batch-total was never set")
    totals = distinct(during, P + "batch-total")
    if totals != [total]:
        fail("batch-total went %s, expected %d" % (totals, total))
    done = distinct(during, P + "batch-done")
    if done != wanted_done:
        fail("batch-done went %s of %d, expected %s" % (done, total, wanted_done))
    # A sample reads its pins one after another: at the window's first and
    # last sample the component may have changed batch-total but not yet state.
    states = distinct(during[1:-1] if len(during) > 2 else during, P + "state")
    if states != [6]:
        fail("the state pin was %s while the batch ran, expected 6 (measuring)" % states)
    if not all(s[P + "can-cancel"] for s in during):
        fail("can-cancel was off while measuring")
    last = r["samples"][-1]
    if last[P + "batch-total"] != 0 or last[P + "state"] != 1:
        fail("after the batch: batch-total %s, state %s" % (last[P + "batch-total"], last[P + "state"]))
    ok("batch-done went %s of %d, state 6 and can-cancel on meanwhile; total 0 and idle after"
       % (done, total))


def files_consistent(r, rack):
    """The state file: the spindle empty, every pocket holding its tool; the status file idle."""
    state = r["state_file"]
    wanted = {str(p): {"in_pocket": True, "tool": t} for p, t in rack.first_tools().items()}
    if state.get("spindle") != 0 or state.get("pockets") != wanted or "in_progress" in state or \
            state.get("uncertain"):
        fail("the state file after the batch: %s" % state)
    ok("the state file: spindle empty, pockets %s" % {k: v["tool"] for k, v in state["pockets"].items()})
    batch = r["status_file"].get("batch")
    if (batch or {}).get("total") != 0:
        fail("the status file's batch after the batch: %s" % batch)
    ok("the status file's batch after the batch: %s" % batch)


def reported(r, line):
    said(r, line)
    return next(m for m in r["messages"] if line in m)


def reports_truth(report, rack, tool, after=""):
    """The report gives `tool` the sensor's true length (within the 0.005 a
    probe may miss it by, as measured_to_truth), followed by `after`."""
    found = re.search(r"T%d (-?[0-9.]+) mm%s" % (tool, re.escape(after)), report)
    truth = sensor_truth(rack.c)
    if not found or abs(float(found.group(1)) - truth) > 0.005:
        fail("the report does not give T%d %.4f mm%s: %s" % (tool, truth, after, report))


def check_batch_all(results, r, rack):
    no_fault(r)
    progress(r, 3, [0, 1, 2, 3])
    one = r["snapshots"]["one done"]
    if one["status_file"].get("batch") != {"done": 1, "total": 3}:
        fail("the status file with one tool done: batch %s" % one["status_file"].get("batch"))
    ok("the status file with one tool done: batch %s" % one["status_file"]["batch"])
    for n, tool in enumerate([1, 2, 3], 1):
        said(r, "measure all: tool %d (%d of 3)" % (tool, n))
    report = reported(r, "measure all done: 3 of 3 tools")
    for tool in (1, 2, 3):
        reports_truth(report, rack, tool, " (first measurement)")
    ok("the report lists T1, T2, T3 at the sensor's length, each a first measurement: %s" % report)
    measured(r, rack, [1, 2, 3], "measure all")
    fetched_and_returned(r, rack, [1, 2, 3])
    spindle_holds(r, 0, "after measure all")
    ok("the spindle is empty (LinuxCNC and the changer)")
    files_consistent(r, rack)
    lengths = r["state_file"].get("lengths", {})
    if sorted(lengths) != ["1", "2", "3"]:
        fail("the state file's measured lengths: %s" % lengths)
    ok("the state file records T1 to T3 as measured: %s" % lengths)


def check_batch_cancel(results, r, rack):
    no_fault(r)
    at = r["snapshots"]["cancel"]
    if at["pins"][P + "batch-done"] != 0 or at["pins"][P + "pocket-served"] != 1 or \
            at["tool_in_spindle"] != 0:
        fail("cancel was not pressed while tool 1 was being fetched: %s" % at["pins"])
    ok("cancel pressed at t=%.2f, while tool 1 was being fetched (pocket-served 1, batch-done 0)"
       % at["t"])
    said(r, "measure all stops once tool 1 is back in its pocket")
    report = reported(r, "measure all cancelled after 1 of 3 tools")
    reports_truth(report, rack, 1)
    if "T2" in report or "T3" in report:
        fail("the report should list T1 alone: %s" % report)
    ok("the report lists T1 alone: %s" % report)
    for tool in (2, 3):
        if any("measure all: tool %d" % tool in m for m in r["messages"]):
            fail("tool %d was started: %s" % (tool, r["messages"]))
    progress(r, 3, [0, 1])
    measured(r, rack, [1], "cancelled measure all")
    fetched_and_returned(r, rack, [1])
    never_near(r, rack, [2, 3])
    # The batch ended with tool 1 back: after it, nothing moved into the rack.
    spindle_holds(r, 0, "after the cancelled measure all")
    ok("the spindle is empty (LinuxCNC and the changer)")
    files_consistent(r, rack)


def check_batch_program(results, r, rack):
    no_fault(r)
    said(r, "measure all skips what is not in the rack: ")
    skip = next(m for m in r["messages"] if "measure all skips" in m)
    if "5" not in skip or "7" not in skip:
        fail("the skip message does not name T5 and T7: %s" % skip)
    ok("skipped: %s" % skip)
    said(r, "measure all: tool 2 (1 of 1)")
    report = reported(r, "measure all done: 1 of 1 tools")
    reports_truth(report, rack, 2)
    progress(r, 1, [0, 1])
    measured(r, rack, [2], "measure all of the loaded program's tools")
    fetched_and_returned(r, rack, [2])
    never_near(r, rack, [1, 3])
    spindle_holds(r, 0, "after measuring the program's tools")
    files_consistent(r, rack)


def main():
    results_path, config_path, name = sys.argv[1:4]
    results = load_results(results_path, name)
    rack = Rack(json.load(open(config_path)))
    r = scenario(results, name)
    globals()["check_" + name](results, r, rack)
    print("%s: %.1f s, %d samples" % (name, r["duration"], len(r["samples"])))


if __name__ == "__main__":
    main()
