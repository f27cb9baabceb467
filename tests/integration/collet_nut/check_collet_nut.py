#!/usr/bin/env python3
"""Checks one scenario of the collet-nut run (config/sim/collet_nut.json, the
simulated magazine of config/sim/sim_nut.hal) against what LinuxCNC and the
simulated magazine reported: the tool in the spindle, the spindle's turning
sampled with the joints' positions, the magazine's nuts against the
component's tools, and each failure's fault.
   check_collet_nut.py RESULTS.json CONFIG.json SCENARIO
   check_collet_nut.py --recorded RECORDER.txt CONFIG.json   (recorder.hal's every servo period)
Prints what it checked with the figures; exits 1 on the first failed expectation."""
import json
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
from check import (TOLERANCE, Rack, distinct, fail, handshake_complete, loading, main, near, no_fault, ok,  # noqa: E402
                   program_completed, rising, said)

NUT = "fatc-sim-nut."
JOINTS = ["joint.%d.pos-fb" % k for k in range(3)]
SERVED = "fixed_atc_probe.pocket-served"
SIM_NUT_HAL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                           "config", "sim", "sim_nut.hal")
# The tools of collet_nut.tbl: 1 to 6 in pockets 1 to 6; 7 and 8 have none.
POCKET_OF = {t: t for t in range(1, 7)}
# The magazine's faults (fatc_sim_nut's pins), sampled by every scenario.
FAULTS = ["reverse", "cross-thread", "stall"] + ["missing-%d" % k for k in range(6)]


def joints(s):
    return [s[j] for j in JOINTS]


def turning(s):
    """The spindle runs or is asked to: the guard lets it, or motion or the
    simulated spindle has a speed."""
    return bool(s["fatc-spindle-guard.spindle-on"]) or s["fatc-spindle-guard.speed-out"] != 0.0 \
        or s["spindle.0.speed-out"] != 0.0 or s[NUT + "speed-out"] != 0.0


def stretches(samples):
    """The runs of samples with the spindle turning, in order."""
    found, current = [], None
    for s in samples:
        if turning(s):
            if current is None:
                current = []
                found.append(current)
            current.append(s)
        else:
            current = None
    return found


def off_the_pocket(rack, pocket, at):
    """Why the nose at `at` (X, Y, Z) is not over `pocket` (X and Y within
    TOLERANCE) between its engage Z and safe Z; None when it is."""
    if pocket not in rack.pockets:
        return "with no pocket served (%s) at X %.4f Y %.4f Z %.4f" % (pocket, at[0], at[1], at[2])
    x, y, z = rack.pocket(pocket)
    safe_z = rack.c["safe"]["z"]
    if abs(at[0] - x) > TOLERANCE or abs(at[1] - y) > TOLERANCE or not z - TOLERANCE <= at[2] <= safe_z + TOLERANCE:
        return "at X %.4f Y %.4f Z %.4f, not over pocket %d (X %.3f Y %.3f) between its engage Z %.3f and " \
            "safe Z %.3f" % (at[0], at[1], at[2], pocket, x, y, z, safe_z)
    return None


def only_over_the_served_pocket(samples, rack):
    """Every sample with the spindle turning stands over the pocket the
    component serves, between its engage Z and safe Z."""
    turning_samples = [s for s in samples if turning(s)]
    for s in turning_samples:
        off = off_the_pocket(rack, s[SERVED], joints(s))
        if off:
            fail("the spindle turned %s, t=%.3f" % (off, s["t"]))
    gaps = [b["t"] - a["t"] for a, b in zip(samples, samples[1:])]
    ok("%d samples of %d with the spindle turning, each over the served pocket (within %.2f mm) between "
       "its engage Z and safe Z; samples %.1f ms apart on average, %.1f ms at most"
       % (len(turning_samples), len(samples), TOLERANCE, 1000 * sum(gaps) / max(len(gaps), 1),
          1000 * max(gaps, default=0.0)))


