#!/usr/bin/env python3
"""Checks one scenario of the rack_touch run: the simulated rack
(config/sim/sim_rack.hal) touched by a probe on the real LinuxCNC, judged
from what LinuxCNC reported (#5061-#5063, #5070 after each G38.3) against
the rack's truth read from its pins.
   check_rack_touch.py RESULTS.json SCENARIO
Prints what it checked with the figures; exits 1 on the first failed expectation."""
import json
import os
import sys

TOLERANCE = 0.002  # mm: a latched touch against the simulated truth
AXES = "XYZ"


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def ok(message):
    print("ok: " + message)


def load(results, name):
    """The scenario as the driver wrote it (harness/driver.py: RESULTS.d/NAME.json)."""
    path = os.path.join(results + ".d", name + ".json")
    if not os.path.exists(path):
        run = json.load(open(os.path.join(results + ".d", "run.json")))
        fail("no scenario %s in the run (%s); the run's error: %s" % (name, run["names"], run["error"]))
    return json.load(open(path))


def expected_trip(truth, touch_name):
    """Where the nose stands when the ball first meets the rack, on the touch's
    axis: pocket 3's bore wall from its axis (the bore's radius less the
    ball's), or the top face with the ball's lowest point on it."""
    pins = truth["pins"]
    bore_x, bore_y = truth["bores"][2]
    wall = pins["bore-diameter"] / 2 - pins["stylus-radius"]
    return {"+X": bore_x + wall, "-X": bore_x - wall, "+Y": bore_y + wall, "-Y": bore_y - wall,
            "-Z": truth["top_z"] + pins["probe-length"]}[touch_name]


def check_touch(name, touch, truth):
    """The latched touch within TOLERANCE of the truth, LinuxCNC's #506x as its
    probed position. Returns the error."""
    axis = AXES.index(touch["axis"])
    latch = touch.get("latch")
    if not touch["seek"]["tripped"] or latch is None or not latch["tripped"]:
        fail("%s: the probe did not touch (seek %s, latch %s)" % (name, touch["seek"], latch))
    found = latch["probed"][axis]
    error = found - expected_trip(truth, name)
    if abs(error) > TOLERANCE:
        fail("%s: touched at %s %.6f, the simulated rack's contact is at %.6f: %.6f off (tolerance %.3f)"
             % (name, touch["axis"], found, expected_trip(truth, name), error, TOLERANCE))
    for k in range(3):
        if abs(latch["probed"][k] - latch["stat_probed"][k]) > 1e-5:
            fail("%s: #%d %.6f is not LinuxCNC's probed position %.6f" % (name, 5061 + k, latch["probed"][k],
                                                                         latch["stat_probed"][k]))
    ok("%s: latched at %s %.6f (F%g), the contact at %.6f: %+.6f; the seek (F%g) %+.6f"
       % (name, touch["axis"], found, latch["feed"], expected_trip(truth, name), error,
          touch["seek"]["feed"], touch["seek"]["probed"][axis] - expected_trip(truth, name)))
    return error


def touches(result, truth_name):
    truth = result["rack_truth"][truth_name]
    done = result.get("touches", {})
    for name in ("+X", "-X", "+Y", "-Y", "-Z"):
        if name not in done:
            fail("no touch %s in %s (touches: %s)" % (name, result["name"], sorted(done)))
        check_touch(name, done[name], truth)
    # The bore's centre from each pair, as the flows find it: the ball's radius cancels.
    centre = [(done["+X"]["latch"]["probed"][0] + done["-X"]["latch"]["probed"][0]) / 2,
              (done["+Y"]["latch"]["probed"][1] + done["-Y"]["latch"]["probed"][1]) / 2]
    bore = truth["bores"][2]
    for k in range(2):
        if abs(centre[k] - bore[k]) > TOLERANCE:
            fail("pocket 3's bore found at %s %.6f, truly at %.6f" % (AXES[k], centre[k], bore[k]))
    ok("pocket 3's bore centre found at X %.6f Y %.6f from its walls; truly at X %.4f Y %.4f (shift %s)"
       % (centre[0], centre[1], bore[0], bore[1],
          [truth["pins"]["shift-" + a] for a in "xyz"]))
    return centre


def check_errors(result):
    errors = [m for m in result["messages"] if not m.startswith("fatc-parameters")
              and ("error" in m.lower() or "tripped" in m.lower())]
    if errors:
        fail("LinuxCNC said: %s" % errors)


def main():
    results, name = sys.argv[1], sys.argv[2]
    result = load(results, name)
    check_errors(result)
    if name == "rack_no_probe":
        touch = result["touches"]["-Z"]
        seek = touch["seek"]
        if seek["tripped"] or seek["stat_tripped"] or seek["probe_input"]:
            fail("with no probe in the spindle the rack tripped the probe input: %s" % seek)
        if not seek["rack_touching"]:
            fail("the move did not reach into the rack (fatc-sim-rack.touching false at Z %.4f)"
                 % seek["stat_probed"][2])
        ok("no probe in the spindle: G38.3 to Z %.3f into the rack's top face ended untripped (#5070 0), "
           "motion.probe-input false while fatc-sim-rack.touching was true" % seek["to"])
    elif name == "rack_fetch_probe":
        truth = result["rack_truth"]["after"]
        length = result["tool_table"].get("2")
        if result["samples"][-1]["tool_in_spindle"] != 2:
            fail("tool 2 (the probe) is not in the spindle: %s" % result["samples"][-1]["tool_in_spindle"])
        if length is None or abs(length - truth["pins"]["probe-length"]) > 0.01:
            fail("the probe measured %s on the simulated sensor, the simulated rack's probe is %.4f long"
                 % (length, truth["pins"]["probe-length"]))
        ok("the probe (T2) in the spindle, measured %.4f on the simulated sensor: the simulated rack's "
           "probe-length is %.4f" % (length, truth["pins"]["probe-length"]))
    elif name == "rack_touch":
        touches(result, "before")
    elif name == "rack_touch_shifted":
        shifted = touches(result, "shifted")
        before = load(results, "rack_touch")
        unshifted = [(before["touches"]["+X"]["latch"]["probed"][0] + before["touches"]["-X"]["latch"]["probed"][0]) / 2,
                     (before["touches"]["+Y"]["latch"]["probed"][1] + before["touches"]["-Y"]["latch"]["probed"][1]) / 2]
        moved = [shifted[k] - unshifted[k] for k in range(2)]
        shift = result["rack_truth"]["shifted"]["pins"]
        if abs(moved[0] - shift["shift-x"]) > TOLERANCE or abs(moved[1] - shift["shift-y"]) > TOLERANCE:
            fail("the rack shifted by X %.4f Y %.4f, the touches found it moved by X %.6f Y %.6f"
                 % (shift["shift-x"], shift["shift-y"], moved[0], moved[1]))
        ok("the rack shifted by X %.4f: the touches found the bore moved by X %.6f Y %.6f"
           % (shift["shift-x"], moved[0], moved[1]))
        restored = result["rack_truth"]["restored"]["pins"]
        if any(restored["shift-" + a] != 0 for a in "xyz"):
            fail("the rack was left shifted: %s" % restored)
    else:
        fail("no such scenario: %s" % name)


if __name__ == "__main__":
    main()
