#!/usr/bin/env python3
"""Checks one scenario of the headless operator's run (integration_operator_run):
`fixed_atc_probe --operator ...` typed against the running machine, its output
and exit status, and what LinuxCNC and the component's files say after.
   check_operator.py RESULTS.json SCENARIO
The run's config has pockets 1 to 3, pocket 3 empty at first start; T7 is
in no pocket (config/sim/sim.tbl: Z20)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
from check import fail, load_results, ok, scenario, tool_table_length  # noqa: E402


def command(r, name, code, *lines):
    """The invocation `name` exited with `code` and printed each of `lines`."""
    run = r.get("operator_commands", {}).get(name)
    if run is None:
        fail("the operator command %s did not run" % name)
    print("--- %s: %s, exit %d\n%s%s---" % (name, " ".join(run["args"][1:]), run["code"], run["out"],
                                         run["err"]))
    if run["code"] != code:
        fail("%s exited %d, expected %d" % (name, run["code"], code))
    for line in lines:
        if line not in run["out"] + run["err"]:
            fail("%s did not print %r" % (name, line))
    ok("%s exited %d and printed %s" % (name, code, lines))
    return run


def check_operator_load(r):
    command(r, "refused", 1, "load of tool 7 into pocket 2 refused: pocket 2 is tool 2's",
            "outcome: refused (exit 1)")
    command(r, "nothing_waits", 1, "Continue: nothing is waiting for the operator",
            "outcome: refused (exit 1)")
    load = command(r, "load", 0, "fixed_atc_probe: load of tool 7 into pocket 3",
                   "prompt: Insert tool 7", "continue (--yes)", "outcome: done (exit 0)")
    # Each prompt printed, then answered: as many answers as prompts.
    prompts = [line for line in load["out"].splitlines() if line.startswith("prompt: ")]
    answers = load["out"].count("continue (--yes)")
    if len(prompts) < 2 or answers != len(prompts):
        fail("%d prompts, %d answers" % (len(prompts), answers))
    ok("%d prompts, each answered once: %s" % (len(prompts), prompts))
    after = r["snapshots"]["after_load"]
    state = after["state_file"]
    if state.get("pockets", {}).get("3") != {"in_pocket": True, "tool": 7} or state.get("spindle") != 0:
        fail("the state file after the load: %s" % state)
    ok("the state file: T7 in pocket 3, the spindle empty")
    if after["tool_in_spindle"] != 0 or after["pins"]["fixed_atc_probe.tool-in-spindle"] != 0:
        fail("LinuxCNC's tool in spindle after the load: %s" % after["tool_in_spindle"])
    ok("LinuxCNC and the component: the spindle empty")
    length = state.get("lengths", {}).get("7")
    table = tool_table_length(r, 7)
    if length is None or abs(length - 20.0) < 1e-6 or abs(table - length) > 1e-4 or \
            abs(r["tool_table"]["7"] - length) > 1e-4:
        fail("T7's length: state %s, tool table file %s, LinuxCNC %s" % (length, table, r["tool_table"]["7"]))
    ok("T7 measured %.4f mm: the state file, the tool table file and LinuxCNC agree" % length)
    if "measured %.4f" % length not in load["out"] and "tool 7 measured" not in load["out"]:
        fail("the load did not print its measurement")
    ok("the outcome printed: tool 7 measured")


def check_operator_cancel(r):
    command(r, "cancel", 0, "fixed_atc_probe: Cancel", "outcome: done (exit 0)")
    command(r, "unload", 4, "prompt: Remove tool 7", "unload of tool 7 cancelled",
            "outcome: cancelled (exit 4)")


def main():
    results_path, name = sys.argv[1:3]
    r = scenario(load_results(results_path, name), name)
    globals()["check_" + name](r)
    print("%s: %.1f s" % (name, r["duration"]))


if __name__ == "__main__":
    main()