def turn_of(run, rack):
    """(pocket, 1 forward or -1 reverse) of a run of samples with the spindle
    turning, checked against the config: one direction at the leg's speed
    (load_rpm forward, unload_rpm in reverse), as far down as the pocket's
    engage Z, as high as spin-off forward (a load stops there) and the rise
    after unloading in reverse."""
    chuck = rack.c["chuck"]
    pocket = run[0][SERVED]
    speeds = sorted({s["spindle.0.speed-out"] for s in run if s["spindle.0.speed-out"] != 0.0})
    if len(speeds) != 1 or speeds[0] not in (chuck["load_rpm"], -chuck["unload_rpm"]):
        fail("a turn of the spindle over pocket %d at the speeds %s (load_rpm %s, unload_rpm %s)"
             % (pocket, speeds, chuck["load_rpm"], chuck["unload_rpm"]))
    forward = speeds[0] > 0
    z = rack.pocket(pocket)[2]
    top = z + chuck["spin_off_offset_z" if forward else "rise_after_unload_offset_z"]
    heights = [joints(s)[2] for s in run]
    if abs(min(heights) - z) > TOLERANCE or abs(max(heights) - top) > TOLERANCE:
        fail("over pocket %d the spindle turned %s from Z %.4f to %.4f, expected the engage Z %.3f to %.3f"
             % (pocket, "forward" if forward else "in reverse", min(heights), max(heights), z, top))
    # The plunge starts once the spindle is at speed (config's sensors.at_speed).
    spin_off = z + chuck["spin_off_offset_z"]
    plunging = next(i for i, s in enumerate(run) if joints(s)[2] < spin_off - TOLERANCE)
    if not any(s["fixed_atc_probe.spindle-at-speed"] for s in run[:plunging]):
        fail("over pocket %d the plunge began below spin-off (Z %.3f) before spindle-at-speed, t=%.3f"
             % (pocket, spin_off, run[plunging]["t"]))
    return pocket, 1 if forward else -1


def spindle_stopped(s, what):
    """The spindle stands: motion's and the guard's commands and the simulated spindle's real speed."""
    if s["spindle.0.speed-out"] != 0.0 or s["fatc-spindle-guard.spindle-on"] or \
            s["fatc-spindle-guard.speed-out"] != 0.0 or s[NUT + "speed-out"] != 0.0:
        fail("%s the spindle is not stopped: spindle.0.speed-out %s, fatc-spindle-guard.spindle-on %s, "
             "speed-out %s, the simulated spindle's real speed %s" % (
                 what, s["spindle.0.speed-out"], s["fatc-spindle-guard.spindle-on"],
                 s["fatc-spindle-guard.speed-out"], s[NUT + "speed-out"]))
    ok("%s the spindle stands: spindle.0.speed-out 0, fatc-spindle-guard.spindle-on off, real speed 0" % what)


def magazine(s):
    """What the simulated magazine holds: pocket -> a nut in it, and the pocket
    number the nut on the spindle came from (0 none)."""
    return {p: bool(s[NUT + "nut-in-pocket-%d" % (p - 1)]) for p in range(1, 7)}, \
        s[NUT + "nut-on-spindle-from"] if s[NUT + "nut-on-spindle"] else 0


def magazine_agrees(s, spindle_tool, what):
    """The nuts are where the component's tools are: every pocket full but the
    one whose tool the spindle holds; that nut on the spindle, seated."""
    pockets, on_spindle = magazine(s)
    from_pocket = POCKET_OF.get(spindle_tool, 0)
    wanted = {p: p != from_pocket for p in range(1, 7)}
    if pockets != wanted or on_spindle != from_pocket or (from_pocket and not s[NUT + "seated"]):
        fail("%s: the magazine holds nuts in %s, on the spindle the nut of pocket %d (seated %s); "
             "the component's tool in the spindle is T%d" % (
                 what, [p for p in pockets if pockets[p]], on_spindle, s[NUT + "seated"], spindle_tool))


def sim_values():
    """config/sim/sim_nut.hal's setp of fatc-sim-nut: pin -> value."""
    values = {}
    for line in open(SIM_NUT_HAL):
        m = re.match(r"setp (fatc-sim-nut\.\S+) (\S+)", line)
        if m:
            values[m.group(1)] = float(m.group(2))
    return values


def check_collet_magazine(r, rack):
    pockets, on_spindle = magazine(r["samples"][-1])
    if not all(pockets.values()) or on_spindle:
        fail("the magazine starts with nuts in %s, on the spindle %d" % (pockets, on_spindle))
    ok("the simulated magazine starts with a nut in each of pockets 1 to 6, none on the spindle")
    if r["samples"][-1]["fixed_atc_probe.tool-in-spindle"] != 0:
        fail("the component starts with T%d in the spindle" % r["samples"][-1]["fixed_atc_probe.tool-in-spindle"])
    ok("the component starts with the spindle empty")


# The program's changes (collet_changes.ngc) and what the spindle turns for
# them, in order: each pocket screwed on forward, then off in reverse.
CHANGES = [0, 1, 2, 7, 3, 4, 8, 5, 6]
TURNS = [(1, 1), (1, -1), (2, 1), (2, -1), (3, 1), (3, -1), (4, 1), (4, -1), (5, 1), (5, -1), (6, 1)]


