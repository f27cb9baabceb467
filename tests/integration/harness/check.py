#!/usr/bin/env python3
"""Checks one scenario of an integration run against what LinuxCNC reported.
   check.py RESULTS.json CONFIG.json SCENARIO
Prints what it checked; exits 1 on the first failed expectation."""
import json
import os
import math
import sys

TOLERANCE = 0.01  # mm: the sim follows its commands exactly


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def ok(message):
    print("ok: " + message)


class Rack:
    def __init__(self, config):
        self.c = config
        default = config.get("pocket_default", {})
        self.pockets = {int(k): {**default, **v} for k, v in config["pockets"].items()}
        # `path: "direct"`: over the rack at safe Z, no safe XY between a return and a fetch.
        self.direct = config.get("path") == "direct"

    def pocket(self, t):
        p = self.pockets[t]
        return [p["x"], p["y"], p["z"]]

    def side(self, t):
        """Pocket t's side: its own `side_offset`, else the rack's `pocket_side_offset`."""
        p = self.pocket(t)
        offset = self.pockets[t].get("side_offset", self.c["pocket_side_offset"])
        return [p[0] + offset["x"], p[1] + offset["y"], p[2]]

    def keepout_margin(self):
        """Half-width of each pocket's keep-out column: rack_keepout_margin, else
        half the side offset's length."""
        return self.c.get("rack_keepout_margin", math.hypot(self.c["pocket_side_offset"]["x"],
                                                            self.c["pocket_side_offset"]["y"]) / 2.0)

    def column_edge(self, t):
        """Between pocket t's side and the pocket, where its keep-out column begins:
        the direct path's side approach is fast up to there."""
        p, side = self.pocket(t), self.side(t)
        edge = self.keepout_margin() / math.dist(p, side)
        return [p[k] + (side[k] - p[k]) * edge for k in range(3)]

    def top(self, t):
        """Pocket t is approached straight down from above (`"approach": "top"`)."""
        return self.pockets[t].get("approach", "side") == "top"

    def first_tools(self):
        """Pocket -> the tool it holds at first start (`tool`; default its own number)."""
        return {n: p.get("tool", n) for n, p in self.pockets.items()}

    def at_safe_z(self, p):
        return [p[0], p[1], self.c["safe"]["z"]]

    def above(self, t, key):
        p = self.pocket(t)
        return [p[0], p[1], p[2] + self.c[key]]

    def safe(self):
        s = self.c["safe"]
        return [s["x"], s["y"], s["z"]]

    def return_waypoints(self, t):
        return [w[:2] for w in self.return_stops(t) if "safe Z" not in w[0]]

    def retrieve_waypoints(self, t):
        return [w[:2] for w in self.retrieve_stops(t)[1:] if "safe Z" not in w[0]]

    def return_stops(self, t):
        """Every stop of a return into pocket t from safe (docs/sequences.md#return):
        (name, position, reached slowly at pocket_feed)."""
        clearance = ("above-clearance %d" % t, self.above(t, "pocket_above_clearance_offset_z"), False)
        above_chuck = ("above-chuck %d" % t, self.above(t, "pocket_above_chuck_offset_z"), False)
        # The direct path stops once on a straight way up or down: not at above-clearance.
        lift = [] if self.direct else [clearance]
        if self.top(t):
            into = [("pocket %d at safe Z" % t, self.at_safe_z(self.pocket(t)), False),
                    above_chuck if self.direct else clearance, ("pocket %d" % t, self.pocket(t), True)]
        else:
            into = [("side of pocket %d at safe Z" % t, self.at_safe_z(self.side(t)), False),
                    ("side of pocket %d" % t, self.side(t), False)]
            if self.direct:
                into.append(("column edge %d" % t, self.column_edge(t), False))
            into.append(("pocket %d" % t, self.pocket(t), True))
        return into + [above_chuck] + lift + [
            ("pocket %d at safe Z" % t, self.at_safe_z(self.pocket(t)), False), ("safe", self.safe(), False)]

    def retrieve_stops(self, t):
        """Every stop of a retrieve out of pocket t from safe (docs/sequences.md#retrieve)."""
        clearance = ("above-clearance %d" % t, self.above(t, "pocket_above_clearance_offset_z"), False)
        above_chuck = ("above-chuck %d" % t, self.above(t, "pocket_above_chuck_offset_z"), False)
        route = [("pocket %d at safe Z" % t, self.at_safe_z(self.pocket(t)), False)] + \
            ([] if self.direct else [clearance]) + [above_chuck, ("pocket %d" % t, self.pocket(t), True)]
        if self.top(t):
            # Slowly up while the holder can touch the pocket: to above-clearance,
            # on the direct path only to above-chuck.
            out = above_chuck if self.direct else clearance
            route += [out[:2] + (True,), ("pocket %d at safe Z" % t, self.at_safe_z(self.pocket(t)), False)]
        else:
            if self.direct:
                route.append(("column edge %d" % t, self.column_edge(t), True))
            route += [("side of pocket %d" % t, self.side(t), not self.direct),
                      ("side of pocket %d at safe Z" % t, self.at_safe_z(self.side(t)), False)]
        return route + [("safe", self.safe(), False)]


def loading(rack):
    return [rack.c["loading"][a] for a in "xyz"]


def sensor_truth(config):
    """The true tool length the simulated sensor (machine Z -70) gives."""
    return -70.0 - config["probe_length_compensation_offset"]


def measured_to_truth(r, config, tool, what):
    """The length LinuxCNC's tool table file holds for `tool`, within 0.005 of the truth."""
    truth = sensor_truth(config)
    length = tool_table_length(r, tool)
    if abs(length - truth) > 0.005:
        fail("%s: tool %d's length in the tool table file is %.4f, truth %.4f" % (what, tool, length, truth))
    ok("%s: tool %d is %.4f in LinuxCNC's tool table file (truth %.4f)" % (what, tool, length, truth))
    return length


def spindle_holds(r, tool, what):
    """LinuxCNC and the changer agree that the spindle holds `tool` at the end."""
    last = r["samples"][-1]
    if last["tool_in_spindle"] != tool or last["fixed_atc_probe.tool-in-spindle"] != tool:
        fail("%s, LinuxCNC says T%d, the changer T%d" % (
            what, last["tool_in_spindle"], last["fixed_atc_probe.tool-in-spindle"]))


