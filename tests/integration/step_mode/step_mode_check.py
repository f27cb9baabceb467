#!/usr/bin/python3
"""Judges one scenario of the step-by-step run (step_mode.py) from what
LinuxCNC reported: usage: step_mode_check.py RESULTS SCENARIO."""
import json
import re
import sys

P = "fixed_atc_probe."
STEP_TIMEOUT = 2.0  # the run's [FIXED_ATC_PROBE]STEP_TIMEOUT
KINDS = ("rapid", "feed", "open the chuck", "close the chuck")  # of a held step's action
# --plan's lines of a move or a chuck action: "  4  chuck      open".
PLAN_STEP = re.compile(r"^\s*(\d+)\s+(rapid|feed|probe|chuck)\s")
problems = []


def expect(ok, what):
    if not ok:
        problems.append(what)
    return ok


def planned_steps(plan):
    return [int(m.group(1)) for m in map(PLAN_STEP.match, plan["out"].splitlines()) if m]


def held_still(scenario):
    """Between each prompt and its answer LinuxCNC's position and the chuck
    stood as they were at the prompt: nothing moved before Continue."""
    for prompt in scenario["prompts"]:
        during = [s for s in scenario["samples"] if prompt["t"] <= s["t"] <= prompt["answered_at"]]
        expect(len(during) >= 10, "step %d: only %d samples while held" % (prompt["number"],
                                                                         len(during)))
        moved = [s for s in during if max(abs(a - b) for a, b in zip(s["pos"], prompt["pos"])) > 1e-6
                 or s[P + "chuck"] != prompt["chuck"]]
        expect(not moved, "step %d (%s): moved while held, at t=%.3f s: %s" % (
            prompt["number"], prompt["words"], moved[0]["t"], moved[0]["pos"]) if moved else "")
        expect(all(s[P + "waiting-for-operator"] for s in during),
               "step %d: waiting-for-operator dropped while held" % prompt["number"])
    return sum(len([s for s in scenario["samples"]
                    if p["t"] <= s["t"] <= p["answered_at"]]) for p in scenario["prompts"])


def moved_between(scenario):
    """How many of the intervals from one Continue to the next prompt saw LinuxCNC move."""
    prompts = scenario["prompts"]
    moved = 0
    for before, after in zip(prompts, prompts[1:]):
        moved += before["pos"] != after["pos"] or before["chuck"] != after["chuck"]
    return moved


def check_step_change(scenario):
    plan = scenario["plan"]
    expect(plan["code"] == 0, "--plan failed: %s" % plan["err"])
    planned = planned_steps(plan)
    held = [p["number"] for p in scenario["prompts"]]
    expect(held == planned, "steps held %s, --plan's moves and chuck actions %s" % (held, planned))
    expect(all(p["answer"] == "continue" for p in scenario["prompts"]), "a step was not continued")
    samples = held_still(scenario)
    first = scenario["prompts"][0] if scenario["prompts"] else None
    expect(first and first["answered_at"] - first["t"] > 2 * STEP_TIMEOUT,
           "the first step was held less than twice STEP_TIMEOUT")
    # The first step of each kind held past STEP_TIMEOUT (the rest answered at
    # once): a move, a feed, the chuck opened and closed each wait past it.
    firsts = {}
    for p in scenario["prompts"]:
        firsts.setdefault(next((k for k in KINDS if p["action"].startswith(k)), p["action"]), p)
    expect(sorted(firsts) == sorted(KINDS), "the kinds of steps held %s, expected %s" % (
        sorted(firsts), sorted(KINDS)))
    short = [p["number"] for p in firsts.values() if p["answered_at"] - p["t"] <= STEP_TIMEOUT]
    expect(not short, "first steps of a kind held no longer than STEP_TIMEOUT: %s" % short)
    last = scenario["samples"][-1]
    expect(last["tool_in_spindle"] == 2, "LinuxCNC's tool after the change: %s" % last["tool_in_spindle"])
    expect(last[P + "state"] == 1, "the changer is not idle after the change (state %s)" % last[P + "state"])
    expect(abs(last["pos"][2] - -5.0) < 1e-3, "the program's move after M6 did not run: Z %s" % last["pos"][2])
    expect(not any(word in m for m in scenario["messages"]
                   for word in ("STEP_TIMEOUT", "stopped answering", "refused or failed", "fault")),
           "a message says the program aborted: %s" % scenario["messages"])
    return "%d steps held, --plan's %s; %d samples while held, none moved; the first of each kind " \
           "held over STEP_TIMEOUT (%.0f s), the first %.1f s; LinuxCNC moved between %d of %d pairs of prompts; T%d in " \
           "the spindle" % (len(held), "the same numbers" if held == planned else planned, samples,
                            STEP_TIMEOUT, first["answered_at"] - first["t"] if first else 0,
                            moved_between(scenario), max(len(held) - 1, 0), last["tool_in_spindle"])


