#!/usr/bin/env python3
"""Checks one scenario of the rack run (scenarios_rack.json on rack_config.json:
tools and pockets differ, pocket 4 is approached from the top, pocket 5 from
its own side) against what LinuxCNC reported: the tool in the spindle, every
place the spindle stood still, the path between them, the pocket the component
said it served, and the state file.
   check_rack.py RESULTS.json CONFIG.json SCENARIO
Prints what it checked; exits 1 on the first failed expectation."""
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
from check import (TOLERANCE, Rack, distance_to_segment, distinct, fail, load_results, measured_to_truth, near, no_fault, ok,  # noqa: E402
                   stops)

SERVED = "fixed_atc_probe.pocket-served"


class Expected:
    """The rack as the changer should keep it: pocket -> tool, and which sit in
    their pocket; the stops each change should make, from the config alone."""

    def __init__(self, rack):
        self.rack = rack
        self.tools = rack.first_tools()
        self.home = {n for n, t in self.tools.items() if t}
        self.spindle = 0

    def pocket_of(self, tool):
        return next(n for n, t in self.tools.items() if t == tool)

    def state_pockets(self):
        """The state file's `pockets`, as it should read now."""
        return {str(n): {"tool": t, "in_pocket": n in self.home} for n, t in self.tools.items()}

    def to_safe(self, at):
        """Up to safe Z, then (the prototype's path) over to safe XY."""
        up = [("safe Z", self.rack.at_safe_z(at), False)]
        return up if self.rack.direct else up + [("safe", self.rack.safe(), False)]

    def put_back(self, at):
        """The spindle's tool back to its own pocket: (stops, pocket)."""
        pocket = self.pocket_of(self.spindle)
        self.home.add(pocket)
        self.spindle = 0
        return self.to_safe(at) + self.rack.return_stops(pocket), pocket

    def change(self, at, tool):
        """M6 T`tool` from position `at`: its stops, and the pockets served in order."""
        route, served = [], []
        if self.spindle:
            legs, pocket = self.put_back(at)
            if tool and self.rack.direct:
                legs = legs[:-1]  # the fetch starts at safe Z over the pocket the return left
            route, served, at = legs, [pocket], legs[-1][1]
        if tool:
            pocket = self.pocket_of(tool)
            self.home.discard(pocket)
            self.spindle = tool
            route += self.to_safe(at) + self.rack.retrieve_stops(pocket)
            served.append(pocket)
        return route, served


def merged(route):
    """A route without repeats: a move to where the spindle already is, is no stop."""
    out = []
    for stop in route:
        if not out or not near(out[-1][1], stop[1]):
            out.append(stop)
    return out


def observed(r):
    """Where the spindle stood still, in order, as (position, first, last) sample indexes."""
    found = stops(r["samples"])
    if not found:
        fail("no sample shows the spindle standing still")
    return found


def follows_route(r, route, found, offset=0):
    """The stops from found[offset] on are the route's, one for one. Returns the
    index after the route's last stop."""
    route = merged(route)
    for i, (name, target, _) in enumerate(route):
        if offset + i >= len(found):
            fail("the spindle stopped %d times, the route has %d more stops from %s on" %
                 (len(found) - offset, len(route) - i, name))
        pos = found[offset + i][0]
        if not near(pos, target):
            fail("stop %d: the spindle stood at %s, expected %s %s (stops so far: %s)" % (
                offset + i, [round(v, 3) for v in pos], name, target,
                [[round(v, 3) for v in f[0]] for f in found[max(0, offset + i - 4):offset + i]]))
    ok("%d stops, each at the config's waypoint: %s" % (len(route), " > ".join(s[0] for s in route)))
    return offset + len(route)