def load_results(path, name):
    """The run's results with only scenario `name` in "scenarios" (and the run's
    "error"): from the driver's per-scenario files beside RESULTS when they are
    there (a whole run's samples take seconds to parse), else from RESULTS."""
    folder = path + ".d"
    try:
        run = json.load(open(os.path.join(folder, "run.json")))
    except (OSError, ValueError):
        results = json.load(open(path))
        results["scenarios"] = [s for s in results["scenarios"] if s["name"] == name]
        return results
    scenarios = [json.load(open(os.path.join(folder, name + ".json")))] if name in run["names"] else []
    return {"error": run["error"], "scenarios": scenarios}


def scenario(results, name):
    """Scenario `name` of the run's results; fails when it did not run."""
    found = next((s for s in results["scenarios"] if s["name"] == name), None)
    if found is None:
        fail("scenario %s did not run: %s" % (name, results["error"]))
    return found


def near(a, b):
    return math.dist(a, b) < TOLERANCE


def distance_to_segment(p, a, b):
    """How far p is from the straight path a to b."""
    ab = [b[k] - a[k] for k in range(3)]
    length = sum(v * v for v in ab)
    if length == 0.0:
        return math.dist(p, a)
    t = max(0.0, min(1.0, sum((p[k] - a[k]) * ab[k] for k in range(3)) / length))
    return math.dist(p, [a[k] + t * ab[k] for k in range(3)])


def visits_in_order(samples, waypoints):
    """Each waypoint must be reached, in order, by the sampled machine position:
    a sample near it, or two samples in a row whose straight path passes it (a
    short stop may fall between two samples of a driver that stalled a moment)."""
    i = 0
    for name, target in waypoints:
        while i < len(samples) and not near(samples[i]["pos"], target) and not (
                i > 0 and distance_to_segment(target, samples[i - 1]["pos"], samples[i]["pos"]) < TOLERANCE):
            i += 1
        if i == len(samples):
            fail("the machine never reached %s %s after the previous waypoint" % (name, target))
    ok("visited %d waypoints in order at the config's positions" % len(waypoints))


def stops(samples):
    """Where the machine stood still, in order: runs of samples with LinuxCNC's
    current velocity zero and the actual position on the commanded one, at one
    place (within TOLERANCE), as (position, first sample index, last sample
    index). (A status not refreshed between two samples repeats a position in
    the middle of a move: its velocity is not zero; at the end of a move the
    velocity is zero a few servo periods before the feedback arrives.)"""
    found = []
    for i, s in enumerate(samples):
        if s["vel"] != 0.0 or math.dist(s["pos"], s["cmd"]) > 1e-6:
            continue
        if found and near(found[-1][0], s["pos"]):
            found[-1] = (found[-1][0], found[-1][1], i)
        else:
            found.append((s["pos"], i, i))
    return found


def rising_samples(samples, pin):
    """The sample at each rising edge of `pin`, in order."""
    found, last = [], False
    for s in samples:
        if s[pin] and not last:
            found.append(s)
        last = s[pin]
    return found


def rising(samples, pin):
    return len(rising_samples(samples, pin))


def distinct(samples, key):
    values = []
    for s in samples:
        if not values or values[-1] != s[key]:
            values.append(s[key])
    return values


def chuck_gate_follows(samples):
    """While the component runs, hal/fixed_atc_probe.hal's gate passes its chuck request."""
    # The gate runs in the servo thread: samples may still show the periods
    # before it ran, and a uspace servo thread on a busy machine runs late (a
    # suite beside a build showed 5 ms); 20 ms is twenty periods.
    since = None
    for s in samples:
        if s["fatc-chuck-guard.chuck"] == s["fixed_atc_probe.chuck"]:
            since = None
            continue
        since = s if since is None else since
        if s["t"] - since["t"] > 0.020:
            fail("fatc-chuck (%s) differs from the component's chuck (%s) from t=%.3f to %.3f" %
                 (s["fatc-chuck-guard.chuck"], s["fixed_atc_probe.chuck"], since["t"], s["t"]))
    ok("the chuck gate passed every chuck request of the live component")


def chuck_only_at_pockets(samples, rack):
    for s in samples:
        if not s["fixed_atc_probe.chuck"]:
            continue
        x, y, z = s["pos"]
        allowed = False
        for t in rack.pockets:
            p = rack.pocket(t)
            top = p[2] + rack.c["pocket_above_chuck_offset_z"]
            if abs(x - p[0]) < TOLERANCE and abs(y - p[1]) < TOLERANCE and p[2] - TOLERANCE <= z <= top + TOLERANCE:
                allowed = True
        if not allowed:
            fail("chuck open at %s, not at a pocket or above its chuck (t=%.3f)" % (s["pos"], s["t"]))
    ok("the chuck opened only at a pocket or above its chuck")


def no_fault(r):
    if any(s["fixed_atc_probe.fault"] for s in r["samples"]):
        fail("fixed_atc_probe faulted: %s" % r["messages"])
    ok("no fault")


def handshake_complete(r):
    last = r["samples"][-1]
    for pin in ("iocontrol.0.tool-change", "iocontrol.0.tool-changed", "iocontrol.0.tool-prepare"):
        if last[pin]:
            fail("%s still high after the program" % pin)
    samples = r["samples"]
    if rising(samples, "iocontrol.0.tool-changed") == 0 and not changes_taken(samples) \
            and not (rising(samples, "iocontrol.0.tool-change") == 0
                     and len(distinct(samples, "tool_in_spindle")) > 1):
        fail("changed never answered tool-change")
    ok("prepare/change handshakes completed (changed answered, all levels low at the end)")


def changes_taken(samples):
    """Every tool-change ended by LinuxCNC taking the new tool: it lowers
    tool-change and sets the spindle's tool only when changed answers. LinuxCNC
    2.10's task does that in its next cycle (2.9's iocontrol some 100 ms later),
    so changed may be high for less than a sampling interval and never sampled;
    with iocontrol's cycle at 0.01 s tool-change too may fall between two
    samples, and then the spindle's tool changing says changed answered.
    The spindle's tool comes by NML status, which may follow the pins a little."""
    ends = 0
    for i in range(1, len(samples)):
        if not (samples[i - 1]["iocontrol.0.tool-change"] and not samples[i]["iocontrol.0.tool-change"]):
            continue
        before = samples[i - 1]["tool_in_spindle"]
        taken = False
        for s in samples[i:]:
            if s["t"] - samples[i]["t"] > 0.5 or s["iocontrol.0.tool-change"]:
                break
            if s["tool_in_spindle"] != before:
                taken = True
                break
        if not taken:
            return False  # tool-change dropped without the change (an abort)
        ends += 1
    return ends > 0


