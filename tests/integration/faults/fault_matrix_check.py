#!/usr/bin/env python3
"""Judges one column of a fault-matrix run and prints the whole matrix.

    fault_matrix_check.py RESULTS.json KIND
    fault_matrix_check.py RESULTS.json --table     (prints the matrix only)

Every case of KIND must: end faulted with the chuck closed; flag the spindle
uncertain and say so; keep the state file and the tool table file whole and
consistent; refuse M6 and the load flow with a message while nothing moves;
and, once the operator confirmed what they found, be idle with LinuxCNC and
the changer agreeing on the tool. Exits 1 naming the first case that fails."""
import json
import re
import sys

# Generous: these machines are shared. The guard's own timeout is 0.5 s and
# the executor looks at it once a second.
CHUCK_CLOSES_WITHIN = {"estop": 2.0, "abort": 2.0, "kill": 2.0}
PROGRAM_STOPS_WITHIN = {"estop": 5.0, "abort": 5.0, "kill": 5.0}
TOOL_LINE = re.compile(r"^T\d+ P\d+( [A-Z][-+0-9.eE]+)*( ;.*)?$")


def hold_problems(case):
    """A feed hold and resume cuts nothing off: the change ends as asked."""
    after = case["after_hold"]
    found = []
    if after["fault"] or after["state"] != 1:
        found.append("not idle after the resumed change (state %s): %s" % (after["state"], after["messages"]))
    if not (after["linuxcnc_tool"] == after["changer_tool"] == case["to"]):
        found.append("LinuxCNC says T%d, the changer T%d, asked for T%d" % (
            after["linuxcnc_tool"], after["changer_tool"], case["to"]))
    if after["chuck"]:
        found.append("the chuck is open after the change")
    state = after["files"]["state_file"]
    if state.get("uncertain") or state.get("in_progress") or state.get("spindle") != case["to"]:
        found.append("the state file after the change: %s" % state)
    return found


def spindle_problems(case):
    """A spindle that never reports stopped: fault, the chuck never open,
    nothing lower than where M6 was called (it rises to safe Z and crosses at
    it while it waits)."""
    after = case["after"]
    found = []
    if not after["fault"]:
        found.append("no fault when the spindle never stopped")
    if after["lowest_z"] < after["start_z"] - 1e-3 or after["end_z"] < after["start_z"] - 1e-3:
        found.append("Z went down to %.3f (from %.3f) while the spindle turned"
                     % (after["lowest_z"], after["start_z"]))
    if after["chuck_ever"]:
        found.append("the chuck opened while the spindle turned")
    if not any("did not stop" in m for m in after["messages"]):
        found.append("no message says the spindle did not stop: %s" % after["messages"])
    return found + confirmed_problems(case)


def confirmed_problems(case):
    done = case["confirmed"]
    found = []
    if not (done["linuxcnc_tool"] == done["changer_tool"] == done["spindle"]):
        found.append("after the confirmation LinuxCNC says T%d, the changer T%d, the operator T%d" % (
            done["linuxcnc_tool"], done["changer_tool"], done["spindle"]))
    after = done["files"]["state_file"]
    if after.get("uncertain") or after.get("in_progress") or after.get("spindle") != done["spindle"]:
        found.append("the state file after the confirmation: %s" % after)
    return found