def straight_and_slow(r, route, found, offset, feed, rounded=()):
    """Between two stops the spindle moved along the straight line (but for the
    moves through rounded corners, `rounded`); into a stop reached slowly, no
    faster than pocket_feed."""
    route = merged(route)
    samples = r["samples"]
    slow = 0
    for i in range(1, len(route)):
        (a, _, left), (b, arrived, _) = found[offset + i - 1], found[offset + i]
        for s in samples[left:arrived + 1] if i not in rounded else []:
            if distance_to_segment(s["pos"], a, b) > TOLERANCE:
                fail("between %s and %s the spindle left the straight line: %s at %.3f s" % (
                    route[i - 1][0], route[i][0], s["pos"], s["t"]))
        if route[i][2]:
            seconds = samples[arrived]["t"] - samples[left]["t"]
            least = math.dist(a, b) / (feed / 60.0)
            if seconds < 0.9 * least:
                fail("%s reached in %.3f s from %s: faster than pocket_feed (%.3f s)" % (
                    route[i][0], seconds, route[i - 1][0], least))
            slow += 1
    ok("every move straight between its stops; %d slow moves at pocket_feed or slower" % slow)


def outside_other_columns(r, rack):
    """No sample inside a pocket's keep-out column (rack_keepout_margin, default
    half the side offset, around it, up to above-clearance) except the pocket
    the component says it serves."""
    margin = rack.keepout_margin()
    inside = 0
    for s in r["samples"]:
        x, y, z = s["pos"]
        for n in rack.pockets:
            p = rack.pocket(n)
            top = p[2] + rack.c["pocket_above_clearance_offset_z"]
            if abs(x - p[0]) < margin - 1e-3 and abs(y - p[1]) < margin - 1e-3 and z < top - 1e-3:
                inside += 1
                if s[SERVED] != n:
                    fail("at %s (%.3f s) the spindle is in pocket %d's keep-out column, but "
                         "pocket-served says %s" % (s["pos"], s["t"], n, s[SERVED]))
    ok("no sample in a keep-out column but the served pocket's (%d samples inside one)" % inside)