def check_changes(r, rack):
    no_fault(r)
    tools = distinct(r["samples"], "tool_in_spindle")
    if tools[-4:] != [1, 3, 0, 5]:
        fail("tool in spindle went %s, expected ... 1, 3, 0, 5" % tools)
    ok("tool in spindle went %s (T3 M6 twice: no change)" % tools)
    # The direct path fetches from safe Z without going to safe XY, and a
    # return that a fetch follows ends over its pocket.
    start = [] if rack.direct else [("safe", rack.safe())]
    before_fetch = [w for w in rack.return_waypoints(1) if not (rack.direct and w[0] == "safe")]
    visits_in_order(r["samples"], start + rack.retrieve_waypoints(1) + before_fetch +
                    rack.retrieve_waypoints(3) + rack.return_waypoints(3) + rack.retrieve_waypoints(5))
    openings = rising(r["samples"], "fixed_atc_probe.chuck")
    expected = 2 + 3 + 0 + 1 + 2  # retrieval: flush + open; return: open
    if openings != expected:
        fail("the chuck opened %d times, expected %d" % (openings, expected))
    ok("the chuck opened %d times: nothing moved for the repeated T3" % openings)
    chuck_only_at_pockets(r["samples"], rack)
    chuck_gate_follows(r["samples"])
    handshake_complete(r)


def check_modal(r, rack):
    no_fault(r)
    snap = r.get("snapshot")
    if not snap:
        fail("the program never reached its M0 after M6")
    codes = set(snap["gcodes"])
    for code, name in ((200, "G20"), (910, "G91"), (610, "G61"), (430, "G43")):
        if code not in codes:
            fail("%s not active after M6 (active: %s)" % (name, sorted(c for c in codes if c > 0)))
    if 611 in codes:
        fail("the executor's G61.1 still active after M6")
    ok("G20, G91, G61 and G43 active after M6, not the executor's G61.1")
    length_in = 35.0 / 25.4  # tool 2's length in sim.tbl, in the program's inches
    if abs(snap["tool_offset"][2] - length_in) > 1e-4 and abs(snap["tool_offset"][2] - 35.0) > 1e-3:
        fail("tool length offset %.4f, expected tool 2's 35 mm" % snap["tool_offset"][2])
    ok("G43 uses tool 2's length (%.4f)" % snap["tool_offset"][2])
    safe = rack.safe()
    expected = [safe[0] + 25.4, safe[1] + 12.7, safe[2]]
    if not near(snap["pos"], expected):
        fail("after M6, G0 X1 Y0.5 went to %s, expected %s (inches, relative)" % (snap["pos"], expected))
    ok("the program's next move was relative and in inches: %s" % snap["pos"])
    if r["samples"][-1]["tool_in_spindle"] != 2:
        fail("tool 2 not in the spindle")
    busy = [s for s in r["samples"] if s["fixed_atc_probe.busy"]]
    if any(s["iocontrol.0.coolant-flood"] for s in busy):
        fail("flood coolant was on while the changer moved")
    after = [s for s in r["samples"] if busy and s["t"] > busy[-1]["t"]]
    if not any(s["iocontrol.0.coolant-flood"] for s in after):
        fail("flood coolant (M8 before M6) was not restored after the change")
    ok("flood coolant off during the change (%d samples), restored after it" % len(busy))


def said_modal(r, after):
    """What the program's DEBUG line says the interpreter holds right after
    `after` (M6, M312): {"motion": #<_motion_mode>, "feed": #<_feed>, ...}."""
    no_fault(r)
    prefix = "modal after %s: " % after
    line = next((m for m in r["messages"] if prefix in m), None)
    if line is None:
        fail("the program never said its modes after %s: %s" % (after, r["messages"]))
    words = line.split(prefix, 1)[1].split()
    return {words[i]: float(words[i + 1]) for i in range(0, len(words) - 1, 2)}


def modal_back(r, feed, motion, name):
    """After M6 the program's feed is exactly its own and its motion mode is `motion`
    (#<_motion_mode>: G1 10, G80 800), as the program set them before the change."""
    modes = said_modal(r, "M6")
    if abs(modes["feed"] - feed) > 5e-7:
        fail("the feed after M6 is F%.6f, the program's was F%r" % (modes["feed"], feed))
    ok("the feed after M6 is the program's exactly: F%.6f" % modes["feed"])
    if modes["motion"] != motion:
        fail("the motion mode after M6 is G%g, the program's was %s" % (modes["motion"] / 10.0, name))
    ok("the motion mode after M6 is the program's %s" % name)


def check_modal_feed(r, rack):
    modal_back(r, 0.25, 10, "G1")


def check_modal_g80(r, rack):
    modal_back(r, 39.37008, 800, "G80")


def check_modal_atom(r, rack):
    modes = said_modal(r, "M312")
    if modes["per-rev"] != 1 or abs(modes["feed"] - 0.004) > 5e-7:
        fail("after M312 the feed is F%.6f (per rev: %g), the program's was F0.004 in G95" % (
            modes["feed"], modes["per-rev"]))
    ok("after M312 (eject) the feed is the program's exactly: F%.6f per revolution" % modes["feed"])


def check_feed_hold(r, rack):
    no_fault(r)
    if "paused_at" not in r or "resumed_at" not in r:
        fail("the feed hold was not applied")
    paused = [s for s in r["samples"] if r["paused_at"] + 0.2 < s["t"] < r["resumed_at"]]
    if paused and math.dist(paused[0]["pos"], paused[-1]["pos"]) > TOLERANCE:
        fail("the machine moved during the feed hold")
    ok("held %.1f s during the sequence" % (r["resumed_at"] - r["paused_at"]))
    if r["samples"][-1]["tool_in_spindle"] != 4:
        fail("tool 4 not in the spindle after resume")
    ok("the change completed after resume: T4 in the spindle")


def check_abort(r, rack):
    last = r["samples"][-1]
    if "aborted_at" not in r:
        fail("the program was not aborted")
    if not last["fixed_atc_probe.fault"] or last["fixed_atc_probe.busy"] or last["fixed_atc_probe.chuck"]:
        fail("after abort: fault=%s busy=%s chuck=%s" % (last["fixed_atc_probe.fault"],
             last["fixed_atc_probe.busy"], last["fixed_atc_probe.chuck"]))
    ok("after abort: fault set, not busy, chuck closed")