def check_step_cancel(scenario):
    prompts = scenario["prompts"]
    cancelled = [p for p in prompts if p["answer"] == "cancel"]
    expect(len(cancelled) == 1 and cancelled[0] is prompts[-1], "not one Cancel, last: %s" %
           [p["answer"] for p in prompts])
    held_still(scenario)
    last = scenario["samples"][-1]
    state = scenario["state_file"]
    expect(scenario["fault_pin"], "no fault after Cancel at a held step")
    expect(scenario["chuck_pins"] == [False, False], "the chuck pins after Cancel: %s" %
           scenario["chuck_pins"])
    expect(last["interp"] == 1, "the program did not end (interp %s)" % last["interp"])
    expect(any("cancelled by the operator before step" in m for m in scenario["messages"]),
           "no message of the Cancel: %s" % scenario["messages"])
    expect(cancelled and cancelled[0]["action"].startswith("open the chuck"),
           "not cancelled at the chuck's release")
    # Nothing moved at the held release: T2 is where it was, in the closed chuck,
    # for the changer (uncertain, as after an abort, until the operator says so) and LinuxCNC.
    expect(state["spindle"] == 2 and last["tool_in_spindle"] == 2,
           "the state file's spindle T%s, LinuxCNC's T%s" % (state["spindle"], last["tool_in_spindle"]))
    expect(state.get("uncertain") and state.get("in_progress", {}).get("pocket") == 2,
           "the state file does not say the change was cut off at pocket 2: %s" % state)
    cleared = scenario["cleared_state_file"]
    expect(cleared["spindle"] == scenario["cleared_tool_in_spindle"] == 2 and
           not cleared.get("uncertain"), "after the clear: state %s, LinuxCNC T%s" % (
               cleared, scenario["cleared_tool_in_spindle"]))
    c = cancelled[0] if cancelled else {"words": "?"}
    return "cancelled at %s; fault, the chuck closed, the program ended, T%s in the spindle " \
           "for the changer (uncertain) and LinuxCNC, both T%s after the clear" % (
               c["words"], state["spindle"], scenario["cleared_tool_in_spindle"])


def check_operator_step(scenario):
    run = scenario["operator_commands"]["unload"]
    lines = run["out"].splitlines()
    steps = [line for line in lines if "Step by step, " in line]
    answered = sum(1 for line in lines if line == "continue (--yes)")
    expect(run["code"] == 0, "--operator unload:2 --step --yes exited %d: %s" % (run["code"], run["err"]))
    # Loading Z, loading XY, the chuck's release and its clamp: each held.
    expect(len(steps) == 4, "%d step prompts printed, not 4" % len(steps))
    expect(all(lines[i + 1] == "continue (--yes)" for i, line in enumerate(lines)
               if "Step by step, " in line and i + 1 < len(lines)), "a step prompt not answered")
    expect(scenario["switch_after"] is False or scenario["switch_after"] == 0,
           "the step-by-step pin left %s" % scenario["switch_after"])
    expect(scenario["state_file"]["spindle"] == 0 and scenario["tool_in_spindle"] == 0,
           "the spindle after the unload: state T%s, LinuxCNC T%s" % (
               scenario["state_file"]["spindle"], scenario["tool_in_spindle"]))
    return "%d step prompts printed, %d Continues by --yes; the pin back off" % (len(steps), answered)


def main():
    results = json.load(open(sys.argv[1]))
    name = sys.argv[2]
    if results["error"]:
        print("the run failed: " + results["error"])
        return 1
    scenario = next((s for s in results["scenarios"] if s["name"] == name), None)
    if scenario is None:
        print("no scenario %s in the results" % name)
        return 1
    said = {"step_change": check_step_change, "step_cancel": check_step_cancel,
            "operator_step": check_operator_step}[name](scenario)
    problems[:] = [p for p in problems if p]
    if problems:
        print("\n".join(problems))
        return 1
    print("%s: %s" % (name, said))
    return 0


if __name__ == "__main__":
    sys.exit(main())