def rounded_at_safe_z(r, route, found, rack):
    """blend_tolerance: the route's stops at safe Z that the spindle did not
    stand at are corners it rounded. Each must lie between two rapids, and the
    path between the stops around it within blend_tolerance of the straight
    moves through it (G64 P; outside_other_columns checks the rest); beside a
    way up or down, rounded where something moved up or down and across at
    once, within blend_tolerance where that way lies that far outside every
    keep-out column, else within how far safe Z lies above the columns' tops
    divided by 3.5 (a run within the least of its corners'). Returns the route
    without them, the stops the spindle stood at, and the indexes of the moves
    between those that ran through a rounded corner."""
    blend, safe_z = rack.c["blend_tolerance"], rack.c["safe"]["z"]
    margin = rack.keepout_margin()
    top = rack.c["pocket_above_clearance_offset_z"]
    room = min(safe_z - (rack.pocket(n)[2] + top) for n in rack.pockets)
    over_columns = room / 3.5

    def over_a_column_xy(pos):
        return [p for p in (rack.pocket(n) for n in rack.pockets)
                if abs(pos[0] - p[0]) < margin and abs(pos[1] - p[1]) < margin]

    def in_a_column(pos):
        return any(pos[2] < p[2] + top for p in over_a_column_xy(pos))

    route = merged(route)
    samples = r["samples"]
    kept, rounded, through, over_a_column, j = [], set(), [], [], 0
    deepest = 0.0  # below safe Z, off the straight moves over a column's XY
    for i, stop in enumerate(route):
        if j < len(found) and near(found[j][0], stop[1]):
            if through:
                # The samples between the two stops stay near the moves through the corners.
                line = [kept[-1][1]] + [c[1] for c, _ in through] + [stop[1]]
                allowed = min(a for _, a in through)
                names = " and ".join(c[0] for c, _ in through)
                for s in samples[found[j - 1][2]:found[j][1] + 1]:
                    off = min(distance_to_segment(s["pos"], a, b) for a, b in zip(line, line[1:]))
                    if off > allowed + TOLERANCE:
                        fail("rounding %s the spindle was %.3f off its moves at %.3f s (allowed %.3f)"
                             % (names, off, s["t"], allowed))
                    if off > TOLERANCE and over_a_column_xy(s["pos"]):
                        deepest = max(deepest, safe_z - s["pos"][2])
                    # Inside a keep-out column nothing is rounded: the spindle is on its straight moves.
                    if off > TOLERANCE and in_a_column(s["pos"]):
                        fail("rounding %s the spindle was %.3f off its moves inside a keep-out column at "
                             "%s, %.3f s" % (names, off, s["pos"], s["t"]))
                rounded.add(len(kept))
                through = []
            kept.append(stop)
            j += 1
            continue
        if not kept or i + 1 == len(route) or abs(stop[1][2] - safe_z) > TOLERANCE \
                or stop[2] or route[i + 1][2]:
            fail("the spindle did not stand at %s %s, and it is no corner at safe Z between two "
                 "rapids (stops so far: %s)" % (stop[0], stop[1], [k[0] for k in kept]))
        # Beside a way up or down lying closer than blend_tolerance to a column,
        # or in one, the corner is rounded within the room above the columns divided by 3.5.
        vertical = any(abs(other[1][0] - stop[1][0]) < TOLERANCE and abs(other[1][1] - stop[1][1]) < TOLERANCE
                       for other in (route[i - 1], route[i + 1]))
        allowed = blend
        if vertical:
            clear = min(math.hypot(max(abs(stop[1][0] - p[0]) - margin, 0.0), max(abs(stop[1][1] - p[1]) - margin, 0.0))
                        for p in (rack.pocket(n) for n in rack.pockets))
            if clear < blend - TOLERANCE:
                allowed = min(blend, over_columns)
                over_a_column.append(stop[0])
            if not any(math.dist(a["pos"], stop[1]) < 3 * allowed
                       and math.dist(a["pos"][:2], b["pos"][:2]) > TOLERANCE
                       and abs(a["pos"][2] - b["pos"][2]) > TOLERANCE for a, b in zip(samples, samples[1:])):
                fail("%s %s was not stood at, but nothing went up or down and across at once near it"
                     % (stop[0], stop[1]))
        through.append((stop, allowed))
    if not rounded:
        fail("blend_tolerance %g: every corner at safe Z was a stop, none rounded" % blend)
    if not over_a_column:
        fail("no corner over or beside a keep-out column was rounded: the run shows nothing of them")
    # Rounded, not only stopped short: somewhere the spindle went up or down and across at once.
    diagonal = sum(1 for a, b in zip(samples, samples[1:])
                   if math.dist(a["pos"][:2], b["pos"][:2]) > TOLERANCE
                   and abs(a["pos"][2] - b["pos"][2]) > TOLERANCE)
    if diagonal == 0:
        fail("no sample moved up or down and across at once: no corner was rounded")
    ok("%d moves ran through rounded corners at safe Z, each within blend_tolerance %g of its "
       "straight moves, %d corners over or beside a column within %.3f; %d samples moved up or "
       "down and across at once; off its straight moves over a column at most %.3f below safe Z, "
       "the columns' tops %.3f below it" % (len(rounded), blend, len(over_a_column),
                                             min(blend, over_columns), diagonal, deepest, room))
    return kept, rounded


def served_at_stops(r, route, found, offset):
    """At every stop at a pocket's waypoint, pocket-served names that pocket."""
    route = merged(route)
    checked = 0
    for i, (name, _, _) in enumerate(route):
        words = name.split()
        if "pocket" not in words or "safe" in words:
            continue
        pocket = int(words[words.index("pocket") + 1])
        first, last = found[offset + i][1], found[offset + i][2]
        values = {s[SERVED] for s in r["samples"][first:last + 1]}
        if values != {pocket}:
            fail("at %s pocket-served read %s" % (name, sorted(values, key=str)))
        checked += 1
    ok("pocket-served named the pocket at each of %d stops at a pocket" % checked)