def program_modes(modes):
    """The modes of abort_modes.ngc and cut_off_modes.ngc, the interpreter's own:
    G20 G91 G18 G95 F0.01, not the executor's G21 G90 G17 G94 and feed."""
    codes = set(modes["gcodes"])
    for code, name in ((200, "G20"), (910, "G91"), (180, "G18"), (950, "G95")):
        if code not in codes:
            fail("%s not in force after the abort (G codes: %s)" %
                 (name, sorted(c / 10 for c in codes if c > 0)))
    if abs(modes["feed"] - 0.01) > 1e-9:
        fail("feed rate F%s after the abort, expected the program's F0.01" % modes["feed"])
    ok("G20 G91 G18 G95 F0.01 in force %.2f s into the scenario, after the abort" % modes["t"])


def modes_restored(r, tool):
    """After an M6 cut off: the program's modes are back, as LinuxCNC reports
    them, with its overrides (feed on, spindle off) and G43 with the length of
    `tool`, which LinuxCNC has in the spindle; motion applies both."""
    modes = r.get("modes", {}).get("after_abort")
    if not modes:
        fail("no modes read after the abort: %s" % r.get("messages"))
    program_modes(modes)
    if 430 not in modes["gcodes"]:
        fail("G43 not in force after the abort (messages %s)" % r["messages"])
    if modes["tool_in_spindle"] != tool:
        fail("LinuxCNC has tool %s in the spindle, expected %d" % (modes["tool_in_spindle"], tool))
    # stat.tool_offset and the table's Z are both in machine units (mm).
    if modes["tool_z"] is None or modes["tool_z"] == 0.0 or \
            abs(modes["tool_offset"][2] - modes["tool_z"]) > 1e-6:
        fail("tool length offset %s, expected tool %d's Z %s" %
             (modes["tool_offset"][2], tool, modes["tool_z"]))
    ok("G43: motion applies tool %d's length %.4f" % (tool, modes["tool_offset"][2]))
    if not modes["feed_override_enabled"] or modes["spindle_override_enabled"]:
        fail("overrides after the abort: feed %s spindle %s, expected the program's on and off" %
             (modes["feed_override_enabled"], modes["spindle_override_enabled"]))
    ok("feed override on and spindle override off, as the program had them")


def check_abort_modes(r, rack):
    if "aborted_at" not in r:
        fail("the program was not aborted")
    modes_restored(r, 1)


def check_stopped_answering_modes(r, rack):
    if "stopped_at" not in r:
        fail("the component was not stopped")
    said(r, "fixed_atc_probe stopped answering")
    if not r.get("decoy_ran"):
        fail("the other fixed_atc_probe (a --lint) did not run beside the component")
    ok("the component's pid %d taken from HAL, another fixed_atc_probe running beside it" %
       r["stopped_pid"])
    modes_restored(r, 1)


def check_estop_modes(r, rack):
    """Motion takes no command in estop: the interpreter's own modes come back,
    and it says what motion has, G49 and the overrides off, on again too."""
    if "estop_at" not in r:
        fail("no estop")
    for name in ("after_abort", "machine_on"):
        modes = r.get("modes", {}).get(name)
        if not modes:
            fail("no modes read %s" % name)
        program_modes(modes)
        if 490 not in modes["gcodes"] or modes["tool_offset"][2] != 0.0:
            fail("%s: the interpreter says %s, motion applies a tool length of %s" %
                 (name, "G49" if 490 in modes["gcodes"] else "G43", modes["tool_offset"][2]))
        if modes["feed_override_enabled"]:
            fail("%s: motion's feed override on, where the executor had it off" % name)
        ok("%s: G49 and no tool length, as motion has it; feed override off in both" % name)


def check_after_abort(r, rack):
    if not any("M6 T1 refused" in m and "fault" in m for m in r["messages"]):
        fail("M6 was not refused with a message while faulted: %s" % r["messages"])
    ok("M6 refused while faulted: %s" % r["messages"])
    nothing_moved(r)


def check_after_clear(r, rack):
    no_fault(r)
    if r["samples"][-1]["tool_in_spindle"] != 1:
        fail("after clearing the fault, M6 T1 did not complete")
    ok("after clearing the fault, M6 T1 completed")


def check_return_to_xy(r, rack):
    no_fault(r)
    last = r["samples"][-1]
    expected = [30.0, 40.0, rack.safe()[2]]
    if not near(last["pos"], expected):
        fail("after M6 the machine stands at %s, expected over X30 Y40 at safe Z %s" % (last["pos"], expected))
    ok("back over X30 Y40 where M6 was called, at safe Z")
    if last["tool_in_spindle"] != 3:
        fail("tool 3 not in the spindle")


def tool_table_length(r, tool):
    for line in r["tool_table_file"].splitlines():
        words = line.split()
        if words and words[0] == "T%d" % tool:
            return float(next(w[1:] for w in words if w.startswith("Z")))
    fail("tool %d not in the tool table file" % tool)


def check_unload(r, rack):
    no_fault(r)
    spindle_holds(r, 0, "after unloading")
    ok("tool 4 unloaded: the spindle is empty for LinuxCNC and the changer")
    visits_in_order(r["samples"], rack.retrieve_waypoints(4) + [("loading", loading(rack))])


def check_load_probe(r, rack):
    no_fault(r)
    length = measured_to_truth(r, rack.c, 4, "load and probe")
    if abs(r["samples"][-1]["fixed_atc_probe.last-length"] - length) > 1e-6:
        fail("last-length pin says %.4f" % r["samples"][-1]["fixed_atc_probe.last-length"])
    if "jogged_to" not in r or abs(r["jogged_to"][2] - (rack.c["loading"]["z"] - 15.0)) > 0.01:
        fail("the jog during the wait did not happen: %s" % r.get("jogged_to"))
    ok("jogged to Z %.3f during the wait" % r["jogged_to"][2])
    last = r["samples"][-1]
    if last["tool_in_spindle"] != 0:
        fail("after load and probe the spindle should be empty, LinuxCNC says T%d" % last["tool_in_spindle"])
    visits_in_order(r["samples"], rack.return_waypoints(4))
    ok("tool 4 put away in its pocket; the spindle is empty")
    said(r, "tool 4 measured %.4f mm, in pocket 4" % last["fixed_atc_probe.last-length"])
    # The component's log beside the state file keeps what it said.
    log = os.path.join(os.path.dirname(sys.argv[2]), "fixed_atc_state.json.log")
    if not os.path.exists(log) or "tool 4 measured" not in open(log, errors="replace").read():
        fail("the component's log %s does not hold the load's message" % log)
    ok("the component's log %s holds it" % log)
    # The load ran over MDI in the executor's modes (G21 G90 G17 G49, feed
    # override off): the operator's come back at its end.
    operator_modes_back(r, "after_load", {200: "G20", 910: "G91", 180: "G18"})


