#!/usr/bin/env python3
"""Judges the headless run (run_headless.sh): every line of the page's session
answered without a NAK, the machine homed, the program ran to its end, and
LinuxCNC and the changer agree that T3 is in the spindle.
   headless_check.py RESULTS.json STATE.json"""
import json
import sys


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def main():
    results = json.load(open(sys.argv[1]))
    if results["error"]:
        fail("the session stopped: %s (after %s)" % (results["error"], results["exchanges"][-3:]))
    for command, answer in results["exchanges"]:
        if answer is not None and "NAK" in answer.upper():
            fail("linuxcncrsh refused %r: %s" % (command, answer))
    print("ok: linuxcncrsh took each of the page's %d lines" % len(results["session"]))
    answers = {command: answer for command, answer in results["exchanges"]}
    homed = answers.get("get joint_homed", "").upper().split()[1:4]
    if homed != ["YES"] * 3:
        fail("the machine's three joints were not homed: %s" % answers.get("get joint_homed"))
    if not results.get("program_ran") or "IDLE" not in answers.get("get program_status", "").upper():
        fail("the program did not run to its end: %s" % answers.get("get program_status"))
    print("ok: homed (%s), the program ran and ended (%s)" % (
        answers["get joint_homed"], answers["get program_status"]))
    if answers.get("get tool", "").split()[-1:] != ["3"]:
        fail("linuxcncrsh says %r, expected tool 3 in the spindle" % answers.get("get tool"))
    state = json.load(open(sys.argv[2]))
    if state.get("spindle") != 3:
        fail("the changer's state file says the spindle holds %r, expected 3" % state.get("spindle"))
    print("ok: LinuxCNC (%s) and the changer's state file agree: T3 in the spindle" % answers["get tool"])


if __name__ == "__main__":
    main()