def served_per_change(r, expected):
    """While each change runs (busy), the pockets pocket-served names, in order."""
    runs, current = [], None
    for s in r["samples"]:
        if s["fixed_atc_probe.busy"]:
            if current is None:
                current = []
                runs.append(current)
            if s[SERVED] and (not current or current[-1] != s[SERVED]):
                current.append(s[SERVED])
        else:
            current = None
    if runs != expected:
        fail("pocket-served named %s during the changes, expected %s" % (runs, expected))
    ok("pocket-served during each change: %s" % runs)


def state_pockets(r, wanted, what):
    got = r["state_file"].get("pockets")
    if got != wanted:
        fail("%s the state file's pockets are %s, expected %s" % (what, got, wanted))
    if r["state_file"].get("spindle") != 0:
        fail("%s the state file has T%s in the spindle" % (what, r["state_file"].get("spindle")))
    ok("%s the state file's pockets: %s" % (what, {k: v["tool"] if v["in_pocket"] else "-"
                                                  for k, v in got.items()}))


def tools_went(r, wanted):
    """LinuxCNC's tool in spindle (stat) and iocontrol's tool-number, change by
    change; the changer's tool-in-spindle the same, empty between a return and a fetch."""
    for key in ("tool_in_spindle", "iocontrol.0.tool-number"):
        went = distinct(r["samples"], key)
        if went != wanted:
            fail("%s went %s, expected %s" % (key, went, wanted))
    changer = [t for t in distinct(r["samples"], "fixed_atc_probe.tool-in-spindle") if t]
    if changer != [t for t in wanted if t]:
        fail("the changer's tool-in-spindle held %s, expected %s" % (changer, [t for t in wanted if t]))
    ok("LinuxCNC's tool in spindle went %s (stat and iocontrol; the changer's pin agrees)" % wanted)


def program_changes(r, rack, expected, tools):
    """A program of M6s: the tools, every stop, the path, pocket-served, the keep-out."""
    no_fault(r)
    tools_went(r, [expected.spindle] + tools)
    found = observed(r)
    at = found[0][0]
    route, served = [("start", at, False)], []
    snapshots = r.get("snapshots", {})
    fetched = []
    for tool in tools:
        legs, pockets = expected.change(at, tool)
        route += legs
        served.append(pockets)
        at = route[-1][1]
        fetched.append(tool)
        # The scenario's snapshot when the changer recorded the tool: "T12", then "T12 #2".
        snap = snapshots.get("T%d" % tool + ("" if fetched.count(tool) == 1 else " #%d" % fetched.count(tool)))
        if tool and not snap:
            fail("no snapshot of the state file when T%d was gripped" % tool)
        if snap and tool:
            # The moment the changer recorded the new tool in the spindle.
            got = snap["state_file"].get("pockets")
            if got != expected.state_pockets() or snap["state_file"].get("spindle") != tool:
                fail("when T%d was gripped the state file said spindle T%s, pockets %s; expected %s" % (
                    tool, snap["state_file"].get("spindle"), got, expected.state_pockets()))
            ok("when T%d was gripped the state file had it out of pocket %d, the previous tool home" %
               (tool, expected.pocket_of(tool)))
    rounded = set()
    if rack.c.get("blend_tolerance", 0) > 0:
        route, rounded = rounded_at_safe_z(r, route, found, rack)
    end = follows_route(r, route, found)
    if end != len(found):
        fail("the spindle stopped %d more times after the route: %s" % (
            len(found) - end, [f[0] for f in found[end:]]))
    straight_and_slow(r, route, found, 0, rack.c["pocket_feed"], rounded)
    served_at_stops(r, route, found, 0)
    served_per_change(r, served)
    outside_other_columns(r, rack)
    state_pockets(r, expected.state_pockets(), "at the end")