def operator_modes_back(r, name, wanted):
    """After an operator flow over MDI: the operator's G codes (code -> name)
    and the feed override are LinuxCNC's again, not the executor's."""
    modes = r.get("modes", {}).get(name)
    if modes is None:
        fail("no modes read %s" % name)
    missing = [word for code, word in wanted.items() if code not in modes["gcodes"]]
    if missing or not modes["feed_override_enabled"]:
        fail("%s LinuxCNC lacks %s of the operator's %s, feed override %s"
             % (name, missing, " ".join(wanted.values()), "on" if modes["feed_override_enabled"] else "off"))
    ok("%s: the operator's %s and the feed override back" % (name, " ".join(wanted.values())))
    return modes


def check_unload_cancel(r, rack):
    no_fault(r)
    spindle_holds(r, 2, "after cancelling")
    ok("unload cancelled: tool 2 stays in the spindle, LinuxCNC knows it")
    if not any("cancelled" in m for m in r["messages"]):
        fail("no message saying what is where: %s" % r["messages"])
    ok("message: %s" % [m for m in r["messages"] if "cancelled" in m][0])


def check_unload_cancel_modes(r, rack):
    """Tool 2 in the spindle, G43 with its length in force: an unload of it
    over MDI, cancelled at the prompt, gives every mode back."""
    check_unload_cancel(r, rack)
    modes = operator_modes_back(r, "after_cancel", {200: "G20", 910: "G91", 180: "G18", 430: "G43"})
    if modes["tool_z"] is None or modes["tool_z"] == 0.0 or \
            abs(modes["tool_offset"][2] - modes["tool_z"]) > 1e-6:
        fail("motion applies %.4f, tool %d's length is %s" % (modes["tool_offset"][2], modes["tool_in_spindle"], modes["tool_z"]))
    ok("G43: motion applies tool %d's length %.4f" % (modes["tool_in_spindle"], modes["tool_z"]))


def said(r, wanted):
    if not any(wanted in m for m in r["messages"]):
        fail("no message saying '%s': %s" % (wanted, r["messages"]))
    ok("message: %s" % wanted)


def nothing_moved(r):
    for s in r["samples"]:
        if not near(s["pos"], r["start_pos"]):
            fail("the machine moved to %s" % s["pos"])
    ok("nothing moved")


def check_unload_missing(r, rack):
    no_fault(r)
    ok("refused: %s" % [m for m in r["messages"] if "not in the rack" in m][0])
    nothing_moved(r)


def in_pockets(state):
    """The tools a state file records sitting in their pockets, sorted: version 2's
    `pockets` map, or version 1's `in_pocket` (pocket N held tool N)."""
    if "pockets" in state:
        return sorted(p["tool"] for p in state["pockets"].values() if p["in_pocket"])
    return sorted(state.get("in_pocket", []))


def check_load_no_pocket(r, rack):
    no_fault(r)
    ok("refused: %s" % [m for m in r["messages"] if "into pocket 2 refused" in m][0])
    nothing_moved(r)


def check_load_cancel(r, rack):
    no_fault(r)
    spindle_holds(r, 0, "after cancelling the load")
    if not any("cancelled" in m and "the spindle is empty" in m for m in r["messages"]):
        fail("no message saying what is where: %s" % r["messages"])
    ok("load cancelled at the insert prompt: the spindle is empty, and the message says so")


def probe_failed(r, rack, wanted):
    no_fault(r)
    if not any(wanted in m for m in r["messages"]):
        fail("no message saying '%s': %s" % (wanted, r["messages"]))
    ok("message: %s" % [m for m in r["messages"] if wanted in m][0])
    if abs(tool_table_length(r, 2) - 35.0) > 1e-9:
        fail("tool 2's length changed to %.4f" % tool_table_length(r, 2))
    ok("nothing written: tool 2 keeps 35.0 in the tool table file")
    last = r["samples"][-1]
    if last["tool_in_spindle"] != 2 or abs(last["pos"][2] - rack.c["loading"]["z"]) > TOLERANCE:
        fail("expected tool 2 in the spindle at loading Z, got T%d at %s" % (last["tool_in_spindle"], last["pos"]))
    ok("retracted to loading Z with tool 2 still in the spindle")


def check_probe_miss(r, rack):
    probe_failed(r, rack, "did not touch the sensor before probe_limit")


def check_probe_tripped(r, rack):
    probe_failed(r, rack, "the touch-off sensor was already tripped")


def check_jog_prompt_cancel(r, rack):
    no_fault(r)
    wanted = "load of tool 2 cancelled, nothing measured; tool 2 is in the spindle"
    said(r, wanted)
    if r["samples"][-1]["tool_in_spindle"] != 2 or abs(tool_table_length(r, 2) - 35.0) > 1e-9:
        fail("tool 2 should stay in the spindle with its length unchanged")
    ok("tool 2 stays in the spindle, its length unchanged")


def program_completed(r):
    if any("abort" in m or "refused" in m for m in r["messages"]):
        fail("the program did not complete: %s" % r["messages"])
    ok("the program ran to its end")


def check_probe_cancel(r, rack):
    no_fault(r)
    wanted = "probe of tool 2 cancelled by the operator; nothing written"
    said(r, wanted)
    lowest = min(s["pos"][2] for s in r["samples"])
    if lowest < -69.0:
        fail("the probe went on to Z %.3f after Cancel (sensor at -70)" % lowest)
    ok("the probe stopped at Z %.3f, short of the sensor" % lowest)
    last = r["samples"][-1]
    if abs(tool_table_length(r, 2) - 35.0) > 1e-9 or last["tool_in_spindle"] != 2:
        fail("tool 2 should stay in the spindle with its length unchanged")
    if abs(last["pos"][2] - rack.c["loading"]["z"]) > TOLERANCE:
        fail("expected the retract to loading Z, the machine stands at %s" % last["pos"])
    ok("retracted to loading Z; tool 2 in the spindle, its length unchanged")


def check_manual(r, rack):
    no_fault(r)
    program_completed(r)
    tools = distinct(r["samples"], "tool_in_spindle")
    if tools[-3:] != [2, 7, 2]:
        fail("tool in spindle went %s, expected ... 2, 7, 2" % tools)
    ok("tool in spindle went %s" % tools)
    holds = rising(r["samples"], "fixed_atc_probe.waiting-for-operator")
    if holds != 2:
        fail("the program held for the operator %d times, expected 2" % holds)
    for wanted in ("M6 T7: insert tool 7", "M6 T2: remove tool 7"):
        if not any(wanted in m for m in r["messages"]):
            fail("no operator message saying '%s': %s" % (wanted, r["messages"]))
    ok("held twice, announced: insert tool 7, remove tool 7")
    held = [s for s in r["samples"] if s["fixed_atc_probe.waiting-for-operator"]]
    if not all(near(s["pos"], loading(rack)) for s in held):
        fail("the operator waits were not at loading %s" % loading(rack))
    if not all(s["interp"] != 1 for s in held):
        fail("the program was not running during the hold")
    ok("every hold at loading %s with the program still running" % loading(rack))
    visits_in_order(r["samples"], rack.return_waypoints(2) + [("loading", loading(rack)),
                    ("X100 Y100", [100.0, 100.0, rack.safe()[2]]), ("loading", loading(rack))] +
                    rack.retrieve_waypoints(2))
    handshake_complete(r)