def check_collet_changes(r, rack):
    no_fault(r)
    program_completed(r)
    samples = r["samples"]
    tools = distinct(samples, "tool_in_spindle")
    if tools != CHANGES:
        fail("LinuxCNC's tool in the spindle went %s, expected %s" % (tools, CHANGES))
    ok("LinuxCNC's tool in the spindle went %s" % tools)
    # The component records each return: the spindle empty between two tools.
    component = distinct(samples, "fixed_atc_probe.tool-in-spindle")
    wanted = [0] + [t for tool in CHANGES[1:] for t in (tool, 0)][:-1]
    if component != wanted:
        fail("the component's tool in the spindle went %s, expected %s" % (component, wanted))
    ok("the component's tool in the spindle went %s" % component)
    # The manual tools: each handed in and out at loading.
    holds = rising(samples, "fixed_atc_probe.waiting-for-operator")
    if holds != 4:
        fail("the program held for the operator %d times, expected 4" % holds)
    for wanted in ("M6 T7: insert tool 7", "M6 T3: remove tool 7", "M6 T8: insert tool 8",
                   "M6 T5: remove tool 8"):
        said(r, wanted)
    held = [s for s in samples if s["fixed_atc_probe.waiting-for-operator"]]
    if not all(near(s["pos"], loading(rack)) for s in held):
        fail("the operator waits were not all at loading %s" % loading(rack))
    ok("every hand-over at loading %s" % loading(rack))
    # The spindle: only over the served pocket, forward to screw on and in
    # reverse to screw off, as far down as the engage Z.
    only_over_the_served_pocket(samples, rack)
    turns = [turn_of(run, rack) for run in stretches(samples)]
    if turns != TURNS:
        fail("the spindle turned over (pocket, direction) %s, expected %s" % (turns, TURNS))
    chuck = rack.c["chuck"]
    ok("the spindle turned %d times: forward at %.0f rpm over pockets 1 to 6 from spin-off (%.0f above the engage "
       "Z) down to the engage Z and back, in reverse at %.0f rpm over 1 to 5 down to the engage Z and up to "
       "%.0f above it" % (len(turns), chuck["load_rpm"], chuck["spin_off_offset_z"], chuck["unload_rpm"],
                          chuck["rise_after_unload_offset_z"]))
    # Between changes the magazine's nuts are where the component's tools are.
    checked = 0
    for s in samples:
        if not s["fixed_atc_probe.busy"] and s["fixed_atc_probe.state"] == 1 and \
                s["fixed_atc_probe.tool-in-spindle"] == s["tool_in_spindle"]:
            magazine_agrees(s, s["tool_in_spindle"], "t=%.3f" % s["t"])
            checked += 1
    ok("the magazine's nuts agree with the component's tools in the %d samples between changes" % checked)
    last = samples[-1]
    magazine_agrees(last, last["fixed_atc_probe.tool-in-spindle"], "at the end")
    state = r["state_file"]
    in_pocket = {int(p): v["in_pocket"] for p, v in state["pockets"].items()}
    pockets, on_spindle = magazine(last)
    if state["spindle"] != 6 or in_pocket != pockets or on_spindle != 6:
        fail("the state file says T%d in the spindle, in their pockets %s; the magazine %s, on the spindle %d"
             % (state["spindle"], in_pocket, pockets, on_spindle))
    ok("at the end the state file, the component and the magazine agree: T6 in the spindle (its nut seated, "
       "from pocket 6), pockets 1 to 5 full, 6 empty")
    spindle_stopped(last, "at the end")
    handshake_complete(r)


def program_of(r):
    return next(iter(r["programs"].values()))