CHANGES = [12, 7, 3, 5, 12, 0]  # rack_changes.ngc
T20 = [20, 0]  # rack_t20.ngc


def check_rack_changes(r, rack, expected):
    program_changes(r, rack, expected, CHANGES)
    # Spelled out: the top pocket has no side stop, pocket 5 none at the rack's side offset.
    default = rack.c["pocket_side_offset"]
    for name, place in (("the side of top pocket 4", rack.side(4)),
                        ("pocket 5's side at the rack's pocket_side_offset",
                         [rack.pocket(5)[0] + default["x"], rack.pocket(5)[1] + default["y"], rack.pocket(5)[2]])):
        if any(near(f[0], place) for f in observed(r)):
            fail("the spindle stopped at %s %s" % (name, place))
        ok("never at %s %s" % (name, place))


def check_rack_load(r, rack, expected):
    """T20 from outside, loaded into pocket 3 through tool-number and pocket-number."""
    no_fault(r)
    spindle = distinct(r["samples"], "tool_in_spindle")
    if spindle != [0, 20, 0]:
        fail("LinuxCNC's tool in spindle went %s, expected [0, 20, 0]" % spindle)
    ok("LinuxCNC's tool in spindle went %s (M61 at the prompt, M61 Q0 once home)" % spindle)
    measured_to_truth(r, rack.c, 20, "loaded into pocket 3")
    found = observed(r)
    start = found[0][0]
    load = [("start", start, False), ("loading Z", [start[0], start[1], rack.c["loading"]["z"]], False),
            ("loading", [rack.c["loading"][a] for a in "xyz"], False)]
    i = follows_route(r, load, found)
    # The probe's stops: over the sensor, between probe_limit and loading Z.
    sensor = rack.c["probe_limit"]
    probe = i
    while i < len(found) and near(found[i][0][:2] + [0.0], [sensor["x"], sensor["y"], 0.0]) and \
            sensor["z"] <= found[i][0][2] <= rack.c["loading"]["z"] + TOLERANCE:
        i += 1
    if i - probe < 3:
        fail("the probe stopped %d times over the sensor, expected seek, back-off, latch and retract" %
             (i - probe))
    ok("%d stops over the sensor while probing" % (i - probe))
    load_t20(expected)
    expected.spindle = 20
    route = [("probed", found[i - 1][0], False)]
    legs, pocket = expected.put_back(found[i - 1][0])
    if pocket != 3:
        fail("the checker put T20 in pocket %d" % pocket)
    route += legs
    end = follows_route(r, route, found, i - 1)
    if end != len(found):
        fail("the spindle stopped %d more times after the return: %s" % (
            len(found) - end, [f[0] for f in found[end:]]))
    straight_and_slow(r, route, found, i - 1, rack.c["pocket_feed"])
    served_at_stops(r, route, found, i - 1)
    outside_other_columns(r, rack)
    state_pockets(r, expected.state_pockets(), "after the load:")


def check_rack_t20(r, rack, expected):
    program_changes(r, rack, expected, T20)


def verify_runs(r):
    """The sample ranges where the state pin said verifying (7), in order."""
    runs, first = [], None
    for i, s in enumerate(r["samples"]):
        if s["fixed_atc_probe.state"] == 7 and first is None:
            first = i
        elif s["fixed_atc_probe.state"] != 7 and first is not None:
            runs.append((first, i))
            first = None
    return runs


def holds(r, first, last):
    """Where the spindle stood each time the dry run held for Continue, in order:
    a sample late in each hold. A hold begins where waiting-for-operator rises
    (it falls between two holds, even of one place) and keeps the step number
    it began with. The driver reads the pins one by one, so the hold's last
    sample may be torn by the Continue that ends it (can-cancel already low,
    waiting-for-operator not yet, the next step number): the one before it
    stands for the hold."""
    holds_seen, waiting, step = [], False, None
    for s in r["samples"][first:last]:
        now = s["fixed_atc_probe.waiting-for-operator"]
        if now and not waiting:
            holds_seen.append([s])
            step = s["fixed_atc_probe.step-number"]
        elif now and s["fixed_atc_probe.step-number"] == step:
            holds_seen[-1].append(s)
        waiting = now
    return [hold[-2] if len(hold) > 1 else hold[-1] for hold in holds_seen]