def check_manual_cancel(r, rack):
    no_fault(r)
    said(r, "M6 T7 cancelled by the operator; the spindle is empty")
    spindle_holds(r, 0, "after the cancel")
    ok("the spindle is empty for LinuxCNC and the changer")
    last = r["samples"][-1]
    if any(abs(s["pos"][0] - 1.0) < TOLERANCE for s in r["samples"]):
        fail("the program went on to G0 X1 Y1 after the cancel")
    if last["interp"] != 1 or last["fixed_atc_probe.state"] != 1:
        fail("the program should be stopped and the changer idle")
    ok("the program stopped before its next move; the changer is idle, not faulted")


def check_busy_refusals(r, rack):
    no_fault(r)
    pressed = [p for p, _ in r.get("pressed", [])]
    if len(pressed) != 3:
        fail("the buttons were not all pressed during the program: %s" % pressed)
    for wanted in ("load of tool 4 refused: a program or MDI command is running",
                   "unload of tool 4 refused: a program or MDI command is running",
                   "Continue: nothing is waiting for the operator"):
        if not any(wanted in m for m in r["messages"]):
            fail("no message saying '%s': %s" % (wanted, r["messages"]))
        ok("message: %s" % wanted)
    if any(s["fixed_atc_probe.state"] != 1 for s in r["samples"]):
        fail("the changer left idle during the program")
    nothing_moved(r)


def measured_at_sensor(r, rack):
    sensor = [rack.c["probe_limit"]["x"], rack.c["probe_limit"]["y"]]
    touches = [s for s in r["samples"] if s["motion.probe-input"]]
    if not touches or any(math.dist(s["pos"][:2], sensor) > TOLERANCE for s in touches):
        fail("the tool was not probed over the sensor at %s" % sensor)
    ok("probed over the sensor at X%.1f Y%.1f" % tuple(sensor))


def check_check_first(r, rack):
    no_fault(r)
    program_completed(r)
    measured_at_sensor(r, rack)
    measured_to_truth(r, rack.c, 3, "never measured before, so M6 measures and writes it")
    if r["samples"][-1]["tool_in_spindle"] != 3:
        fail("tool 3 not in the spindle")


def check_check_pass(r, rack):
    no_fault(r)
    program_completed(r)
    measured_at_sensor(r, rack)
    said = [m for m in r["messages"] if "tool 3 measures" in m and "stored" in m]
    if not said:
        fail("no message with the checked length: %s" % r["messages"])
    ok("checked: %s" % said[0])
    if r["samples"][-1]["tool_in_spindle"] != 3:
        fail("tool 3 not in the spindle")
    ok("the program went on with tool 3")


def check_check_broken(r, rack):
    last = r["samples"][-1]
    if not last["fixed_atc_probe.fault"]:
        fail("a tool 5 mm shorter than stored did not fault: %s" % r["messages"])
    said = [m for m in r["messages"] if "tool broken or pulled out?" in m]
    if not said:
        fail("no message asking 'tool broken or pulled out?': %s" % r["messages"])
    ok("fault: %s" % said[0])
    if last["interp"] != 1:
        fail("the program is still running")
    if abs(tool_table_length(r, 3) - 25.0) > 0.005:
        fail("a check must not write: tool 3 now %.4f" % tool_table_length(r, 3))
    ok("program stopped; tool 3's stored length unchanged (%.4f)" % tool_table_length(r, 3))


def check_refuse_when_off(r, rack):
    no_fault(r)
    said(r, "load of tool 4 refused: the machine is not on and homed, or is in estop")
    said(r, "unload of tool 4 refused: the machine is not on and homed, or is in estop")
    nothing_moved(r)
    if r["samples"][-1]["fixed_atc_probe.state"] != 1:
        fail("the changer is not idle after the machine came back on")
    ok("idle again once the machine is back on and homed")


def over_a_pocket(rack, pos):
    return any(abs(pos[0] - rack.pocket(t)[0]) < TOLERANCE and abs(pos[1] - rack.pocket(t)[1]) < TOLERANCE
               for t in rack.pockets)


def check_chuck_atoms(r, rack):
    no_fault(r)
    openings = rising_samples(r["samples"], "fixed_atc_probe.chuck")
    away = [s for s in openings if not over_a_pocket(rack, s["pos"])]
    zs = [round(s["pos"][2], 3) for s in away]
    if len(away) != 4 or any(not near(s["pos"][:2] + [0], [150.0, 200.0, 0]) for s in away):
        fail("expected 4 openings at X150 Y200 (M312 P2, then the lifting macro's 2), got %s" %
             [s["pos"] for s in away])
    if zs != [-40.0, -40.0, -40.0, -37.0]:
        fail("the openings were at Z %s, expected -40, -40, -40 and -37 (lifted 3 after a pulse)" % zs)
    if any(s["tool_in_spindle"] != 0 for s in away):
        fail("the chuck opened away from the rack with a tool in the spindle")
    ok("the eject pulsed twice and the macro twice, lifting Z between, all with the spindle empty")
    # Each pulse: chuck_seconds to open, Q (0.1 s) more open.
    samples, shortest = r["samples"], None
    for first in away[:2]:
        i = samples.index(first)
        j = next(k for k in range(i, len(samples)) if not samples[k]["fixed_atc_probe.chuck"])
        held = samples[j]["t"] - first["t"]
        shortest = held if shortest is None else min(shortest, held)
    if shortest < rack.c["chuck_seconds"] + 0.1 - 0.02:
        fail("an eject pulse held the chuck open %.3f s, less than chuck_seconds + Q" % shortest)
    ok("each eject pulse held the chuck open %.3f s at least (chuck_seconds %.2f + Q 0.1)" %
       (shortest, rack.c["chuck_seconds"]))
    if not any(s["fixed_atc_probe.state"] == 8 for s in samples):
        fail("the state pin never read chuck (8)")
    ok("the state pin read chuck (8) during the atoms")
    said(r, "chuck release refused: tool 2 is in the spindle and would drop; release it only at loading")
    said(r, "the machine is at X150.000 Y200.000 Z-40.000 mm")
    last = samples[-1]
    if last["interp"] != 1 or not near(last["pos"], [150.0, 200.0, -40.0]):
        fail("the program went on past the refused release: %s" % last["pos"])
    ok("the refused release stopped the program where it stood")
    spindle_holds(r, 2, "after the refused release")
    if last["fixed_atc_probe.chuck"] or last["fixed_atc_probe.state"] != 1:
        fail("the chuck is not closed with the changer idle at the end")
    ok("the chuck stayed closed, the changer idle")