def problems_of(case):
    """What is wrong with one case, in words; empty when it passed."""
    kind = case["kind"]
    if "error" in case:
        return ["the run failed: %s" % case["error"]]
    if kind == "hold":
        return hold_problems(case)
    if kind == "spindle":
        return spindle_problems(case)
    found = []
    cut = case["after_cut"]
    if not cut["fault"]:
        found.append("not faulted after the cut (state %s)" % cut["state"])
    if cut["chuck"]:
        found.append("the chuck (fatc-chuck) is open after the cut")
    if kind in CHUCK_CLOSES_WITHIN and case["chuck_closed_after"] > CHUCK_CLOSES_WITHIN[kind]:
        found.append("the chuck closed %.2f s after the cut" % case["chuck_closed_after"])
    if kind in PROGRAM_STOPS_WITHIN and case["program_stopped_after"] > PROGRAM_STOPS_WITHIN[kind]:
        found.append("the program stopped %.2f s after the cut" % case["program_stopped_after"])
    state = cut["files"]["state_file"]
    if "unreadable" in state:
        found.append("state file unreadable after the cut: %s" % state["unreadable"])
    else:
        progress = state.get("in_progress") or {}
        if progress.get("sequence") != "M6 T%d" % case["to"]:
            found.append("the state file does not name the cut-off M6 T%d: %s" % (case["to"], progress))
        if state.get("spindle") not in (case["from"], 0, case["to"]):
            found.append("the state file says T%s in the spindle" % state.get("spindle"))
    said = " ".join(cut["messages"])
    if "not certain" not in said or "cut off during M6 T%d" % case["to"] not in said:
        found.append("no message says the spindle is uncertain and what was cut off: %s" % cut["messages"])
    table = cut["files"]["tool_table"].splitlines()
    bad = [line for line in table if line.strip() and not TOOL_LINE.match(line.strip())]
    if bad or len([line for line in table if line.strip()]) < 6:
        found.append("the tool table file is damaged: %s" % (bad or table))
    refusal = case["refusal"]
    if not any("refused" in m for m in refusal["m6_messages"]):
        found.append("M6 was not refused with a message: %s" % refusal["m6_messages"])
    if not any("refused" in m for m in refusal["load_messages"]):
        found.append("the load flow was not refused with a message: %s" % refusal["load_messages"])
    if refusal["moved"] > 1e-6 or not refusal["fault_after"]:
        found.append("the refused M6 moved %.3f or cleared the fault" % refusal["moved"])
    return found + confirmed_problems(case)


def cell(case):
    """One cell of the printed matrix."""
    if problems_of(case):
        return "FAIL"
    if case["kind"] == "restart":
        return "ok T%d" % case["confirmed"]["spindle"]
    if case["kind"] == "hold":
        return "ok T%d" % case["after_hold"]["changer_tool"]
    if case["kind"] == "spindle":
        return "ok fault, Z >= %.0f" % case["after"]["start_z"]
    return "ok %.2f/%.2f T%d" % (case["chuck_closed_after"], case["program_stopped_after"],
                                 case["confirmed"]["spindle"])


def print_matrix(results):
    kinds = []
    for case in results["cases"]:
        if case["kind"] not in kinds:
            kinds.append(case["kind"])
    cells = {(c["kind"], c["step"]): cell(c) for c in results["cases"]}
    width = 20
    print("fault matrix, M6 between tools %s: cell = chuck closed / program stopped "
          "(s after the cut), tool confirmed" % "1 and 2")
    print("%-4s %-6s %-28s" % ("step", "kind", "what") + "".join("%-*s" % (width, k) for k in kinds))
    for number, kind, what in [[0, "-", "before the first step"]] + results["plan"]:
        if not any((k, number) in cells for k in kinds):
            continue
        print("%-4d %-6s %-28s" % (number, kind, what[:28]) +
              "".join("%-*s" % (width, cells.get((k, number), "-")) for k in kinds))


def main():
    results = json.load(open(sys.argv[1]))
    kind = sys.argv[2]
    print_matrix(results)
    if kind == "--table":
        return 0
    if results.get("error"):
        print("FAIL: the run stopped: %s" % results["error"])
        return 1
    cases = [c for c in results["cases"] if c["kind"] == kind]
    if not cases:
        print("FAIL: no %s case ran" % kind)
        return 1
    failed = 0
    for case in cases:
        for problem in problems_of(case):
            print("FAIL: %s at step %d (%s): %s" % (kind, case["step"], " ".join(case["what"]), problem))
            failed += 1
    print("%s: %d cases, %d problems" % (kind, len(cases), failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