def check_rack_verify(r, rack, expected):
    """M6 T3 over MDI empties top pocket 4; a dry run through it held at every
    waypoint; pocket 1 (T12 in it) refused; a second run cancelled in the pocket."""
    no_fault(r)
    if distinct(r["samples"], "tool_in_spindle") != [3]:
        fail("LinuxCNC's tool in spindle went %s after M6 T3, expected [3] throughout" %
             distinct(r["samples"], "tool_in_spindle"))
    runs = verify_runs(r)
    if len(runs) != 2:
        fail("the state pin read verifying (7) in %d runs, expected 2" % len(runs))
    p = rack.pocket(4)
    safe_z = rack.c["safe"]["z"]
    clearance = rack.above(4, "pocket_above_clearance_offset_z")
    waypoints = [("safe Z", None), ("safe XY", rack.safe()), ("over pocket 4", [p[0], p[1], safe_z]),
                 ("above-clearance 4", clearance), ("pocket 4", p), ("above-clearance 4", clearance),
                 ("safe Z over pocket 4", [p[0], p[1], safe_z])]
    for (first, last), wanted in zip(runs, (waypoints, waypoints[:5])):
        held = holds(r, first, last)
        if len(held) != len(wanted):
            fail("the dry run held %d times, expected %d: %s" % (
                len(held), len(wanted), [[round(v, 3) for v in s["pos"]] for s in held]))
        for s, (name, target) in zip(held, wanted):
            at = s["pos"]
            if (target is None and abs(at[2] - safe_z) > 1e-3) or (target and not near(at, target)):
                fail("held for Continue at %s, expected %s %s" % (at, name, target or "Z %s" % safe_z))
            if s[SERVED] != 4 or s["fixed_atc_probe.can-cancel"] is not True:
                fail("at %s pocket-served read %s, can-cancel %s" % (name, s[SERVED], s["fixed_atc_probe.can-cancel"]))
        ok("held for Continue %d times, each at the config's waypoint: %s" % (
            len(held), " > ".join(n for n, _ in wanted)))
        during = r["samples"][first:last]
        for pin in ("fixed_atc_probe.chuck", "fatc-chuck-guard.chuck", "fixed_atc_probe.air-blast"):
            if any(s[pin] for s in during):
                fail("%s went on during the dry run" % pin)
        fastest = max(s["vel"] for s in during) * 60.0
        if fastest > rack.c["verify_feed"] * 1.02:
            fail("the dry run moved at %.0f per minute, faster than verify_feed %s" % (
                fastest, rack.c["verify_feed"]))
        ok("the chuck and the air blast stayed off; fastest move F%.0f (verify_feed %s)" % (
            fastest, rack.c["verify_feed"]))
    end_of_first = r["samples"][runs[0][1]]
    if not near(end_of_first["pos"], rack.safe()):
        fail("the full dry run ended at %s, expected safe %s" % (end_of_first["pos"], rack.safe()))
    ok("the full dry run ended at safe %s" % rack.safe())
    last = r["samples"][-1]
    if not near(last["pos"], p) or last["fixed_atc_probe.state"] != 1:
        fail("after Cancel the spindle is at %s (state %s), expected to stay in pocket 4 %s, idle" % (
            last["pos"], last["fixed_atc_probe.state"], p))
    ok("after Cancel the spindle stayed in pocket 4 %s and the changer is idle" % p)
    said = {
        "refused": "verify of pocket 1 refused: pocket 1 holds tool 12; fetch it first (M6 T12) to "
                   "verify with it in the spindle",
        "done": "verify of pocket 4 done: 8 moves through its approach at F3000, back at safe XY",
        "cancelled": "verify of pocket 4 cancelled by the operator; the spindle stays where it stopped: pocket 4 "
                     "(X=200.000 Y=20.000 Z=-80.000), below the rack's clearance: jog it out the "
                     "way it came in before the next change"}
    status_said = [m["text"] for m in (r["status_file"] or {}).get("messages", [])]
    for what, line in said.items():
        if not any(line in m for m in r["messages"]):
            fail("LinuxCNC never showed the %s line %r: %s" % (what, line, r["messages"][-6:]))
        if line not in status_said:
            fail("the status file (the panel's words) lacks the %s line: %s" % (what, status_said))
    ok("LinuxCNC and the status file said: refused, done, cancelled in the machinist's words")
    # Until the cancelled run ended: the spindle then stays in pocket 4, served by nothing.
    # The driver reads the pins one by one, so a sample may already have
    # pocket-served 0 and still the state verifying: the run ends at the first.
    end = runs[1][1]
    while end > runs[1][0] and r["samples"][end - 1][SERVED] != 4:
        end -= 1
    outside_other_columns({"samples": r["samples"][:end]}, rack)
    if r["state_file"].get("spindle") != 3 or r["state_file"]["pockets"]["4"] != {"tool": 3, "in_pocket": False}:
        fail("the state file after the dry runs: %s" % r["state_file"])
    ok("the state file still has T3 in the spindle, pocket 4 its but empty: a dry run records nothing")