def check_chuck_held(r, rack):
    no_fault(r)
    # chuck_atoms ended in an aborted program: its overrides must have been
    # restored in motion, or this first release is refused ("… M48 first").
    if any("override is off" in m for m in r["messages"]):
        fail("the overrides stayed off after the aborted program before: %s" % r["messages"])
    ok("the overrides were back on after the aborted program before (the release was taken)")
    held = [s for s in r["samples"] if s["fixed_atc_probe.chuck-held"]]
    if not held or any(not (s["motion.feed-inhibit"] and s["spindle.0.inhibit"]) for s in held):
        fail("chuck-held did not hold motion and the spindle in every sample it was on")
    # Each time the chuck was held, the machine stood where it was.
    moved, first = [], None
    for s in r["samples"]:
        if not s["fixed_atc_probe.chuck-held"]:
            first = None
            continue
        first = first or s
        if not near(s["pos"], first["pos"]):
            moved.append(s)
    if "held_at" not in r or moved:
        fail("the machine moved while the chuck was held open: %s" % [s["pos"] for s in moved[:3]])
    ok("while the release held the chuck open (%d samples) motion and the spindle were inhibited; "
       "a G0 asked for meanwhile waited at %s until aborted" % (len(held), r["held_at"]))
    said(r, "M6 T1 refused: the chuck is open (released from G-code); clamp it first")
    said(r, "chuck release refused: tool 1 is in the spindle and would drop")
    said(r, "chuck released at loading (G-code); tool 1 stays recorded in the spindle")
    openings = [s for s in rising_samples(r["samples"], "fixed_atc_probe.chuck")
                if not over_a_pocket(rack, s["pos"])]
    at_loading = [s for s in openings if near(s["pos"], loading(rack))]
    elsewhere = [s for s in openings if not near(s["pos"], loading(rack))]
    if len(at_loading) != 1 or at_loading[0]["tool_in_spindle"] != 1:
        fail("expected one opening at loading with tool 1 in the spindle: %s" %
             [(s["pos"], s["tool_in_spindle"]) for s in at_loading])
    if len(elsewhere) != 1 or elsewhere[0]["tool_in_spindle"] != 0:
        fail("expected one opening away from the rack and loading, with the spindle empty: %s" %
             [(s["pos"], s["tool_in_spindle"]) for s in elsewhere])
    ok("released once with the spindle empty, once with tool 1 at loading; never elsewhere")
    spindle_holds(r, 0, "at the end")
    last = r["samples"][-1]
    if last["fixed_atc_probe.chuck"] or last["fixed_atc_probe.state"] != 1:
        fail("the chuck is not closed with the changer idle at the end")
    ok("clamped and idle at the end")


CUT_OFF = {"sequence": "M6 T3", "step": "returning tool 1 to pocket 1", "pocket": 1}


def first_after(samples, t, condition):
    return next((s for s in samples if s["t"] >= t and condition(s)), None)


def check_kill_mid_change(r, rack):
    if "killed_at" not in r:
        fail("the component was not killed (the chuck never opened a 3rd time?): %s" % r["messages"])
    kill, at = r["kill_sample"], r["killed_at"]
    before = [s for s in r["samples"] if s["t"] < kill["t"]]
    after = [s for s in r["samples"] if s["t"] >= at]
    # The 3rd opening: T1's retrieval opens twice (flush, open), its return once.
    if kill["tool_in_spindle"] != 1 or not near(kill["pos"], rack.pocket(1)):
        fail("the kill was not at the return of tool 1: LinuxCNC T%d at %s" % (kill["tool_in_spindle"], kill["pos"]))
    ok("killed pid %d at t=%.3f with the chuck open at pocket 1, returning tool 1 (in M6 T3)" %
       (r["killed_pid"], at))
    chuck_gate_follows(before)
    closed = first_after(r["samples"], at, lambda s: not s["fatc-chuck-guard.chuck"])
    if closed is None or closed["t"] - at > 0.6:
        fail("the chuck guard did not close the chuck within 0.6 s of the kill (%s)" %
             ("never" if closed is None else "%.3f s" % (closed["t"] - at)))
    dead = first_after(r["samples"], at, lambda s: not s["fatc-chuck-guard.alive"])
    if dead is None or dead["t"] - at > 0.6:
        fail("fatc-chuck-guard.alive did not fall within 0.6 s of the kill")
    reopened = [s for s in r["samples"] if s["t"] >= closed["t"] and s["fatc-chuck-guard.chuck"]]
    if reopened:
        fail("the chuck opened again at t=%.3f after the guard closed it" % reopened[0]["t"])
    stuck = all(s["fixed_atc_probe.chuck"] for s in after)
    ok("the chuck guard closed the chuck %.3f s after the kill, alive fell after %.3f s "
       "(the dead component's chuck request stays %s)" % (closed["t"] - at, dead["t"] - at,
                                                          "true" if stuck else "mixed"))
    stopped = first_after(r["samples"], at, lambda s: s["interp"] == 1)
    if stopped is None or stopped["t"] - at > 3.0:
        fail("the program did not stop within 3 s of the kill (%s): %s" %
             ("never" if stopped is None else "%.3f s" % (stopped["t"] - at), r["messages"]))
    said(r, "stopped answering")
    if any("STEP_TIMEOUT" in m for m in r["messages"]):
        fail("the executor waited for STEP_TIMEOUT instead: %s" % r["messages"])
    ok("the program stopped %.3f s after the kill" % (stopped["t"] - at))
    # The kill comes while the chuck is open at the pocket, where the machine
    # stands: the abort has no move to stop, so nothing may move after it.
    for s in after:
        if not near(s["pos"], kill["pos"]):
            fail("the machine moved to %s at t=%.3f after the kill" % (s["pos"], s["t"]))
    ok("nothing moved after the kill (%d samples at %s)" % (len(after), kill["pos"]))
    last = r["samples"][-1]
    if last["tool_in_spindle"] != 1:
        fail("LinuxCNC should still say T1 (nobody told it otherwise), says T%d" % last["tool_in_spindle"])
    progress = r["snapshots"]["after_kill"]["state_file"].get("in_progress")
    if progress != CUT_OFF:
        fail("the state file does not say what was cut off: %s" % progress)
    ok("LinuxCNC still says T1; the state file says in_progress %s" % progress)


