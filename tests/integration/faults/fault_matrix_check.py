#!/usr/bin/env python3
"""Judges one column of a fault-matrix run and prints the whole matrix.

    fault_matrix_check.py RESULTS.json KIND
    fault_matrix_check.py RESULTS.json --table     (prints the matrix only)

Every case of KIND must: end faulted with the chuck closed; flag the spindle
uncertain and say so; keep the state file and the tool table file whole and
consistent; refuse M6 and the load flow with a message while nothing moves;
and, once the operator confirmed what they found, be idle with LinuxCNC and
the changer agreeing on the tool. On a collet-nut magazine, besides: the
spindle stood once the cut settled (LinuxCNC's spindle off, the drive's run
and speed off, the real speed 0, the changer not asking for it); the nuts
the simulated magazine holds are what the change's plan allows at the step
cut (collet_outcomes); and after the confirm the state file holds what the
magazine holds. Exits 1 naming the first case that fails."""
import json
import re
import sys

# Generous: these machines are shared. The guard's own timeout is 0.5 s and
# the executor looks at it once a second.
CHUCK_CLOSES_WITHIN = {"estop": 2.0, "abort": 2.0, "kill": 2.0}
PROGRAM_STOPS_WITHIN = {"estop": 5.0, "abort": 5.0, "kill": 5.0}
# The guard holds the drive at once on an estop or abort; a killed component
# is taken for gone after the guard's 0.5 s; the ramp to 0 is 0.24 s.
SPINDLE_STANDS_WITHIN = {"estop": 3.0, "abort": 3.0, "kill": 3.0}
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


def collet_outcomes(plan, at, held, target):
    """What a cut of a collet-nut change at step `at` may leave, as
    (nut on the spindle, {pocket: holds its nut}) (a tool's nut lives in the
    pocket of its number): a nut comes off only while the spindle reverses
    and on only while it turns forward, on the first plunge to the engage Z
    after the start (spin-off, where the spindle starts, is above the window
    where the thread engages). A cut during that plunge may find either."""
    spindle = [(n, what.split()[0]) for n, kind, what in plan if kind == "spindle"]
    reverse = next(n for n, code in spindle if code == "M4")
    forward = next(n for n, code in spindle if code == "M3" and n > reverse)
    plunge_off = next(n for n, kind, _ in plan if kind == "feed" and n > reverse)
    plunge_on = next(n for n, kind, _ in plan if kind == "feed" and n > forward)
    holding = (held, {held: False, target: True})
    empty = (0, {held: True, target: True})
    holding_next = (target, {held: True, target: False})
    if at < plunge_off:
        return [holding]
    if at == plunge_off:
        return [holding, empty]
    if at < plunge_on:
        return [empty]
    if at == plunge_on:
        return [empty, holding_next]
    return [holding_next]


def collet_problems(case, plan):
    """The spindle stood after the cut; the magazine holds what the plan
    allows; after the confirm the changer believes what the magazine holds."""
    found = []
    kind = case["kind"]
    spindle = case["after_cut"]["spindle"]
    if spindle["on"] or spindle["drive_on"] or spindle["drive_speed"] or spindle["speed"] \
            or spindle["changer_spindle"]:
        found.append("the spindle did not stand after the cut: %s" % spindle)
    if case["spindle_stopped_after"] is None:
        found.append("the spindle did not stand within %.0f s of the cut: %s" % (
            case["spindle_turning"]["after"], case["spindle_turning"]))
    elif case["spindle_stopped_after"] > SPINDLE_STANDS_WITHIN.get(kind, 3.0):
        found.append("the spindle stood %.2f s after the cut" % case["spindle_stopped_after"])
    nuts = case["found"]
    seen = (nuts["spindle"], {int(p): v for p, v in nuts["pockets"].items()
                              if int(p) in (case["from"], case["to"])})
    allowed = collet_outcomes(plan, case["step"], case["from"], case["to"])
    if seen not in allowed:
        found.append("the magazine holds %s, the plan allows %s" % (seen, allowed))
    done = case["confirmed"]
    state = done["files"]["state_file"]
    magazine = done["found"]
    if state.get("spindle") != magazine["spindle"]:
        found.append("after the confirm the state file says T%s, the magazine's spindle T%s" % (
            state.get("spindle"), magazine["spindle"]))
    for pocket, holds in magazine["pockets"].items():
        entry = state.get("pockets", {}).get(str(pocket), {})
        believed = entry.get("in_pocket") and entry.get("tool") == int(pocket)
        if bool(believed) != holds:
            found.append("after the confirm the state file has pocket %s %s, the magazine %s" % (
                pocket, entry, "its nut" if holds else "no nut"))
    return found


def problems_of(case, plan=None):
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
    if "found" in case:
        found += collet_problems(case, plan)
    return found + confirmed_problems(case)


def cell(case, plan):
    """One cell of the printed matrix."""
    if problems_of(case, plan):
        return "FAIL"
    if case["kind"] == "restart":
        return "ok T%d" % case["confirmed"]["spindle"]
    if case["kind"] == "hold":
        return "ok T%d" % case["after_hold"]["changer_tool"]
    if case["kind"] == "spindle":
        return "ok fault, Z >= %.0f" % case["after"]["start_z"]
    if "found" in case:
        return "ok %.2f/%.2f T%d>T%d" % (case["spindle_stopped_after"], case["program_stopped_after"],
                                         case["found"]["spindle"], case["confirmed"]["spindle"])
    return "ok %.2f/%.2f T%d" % (case["chuck_closed_after"], case["program_stopped_after"],
                                 case["confirmed"]["spindle"])


def print_matrix(results):
    kinds = []
    for case in results["cases"]:
        if case["kind"] not in kinds:
            kinds.append(case["kind"])
    cells = {(c["kind"], c["step"]): cell(c, results["plan"]) for c in results["cases"]}
    width = 20
    if results.get("collet_nut"):
        print("fault matrix, collet nuts, M6 between tools 1 and 2: cell = spindle stood / program "
              "stopped (s after the cut), the nut on the spindle found > the tool confirmed")
    else:
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
        for problem in problems_of(case, results["plan"]):
            print("FAIL: %s at step %d (%s): %s" % (kind, case["step"], " ".join(case["what"]), problem))
            failed += 1
    print("%s: %d cases, %d problems" % (kind, len(cases), failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
