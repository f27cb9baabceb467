#!/usr/bin/env python3
"""Checks one scenario of the rack found by touch as the changer runs it
(touch-pockets, teach-datum, check-datum, clear-datum-drift over
`fixed_atc_probe --operator`) on the real LinuxCNC: config.json as written
on disk, the state file, the command's exit status and words, against the
simulated rack's truth (config/sim/sim_rack.hal, moved by shift_rack).
   check_touch_flows.py RESULTS.json SCENARIO
Prints what it checked with the figures; exits 1 on the first failed expectation."""
import json
import sys

from check_rack_touch import fail, ok, load

TOLERANCE = 0.02     # mm: a taught position against the simulated truth (issue 45)
ABOVE_TOP = 20.0     # rack_touch.pocket_above_top of the run's config
FAILED = 7           # --operator's exit status for a request that failed


def config_of(files, name):
    return json.loads(files[name]["config"])


def command(result, name, code):
    run = result.get("operator_commands", {}).get(name)
    if run is None:
        fail("no operator command %s" % name)
    if run["code"] != code:
        fail("--operator %s exited %d, expected %d:\n%s%s" % (name, run["code"], code, run["out"], run["err"]))
    ok("--operator %s exited %d" % (" ".join(run["args"][2:-2]), code))
    return run["out"] + run["err"]


def says(text, words, where):
    if words not in text:
        fail("%s does not say %r:\n%s" % (where, words, text))
    ok("%s says %r" % (where, words))


def truth_of_pocket_2(result):
    truth = result["rack_truth"]["truth"]
    x, y = truth["bores"][1]
    return [x, y, truth["top_z"] + ABOVE_TOP]


def within(found, truth, what):
    errors = [f - t for f, t in zip(found, truth)]
    if max(abs(e) for e in errors) > TOLERANCE:
        fail("%s at %s, the simulated truth %s: off by %s (tolerance %.2f)" % (what, found, truth, errors, TOLERANCE))
    ok("%s at X%.4f Y%.4f Z%.4f, the truth X%.4f Y%.4f Z%.4f: %+.4f %+.4f %+.4f" %
       tuple([what] + found + truth + errors))


def unchanged(files, before, after):
    if files[after]["config"] != files[before]["config"]:
        fail("config.json changed between %s and %s" % (before, after))
    ok("config.json unchanged between %s and %s" % (before, after))


def pocket(config, number):
    p = dict(config.get("pocket_default", {}))
    p.update(config["pockets"][str(number)])
    return [p["x"], p["y"], p["z"]]


def touch_teach(result):
    files = result["files"]
    out = command(result, "touch", 0)
    says(out, "found: pocket 2", "the prompt")
    says(out, "taught ", "the component")
    after = config_of(files, "after")
    within(pocket(after, 2), truth_of_pocket_2(result), "pocket 2 taught by touch")
    before = config_of(files, "before")
    for n in before["pockets"]:
        if n != "2" and before["pockets"][n] != after["pockets"][n]:
            fail("pocket %s changed: %s -> %s" % (n, before["pockets"][n], after["pockets"][n]))
    ok("every other pocket as it was")
    if files["after"]["bak"] != files["before"]["config"]:
        fail("config.json.bak is not the config before the teach")
    ok("the previous config.json kept as config.json.bak")


def touch_datum(result):
    files = result["files"]
    command(result, "teach", 0)
    datum = config_of(files, "taught")["rack_touch"]["datum"]
    found = [datum["x"], datum["y"], datum["z"]]
    previous = load(sys.argv[1], "touch_teach")
    within(found, truth_of_pocket_2(previous), "the rack datum (pocket 2) taught")
    says(command(result, "check", 0), "within", "the drift check")
    unchanged(files, "taught", "checked")


def touch_drift(result):
    files = result["files"]
    out = command(result, "check", FAILED)
    says(out, "the rack datum is 0.50 mm off in X (tolerance 0.10): re-teach or check the rack",
         "the drift check")
    unchanged(files, "before", "checked")
    state = json.loads(files["checked"]["state"])
    says(state.get("datum", {}).get("drift", ""), "0.50 mm off in X", "the state file")
    says("\n".join(result["messages"]), "M6 is refused until", "LinuxCNC's messages after M6 T3")
    unchanged(files, "before", "refused")
    command(result, "clear", 0)
    cleared = json.loads(files["cleared"]["state"])
    if cleared.get("datum", {}).get("drift"):
        fail("the drift is still in the state file after clear-datum-drift: %s" % cleared["datum"])
    ok("clear-datum-drift: no drift left in the state file; pockets unchanged")
    unchanged(files, "before", "cleared")


def touch_nothing(result):
    files = result["files"]
    out = command(result, "touch", FAILED)
    says(out, "pocket 2, top face: no touch within", "the touch that found nothing")
    says(out, "travelled", "the touch that found nothing")
    unchanged(files, "before", "after")
    z = files["after"]["pos"][2]
    top = pocket(config_of(files, "after"), 2)[2]
    if z <= top:
        fail("the spindle stayed at Z %.3f, not above pocket 2's Z %.3f" % (z, top))
    ok("backed out: the spindle at Z %.3f, above pocket 2's %.3f" % (z, top))


def stopped_midway(result):
    unchanged(result["files"], "before", "after")


def touch_killed(result):
    files = result["files"]
    state = json.loads(files["faulted"]["state"])
    progress = state.get("in_progress") or {}
    says(progress.get("sequence", ""), "by touch", "the state file after the kill")
    unchanged(files, "before", "faulted")
    unchanged(files, "before", "after")


CHECKS = {"touch_teach": touch_teach, "touch_datum": touch_datum, "touch_drift": touch_drift,
          "touch_nothing": touch_nothing, "touch_abort": stopped_midway,
          "touch_estop": stopped_midway, "touch_killed": touch_killed}

if __name__ == "__main__":
    results, name = sys.argv[1], sys.argv[2]
    CHECKS[name](load(results, name))
    print("PASS: " + name)
