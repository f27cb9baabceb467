#!/usr/bin/env python3
"""Checks the GUI test's results: the panel's HAL outputs and its buttons'
enabled state at each stage of an unload and a load flow clicked in AXIS,
the measured length in LinuxCNC's tool table, and the screenshots.
   check_gui.py RESULTS.json"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "integration"))
from check import fail, measured_to_truth, ok  # noqa: E402

CONFIG = os.path.join(os.path.dirname(__file__), "..", "..", "config", "config.json")

ENABLED = ("load-enabled", "unload-enabled", "continue-enabled", "cancel-enabled")


def stage(r, what):
    found = [s for s in r["steps"] if s["what"] == what]
    if not found:
        fail("the run never reached '%s'" % what)
    return found[0]


def expect_enabled(r, what, **wanted):
    s = stage(r, what)
    got = {name: s["fatc-panel." + name] for name in ENABLED}
    expected = {name: wanted.get(name.replace("-", "_"), False) for name in ENABLED}
    if got != expected:
        fail("at '%s' the panel's pins say %s, expected %s" % (what, got, expected))
    ok("at '%s': enabled %s" % (what, [n for n in ENABLED if got[n]] or "nothing"))


def main():
    r = json.load(open(sys.argv[1]))
    if r["error"]:
        fail("the GUI run failed: %s (messages: %s)" % (r["error"], r["messages"][-3:]))
    expect_enabled(r, "idle, tool number 0")
    expect_enabled(r, "unloaded", load_enabled=True, unload_enabled=True)
    expect_enabled(r, "removal prompt", continue_enabled=True, cancel_enabled=True)
    expect_enabled(r, "insert prompt", continue_enabled=True, cancel_enabled=True)
    expect_enabled(r, "jog prompt", continue_enabled=True, cancel_enabled=True)
    expect_enabled(r, "probing", cancel_enabled=True)
    expect_enabled(r, "loaded", load_enabled=True, unload_enabled=True)
    for key, wanted in (("idle_tool0_sensitive", {"Load / Probe": False, "Unload": False, "Continue": False, "Cancel": False}),
                        ("waiting_sensitive", {"Load / Probe": False, "Unload": False, "Continue": True, "Cancel": True}),
                        ("probing_sensitive", {"Load / Probe": False, "Unload": False, "Continue": False, "Cancel": True})):
        if r[key] != wanted:
            fail("the buttons' sensitivity (%s) is %s, expected %s" % (key, r[key], wanted))
    ok("the buttons on screen are enabled exactly as the panel's pins say")
    clicks = [s["what"] for s in r["steps"] if s["what"].startswith("clicked")]
    ok("clicked in AXIS: %s" % ", ".join(c[8:] for c in clicks))

    measured_to_truth(r, json.load(open(CONFIG)), 4, "measured through the panel")
    state = r["state_file"]
    if 4 not in state["in_pocket"] or state["spindle"] != 0:
        fail("after the load, tool 4 should be in its pocket and the spindle empty: %s" % state)
    ok("tool 4 back in its pocket, the spindle empty")

    for shot in r["screenshots"]:
        for path in (shot["file"], shot["panel_file"]):
            with open(path, "rb") as f:
                head = f.read(8)
            if head != b"\x89PNG\r\n\x1a\n" or os.path.getsize(path) < 2000:
                fail("%s is not a screenshot" % path)
        ok("screenshot %s (panel at %s)" % (shot["file"], shot["panel"]))
    if len(r["screenshots"]) != 2:
        fail("expected two screenshots, got %d" % len(r["screenshots"]))


if __name__ == "__main__":
    main()