def check_failure(r, rack, wanted, belief, nuts, retry=None):
    """The fault saying `wanted` (each piece in one message), the spindle
    stopped, nothing moved after the fault, the component's tool `belief`
    and the magazine `nuts` (pocket numbers with a nut, the pocket of the nut
    on the spindle); then the fault cleared and the magazine restored."""
    samples = r["samples"]
    first = next((i for i, s in enumerate(samples) if s["fixed_atc_probe.fault"]), None)
    if first is None:
        fail("no fault; the messages: %s" % r["messages"])
    fault = r["snapshots"]["fault"]
    status = fault["status_file"]
    texts = [m["text"] for m in status.get("messages", []) if m.get("kind") == "error"]
    found = [t for t in texts if all(w in t for w in wanted)]
    if not found:
        fail("no fault saying %s among the component's errors %s" % (wanted, texts))
    ok("the fault: %s" % found[-1])
    # LinuxCNC shows a long message in lines of its own: the first holds the start.
    if not any(found[-1][:100] in m for m in r["messages"]):
        fail("LinuxCNC was not told the fault: %s" % r["messages"])
    ok("LinuxCNC's operator messages carry it")
    if retry:
        said(r, retry)
    if fault["pins"]["fixed_atc_probe.state"] == 1 or not fault["pins"]["fixed_atc_probe.fault"]:
        fail("the component is not in fault once the program ended: %s" % fault["pins"])
    # Nothing moved from the fault on: the joints where they stood at it.
    at_fault = joints(samples[first])
    idle = [s for s in samples[first:] if s["interp"] == 1]
    if not idle:
        fail("LinuxCNC's interpreter never came back to idle after the fault")
    for s in samples[first:]:
        if joints(s) != at_fault:
            fail("the machine moved after the fault: from %s to %s at t=%.3f (fault at t=%.3f)"
                 % (at_fault, joints(s), s["t"], samples[first]["t"]))
    ok("nothing moved from the fault (t=%.3f) to the interpreter idle (t=%.3f) and after: the joints at %s"
       % (samples[first]["t"], idle[0]["t"], [round(v, 4) for v in at_fault]))
    # The spindle: stopped by the end of the program, its real speed 0.
    pins = fault["pins"]
    spindle_stopped(pins, "after the fault")
    late = [s for s in samples[first:] if s["t"] > idle[0]["t"] and s["fatc-spindle-guard.spindle-on"]]
    if late:
        fail("the guard let the spindle run after the interpreter was idle, t=%.3f" % late[0]["t"])
    ok("the guard held the spindle off from the interpreter idle on")
    # The component's belief and the magazine.
    if pins["fixed_atc_probe.tool-in-spindle"] != belief:
        fail("the component believes T%d in the spindle, expected T%d" % (pins["fixed_atc_probe.tool-in-spindle"], belief))
    ok("the component believes T%d in the spindle" % belief)
    pockets, on_spindle = magazine(pins)
    full = sorted(p for p in pockets if pockets[p])
    if (full, on_spindle) != nuts:
        fail("the magazine holds nuts in %s, on the spindle pocket %d's; expected %s" % (full, on_spindle, nuts))
    ok("the magazine: nuts in pockets %s, on the spindle pocket %d's" % (full, on_spindle))
    # Cleared with the operator's word; the magazine as sim_nut.hal sets it.
    cleared = r["snapshots"]["cleared"]["pins"]
    if cleared["fixed_atc_probe.fault"] or cleared["fixed_atc_probe.state"] != 1 or \
            cleared["fixed_atc_probe.tool-in-spindle"] != belief:
        fail("after clear-fault: fault %s, state %s, T%d" % (cleared["fixed_atc_probe.fault"],
                                                            cleared["fixed_atc_probe.state"],
                                                            cleared["fixed_atc_probe.tool-in-spindle"]))
    on = [pin for pin in FAULTS if cleared[NUT + pin]]
    if on:
        fail("the magazine's faults %s still on after the scenario" % on)
    values = sim_values()
    if cleared[NUT + "window"] != values[NUT + "window"]:
        fail("the window %s after the scenario, sim_nut.hal's %s" % (cleared[NUT + "window"], values[NUT + "window"]))
    if r["snapshots"]["cleared"]["tool_in_spindle"] != belief:
        fail("LinuxCNC's tool after clearing: T%d" % r["snapshots"]["cleared"]["tool_in_spindle"])
    ok("fault cleared (T%d confirmed), the component idle, LinuxCNC's tool T%d; the magazine's faults off and its "
       "window sim_nut.hal's" % (belief, belief))
    print("%s: the program ran %.1f s" % (r["name"], program_of(r)["ended"] - program_of(r)["began"]))


def check_collet_reverse(r, rack):
    check_failure(r, rack, ["tool 6's nut still on the spindle", "unscrewed twice", "pocket 6",
                            "zone 1 (Z -60.000) sees it"], 6, ([1, 2, 3, 4, 5], 6),
                  "tool 6's nut still seen at zone 1 (nut-seen on) over pocket 6; unscrewing it once more")


def check_collet_missing(r, rack):
    check_failure(r, rack, ["tool 1 not on the spindle", "pocket 1", "zone 1 (Z -60.000) sees no nut"],
                  0, ([2, 3, 4, 5, 6], 0), "tool 1 over pocket 1: zone 1 sees no nut (nut-seen off); "
                  "screwing it on once more")


