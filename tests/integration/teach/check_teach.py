#!/usr/bin/env python3
"""Checks one scenario of the teach run (integration_teach_run) against what
LinuxCNC reported and what the component wrote: config.json and its backup
as the driver read them before and after each teach, the messages, the
sampled positions of the M6 that followed, and `fixed_atc_probe --check` on
the taught files.
   check_teach.py RESULTS.json CONFIG.json BINARY SCENARIO
CONFIG.json is the config the run started from (its copy in the run folder is
the one taught)."""
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
from check import (Rack, chuck_only_at_pockets, fail, handshake_complete, no_fault, ok, said,  # noqa: E402
                   scenario, spindle_holds, visits_in_order)

# mm: teaching rounds to 4 decimals, and reads the actual position a moment
# after the driver did (which may catch the last micrometres of the move).
ROUNDING = 5e-3
# Farther than this from the old pocket 3's waypoints: the M6 did not go there.
AWAY = 1.0


def files(r, when):
    if when not in r.get("files", {}):
        fail("the driver never read the files %s the teach (%s)" % (when, r["messages"]))
    return r["files"][when]


def point(entry, default=None):
    merged = {**(default or {}), **entry}
    return [merged["x"], merged["y"], merged["z"]]


def taught_at(config_text, where, target):
    """`where` (the machine position the driver read) went into config.json at
    `target` (a path of keys), rounded; every other key kept its value."""
    config = json.loads(config_text)
    entry = config
    for key in target:
        entry = entry[key]
    got = point(entry)
    if any(abs(g - w) > ROUNDING for g, w in zip(got, where)):
        fail("config.json has %s at %s, the machine was at %s" % (".".join(target), got, where))
    ok("config.json has %s at %s: where the machine was (G53)" % (".".join(target), got))
    return config


def same_except(before, after, target):
    """Every key but `target` keeps its value (the layout may change)."""
    before, after = json.loads(before), json.loads(after)
    for tree in (before, after):
        parent = tree
        for key in target[:-1]:
            parent = parent[key]
        parent.pop(target[-1])
    if before != after:
        fail("teaching %s changed other keys of config.json" % ".".join(target))
    ok("every other key of config.json kept its value")


def backup_is(r, text, what):
    bak = files(r, "after")["bak"]
    if bak != text:
        fail("config.json.bak is not %s byte for byte (%s bytes, expected %s)" % (
            what, None if bak is None else len(bak), len(text)))
    ok("config.json.bak is %s byte for byte" % what)


def unchanged(r, what):
    before, after = files(r, "before"), files(r, "after")
    for key, name in (("config", "config.json"), ("bak", "config.json.bak")):
        if before[key] != after[key]:
            fail("%s changed %s" % (name, what))
    ok("config.json and config.json.bak unchanged byte for byte %s" % what)


def passes_check(binary, run, text, what):
    """fixed_atc_probe --check with the run's INI (soft limits) and state file."""
    with tempfile.NamedTemporaryFile("w", suffix=".json", dir=run, delete=False) as f:
        f.write(text)
    try:
        done = subprocess.run([binary, "--check", "--config", f.name, "--ini",
                               os.path.join(run, "sim.ini"), "--state",
                               os.path.join(run, "fixed_atc_state.json")],
                              capture_output=True, text=True, timeout=120)
    finally:
        os.unlink(f.name)
    if done.returncode != 0:
        fail("fixed_atc_probe --check refuses %s (exit %d): %s" % (
            what, done.returncode, (done.stdout + done.stderr).strip()))
    ok("fixed_atc_probe --check passes %s" % what)


def check_teach_pocket(results, r, original, binary, run):
    no_fault(r)
    said(r, "taught pocket 3")
    before, after = files(r, "before"), files(r, "after")
    if before["config"] != original:
        fail("the run's config.json was not the sample config before the teach")
    if after["config"] == before["config"]:
        fail("config.json did not change")
    where = [round(v, 4) for v in before["pos"]]
    taught_at(after["config"], where, ["pockets", "3"])
    old = point(json.loads(original)["pockets"]["3"], json.loads(original)["pocket_default"])
    if math.dist(old, where) < 1.0:
        fail("the taught position %s is the old one %s: nothing learned" % (where, old))
    same_except(before["config"], after["config"], ["pockets", "3"])
    backup_is(r, original, "the config before the teach")
    passes_check(binary, run, after["config"], "the taught config")


def check_teach_used(results, r, original, binary, run):
    no_fault(r)
    new = Rack(json.loads(files(scenario(results, "teach_pocket"), "after")["config"]))
    old = Rack(json.loads(original))
    visits_in_order(r["samples"], new.retrieve_waypoints(3))
    ok("M6 T3 fetched tool 3 from the taught pocket 3 at %s, without a restart" % new.pocket(3))
    for name, target in (("pocket 3", old.pocket(3)), ("side of pocket 3", old.side(3)),
                         ("above-chuck 3", old.above(3, "pocket_above_chuck_offset_z"))):
        closest = min(r["samples"], key=lambda s: math.dist(s["pos"], target))
        if math.dist(closest["pos"], target) < AWAY:
            fail("the machine went to the old %s %s (at t=%.3f: %s)" % (
                name, target, closest["t"], closest["pos"]))
        ok("never near the old %s %s (closest %.2f mm)" % (name, target,
                                                          math.dist(closest["pos"], target)))
    chuck_only_at_pockets(r["samples"], new)
    spindle_holds(r, 3, "after T3 M6")
    handshake_complete(r)


def check_teach_refused(results, r, original, binary, run):
    no_fault(r)
    said(r, "teach pocket 3 at X195 Y20 Z-80: not written: ")
    message = next(m for m in r["messages"] if "not written" in m)
    if "pocket 4" not in message and "pockets.4" not in message:
        fail("the refusal does not name pocket 4, whose keep-out it is in: %s" % message)
    ok("the refusal names pocket 4: %s" % message)
    unchanged(r, "by the refused teach")


def check_teach_busy(results, r, original, binary, run):
    no_fault(r)
    said(r, "teach safe refused: only while the changer is idle")
    unchanged(r, "by a teach while the changer waited for the operator")
    spindle_holds(r, 3, "after the unload was cancelled")
    ok("the unload was cancelled: tool 3 stays in the spindle")


def check_teach_loading(results, r, original, binary, run):
    no_fault(r)
    said(r, "taught loading")
    before, after = files(r, "before"), files(r, "after")
    where = [round(v, 4) for v in before["pos"]]
    config = taught_at(after["config"], where, ["loading"])
    if point(json.loads(before["config"])["loading"]) == point(config["loading"]):
        fail("loading did not change")
    ok("loading went from %s to %s" % (point(json.loads(before["config"])["loading"]),
                                       point(config["loading"])))
    same_except(before["config"], after["config"], ["loading"])
    backup_is(r, before["config"], "the config before this teach")
    with open(os.path.join(run, "config.json"), newline="") as f:
        final = f.read()
    if final != after["config"]:
        fail("config.json changed after the last teach")
    passes_check(binary, run, final, "the run's config.json after both teaches")


def main():
    results_path, config_path, binary, name = sys.argv[1:5]
    results = json.load(open(results_path))
    with open(config_path, newline="") as f:
        original = f.read()
    r = scenario(results, name)
    globals()["check_" + name](results, r, original, binary, os.path.dirname(results_path))
    print("%s: %.1f s, %d samples" % (name, r["duration"], len(r["samples"])))


if __name__ == "__main__":
    main()