def program_samples(r, name):
    run = r["programs"][name]
    return [s for s in r["samples"] if run["began"] <= s["t"] <= run["ended"]]


def check_restart_after_kill(r, rack):
    restart = r.get("restart")
    if not restart:
        fail("the component was not restarted: %s" % r["messages"])
    dead, new = restart["dead"], restart["new"]
    if restart["registered_after_unload"]:
        ok("halcmd unloadusr/unload left the dead %s (pid %d) registered: they only SIGTERM its pid" %
           (dead["type"], dead["pid"]))
    if restart["registered_after_hal_exit"]:
        fail("the dead component is still registered after hal_exit(%d)" % dead["id"])
    if not new or new["pid"] == dead["pid"] or restart["pid_new"] != [new["pid"]] or new["state"] != "ready":
        fail("the component did not come back: %s, processes %s" % (new, restart["pid_new"]))
    ok("restarted in %.2f s: pid %d (was %d), %s" % (restart["load_seconds"], new["pid"], dead["pid"],
                                                   restart["commands"][0]))
    linked = {p: sig for p, sig in restart["links_before"].items() if sig}
    lost = {p: (sig, restart["links_after"].get(p)) for p, sig in linked.items()
            if restart["links_after"].get(p) != sig}
    if lost or set(restart["links_after"]) != set(restart["links_before"]):
        fail("the restarted component's pins are not wired as before: %s" % lost)
    ok("all %d pins are back on the signals they were on before the kill" % len(linked))

    before = r["snapshots"]["before_restart"]
    if before["tool_in_spindle"] != 1:
        fail("before the restart LinuxCNC should say T1, says T%d" % before["tool_in_spindle"])
    faulted = r["snapshots"]["faulted"]
    pins, status = faulted["pins"], faulted["status_file"]
    if not pins["fixed_atc_probe.fault"] or pins["fixed_atc_probe.cut-off-pocket"] != 1:
        fail("after the restart: fault=%s cut-off-pocket=%s" %
             (pins["fixed_atc_probe.fault"], pins["fixed_atc_probe.cut-off-pocket"]))
    if status.get("phase") != "fault" or status.get("cut_off") != CUT_OFF:
        fail("the status file says %s, cut_off %s" % (status.get("phase"), status.get("cut_off")))
    said(r, "cut off during M6 T3, returning tool 1 to pocket 1; pocket 1 may or may not hold tool 1")
    ok("came up faulted: cut-off-pocket 1, status file cut_off %s" % status["cut_off"])
    if not pins["fatc-chuck-guard.alive"] or pins["fatc-chuck-guard.chuck"]:
        fail("after the restart the guard should be alive with the chuck closed: %s" % pins)
    ok("the chuck guard is alive again, the chuck closed")

    refused = program_samples(r, "refused")
    if not any("M6 T3 refused" in m and "fault" in m for m in r["messages"]):
        fail("T3 M6 was not refused while faulted: %s" % r["messages"])
    ok("T3 M6 refused while faulted: %s" % [m for m in r["messages"] if "M6 T3 refused" in m][0])
    for s in refused:
        if not near(s["pos"], refused[0]["pos"]) or s["fatc-chuck-guard.chuck"]:
            fail("something moved during the refused program: %s, chuck %s" % (s["pos"], s["fatc-chuck-guard.chuck"]))
    if r["snapshots"]["after_refusal"]["tool_in_spindle"] != 1:
        fail("the refusal changed LinuxCNC's tool")
    ok("nothing moved during the refused program (%d samples); LinuxCNC still says T1" % len(refused))

    said(r, "told LinuxCNC the spindle holds nothing")
    confirmed = r["snapshots"]["confirmed"]
    state = confirmed["state_file"]
    if confirmed["pins"]["fixed_atc_probe.state"] != 1 or confirmed["tool_in_spindle"] != 0:
        fail("after the confirm: state %s, LinuxCNC T%s" % (confirmed["pins"]["fixed_atc_probe.state"],
                                                          confirmed["tool_in_spindle"]))
    if state.get("spindle") != 0 or 1 not in in_pockets(state) or "in_progress" in state or \
            state.get("uncertain"):
        fail("the state file after the confirm: %s" % state)
    ok("confirmed (spindle empty, pocket 1 holds its tool): idle %.2f s after Clear fault, "
       "LinuxCNC's tool 1 -> 0 by the component's M61, state file spindle 0, in_pocket %s" %
       (r["idle_after_confirm_at"] - r["confirmed_at"], in_pockets(state)))

    tools = distinct(r["samples"], "tool_in_spindle")
    if tools != [1, 0, 3]:
        fail("LinuxCNC's tool in spindle went %s, expected 1, 0, 3" % tools)
    change = program_samples(r, "after_confirm")
    if any(s["fixed_atc_probe.fault"] for s in change):
        fail("fixed_atc_probe faulted during T3 M6 after the confirm: %s" % r["messages"])
    visits_in_order(change, rack.retrieve_waypoints(3))
    spindle_holds(r, 3, "after T3 M6")
    ok("T3 M6 ran after the confirm: LinuxCNC and the changer say T3")


def check_status_lock_lost(r, rack):
    words = "load of tool 4 refused: LinuxCNC's status channel does not answer"
    shown = [m["text"] for m in r["status_file"].get("messages", [])]
    if not any(words in text for text in shown):
        fail("the panel's words after the status lock was lost: %s" % shown)
    if r["status_file"].get("phase") != "idle":
        fail("the changer left idle: %s" % r["status_file"].get("phase"))
    ok("with task's status lock held by a dead reader, Load is refused in one line on the panel "
       "(%.1f s after)" % (r["answered_at"] - r["lock_lost_at"]))


def main(checks=None):
    """check_SCENARIO(r, rack) of `checks` (a checker's globals; this file's unless given)."""
    results = load_results(sys.argv[1], sys.argv[3])
    rack = Rack(json.load(open(sys.argv[2])))
    name = sys.argv[3]
    r = scenario(results, name)
    (checks or globals())["check_" + name](r, rack)
    print("%s: %.1f s, %d samples" % (name, r["duration"], len(r["samples"])))


if __name__ == "__main__":
    main()