def check_collet_cross_thread(r, rack):
    check_failure(r, rack, ["tool 2's nut not screwed home", "pocket 2", "zone 2 (Z -54.000) still sees it"],
                  2, ([1, 3, 4, 5, 6], 2), "zone 2 still sees it (nut-seen on); screwing it on once more")
    if r["snapshots"]["fault"]["pins"][NUT + "seated"]:
        fail("the cross-threaded nut reads seated")
    ok("the nut on the spindle is not seated")


def check_collet_stall_plunge(r, rack):
    """The stall as sim_nut.hal has it: only with the nose in the engage
    window, so the spindle came up to speed at spin-off and stalled in the
    plunge; the nut stayed on."""
    check_failure(r, rack, ["tool 2's nut still on the spindle", "unscrewed twice", "pocket 2",
                            "zone 1 (Z -60.000) sees it"], 2, ([1, 3, 4, 5, 6], 2),
                  "tool 2's nut still seen at zone 1 (nut-seen on) over pocket 2; unscrewing it once more")
    stalled = [s for s in r["samples"] if s[NUT + "stalled"]]
    if not stalled:
        fail("the spindle never stalled")
    ok("the spindle stalled in the plunge, from Z %.3f down to %.3f"
       % (max(joints(s)[2] for s in stalled), min(joints(s)[2] for s in stalled)))


def check_collet_after(r, rack):
    """After every failure, cleared and the magazine restored: the next change works."""
    no_fault(r)
    last = r["samples"][-1]
    if last["tool_in_spindle"] != 3 or last["fixed_atc_probe.tool-in-spindle"] != 3:
        fail("after T3 M6 LinuxCNC says T%d, the component T%d" % (last["tool_in_spindle"],
                                                                  last["fixed_atc_probe.tool-in-spindle"]))
    ok("T2 screwed off into pocket 2 and T3 on: LinuxCNC and the component say T3")
    only_over_the_served_pocket(r["samples"], rack)
    turns = [turn_of(run, rack) for run in stretches(r["samples"])]
    if turns != [(2, -1), (3, 1)]:
        fail("the spindle turned over (pocket, direction) %s, expected [(2, -1), (3, 1)]" % turns)
    ok("the spindle turned in reverse over pocket 2, then forward over pocket 3")
    magazine_agrees(last, 3, "at the end")
    ok("the magazine agrees: T3's nut on the spindle, seated, every other pocket full")
    spindle_stopped(last, "at the end")


def check_collet_stall(r, rack):
    check_failure(r, rack, ["did not come up to 1200 rpm in reverse over pocket 2",
                            "spindle_stop_timeout_seconds", "tool 2 not screwed"], 2, ([1, 3, 4, 5, 6], 2))


def check_recorded(path, rack):
    """recorder.hal's file: per servo period its number, X Y Z (the joints'
    commands), the guard's run, the guard's speed, motion's speed, the real
    speed, the pocket served, the pocket cut off by a fault. Every period
    with the spindle turning stands over the served pocket (in a fault, the
    one it was cut off at: the spindle runs on until LinuxCNC's abort stops
    it) between its engage Z and safe Z; no period lost."""
    periods, turning_periods, faulted, last, pockets = 0, 0, 0, None, set()
    for line in open(path):
        words = line.split()
        if words == ["overrun"]:
            fail("the recorder lost periods after period %s (overrun)" % last)
        if len(words) != 10:
            continue  # a last line cut short by the shutdown
        number = int(words[0])
        if last is not None and number != last + 1:
            fail("the recorder went from period %d to %d" % (last, number))
        last, periods = number, periods + 1
        x, y, z = map(float, words[1:4])
        run, speeds, pocket, cut_off = words[4] == "1", [float(v) for v in words[5:8]], int(words[8]), int(words[9])
        if not run and not any(speeds):
            continue
        turning_periods += 1
        if pocket == 0 and cut_off:
            pocket = cut_off
            faulted += 1
        off = off_the_pocket(rack, pocket, [x, y, z])
        if off:
            fail("period %d: the spindle turned (run %s, speeds %s) %s" % (number, run, speeds, off))
        pockets.add(pocket)
    if turning_periods == 0:
        fail("the recorder saw the spindle turn in none of its %d periods" % periods)
    ok("%d servo periods recorded, none lost; in the %d with the spindle turning it stood over the served "
       "pocket (pockets %s, within %.2f mm) between its engage Z and safe Z (%d of them in a fault, over the "
       "pocket it cut off)" % (periods, turning_periods, sorted(pockets), TOLERANCE, faulted))


if __name__ == "__main__":
    if sys.argv[1] == "--recorded":
        check_recorded(sys.argv[2], Rack(json.load(open(sys.argv[3]))))
    else:
        main(globals())