def check_blend_modal(r, rack, expected):
    """A program cutting in G64 P0.02 Q0.01 gets them back after a blended M6:
    neither the executor's G64 P (its blend_tolerance) nor its G61.1."""
    no_fault(r)
    snap = r.get("snapshot")
    if not snap:
        fail("the program never reached its M0 after M6")
    codes = set(snap["gcodes"])
    if 640 not in codes or 611 in codes:
        fail("after M6: %s, expected the program's G64, not the executor's G61.1"
             % sorted(c for c in codes if c > 0))
    tolerances = (snap["path_tolerance"], snap["naive_cam_tolerance"])
    if abs(tolerances[0] - 0.02) > 1e-9 or abs(tolerances[1] - 0.01) > 1e-9:
        fail("after M6 G64 P%g Q%g, expected the program's P0.02 Q0.01 (blend_tolerance %g)"
             % (tolerances + (rack.c["blend_tolerance"],)))
    if r["samples"][-1]["tool_in_spindle"] != 7:
        fail("T7 not in the spindle after M6")
    ok("after a blended M6 the program's G64 P0.02 Q0.01 again (LinuxCNC says), T7 in the spindle")


def load_t20(expected):
    expected.tools[3] = 20


# What each scenario leaves in the rack, for the checks of those after it.
ORDER = [("rack_changes", lambda e: [e.change(e.rack.safe(), t) for t in CHANGES]),
         ("blend_modal", lambda e: None),  # the blend run's last
         ("rack_load", load_t20), ("rack_t20", lambda e: [e.change(e.rack.safe(), t) for t in T20]),
         ("rack_verify", None)]


def main():
    results = load_results(sys.argv[1], sys.argv[3])
    rack = Rack(json.load(open(sys.argv[2])))
    name = sys.argv[3]
    if results.get("error"):
        print("the run reported: %s" % results["error"])
    expected = Expected(rack)
    # The scenarios run one after the other on one machine.
    for before, effect in ORDER[:[n for n, _ in ORDER].index(name)]:
        effect(expected)
    by_name = {s["name"]: s for s in results["scenarios"]}
    if name not in by_name:
        fail("scenario %s did not run" % name)
    globals()["check_" + name](by_name[name], rack, expected)
    print("%s on the %s path: %.1f s" % (name, "direct" if rack.direct else "prototype",
                                         by_name[name]["duration"]))


if __name__ == "__main__":
    main()
