#!/usr/bin/python3
"""Holds what the rehearsal printed (scripts/rehearse.py) against what happened:
the soak's events file (every change, check, fault), the picture, and the
simulated copy's INI against the user's (LinuxCNC's reader on both).

    rehearse_check.py USER_INI REHEARSAL_DIR PRINTED CHANGES"""
import collections
import json
import os
import re
import subprocess
import sys

import linuxcnc

user_ini, work, printed, wanted = sys.argv[1], sys.argv[2], open(sys.argv[3]).read(), int(sys.argv[4])
soak = os.path.join(work, "soak")
events = [json.loads(line) for line in open(os.path.join(soak, "soak_events.jsonl"))]
bad = []


def expect(what, got, want):
    print("%s: %s (expected %s)" % (what, got, want))
    if got != want:
        bad.append(what)


held = re.search(r"(\d+) changes made of (\d+) asked; the changer's belief held against the "
                 r"simulated rack (\d+) times, (\d+) mismatches", printed)
faulted = re.search(r"^faulted: (.*); (\d+) recoveries", printed, re.M)
slow = re.search(r"^slowest change: ([0-9.]+) s, T(\d+) to T(\d+) \(change (\d+)\)", printed, re.M)
if not (held and faulted and slow):
    sys.exit("FAIL: the report's lines are missing: %s" % [held, faulted, slow])

changes = [e for e in events if e["kind"] == "change"]
mismatches = [e for e in events if e["kind"] == "mismatch"]
checks = len([e for e in events if e["kind"] in ("agree", "mismatch") or e.get("checked")])
expect("changes made", int(held.group(1)), wanted)
expect("changes in the events file", len(changes), wanted)
expect("changes asked", int(held.group(2)), wanted)
expect("mismatches", int(held.group(4)), 0)
expect("mismatches in the events file", len(mismatches), 0)
expect("checks that held", int(held.group(3)), checks - len(mismatches))
kinds = collections.Counter(e["fault"] for e in events if e["kind"] == "fault")
said = {} if faulted.group(1) == "nothing" else \
    dict((k, int(n)) for k, n in (w.rsplit(" ", 1) for w in faulted.group(1).split(", ")))
expect("faults by kind", said, dict(kinds))
timed = [e for e in changes if e["clean"] and e["seconds"] and not e.get("manual")]
slowest = max(timed, key=lambda e: e["seconds"])
expect("slowest change", (slow.group(1), int(slow.group(2)), int(slow.group(3)), int(slow.group(4))),
       ("%.2f" % slowest["seconds"], slowest["frm"], slowest["to"], slowest["changes"]))
svg = subprocess.run([sys.executable, os.path.join(os.path.dirname(__file__), "..", "..", "..", "scripts",
                                                  "check_svg.py"), os.path.join(soak, "soak.svg"),
                      "Soak: %d tool changes" % wanted], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                     text=True)
expect("the picture (scripts/check_svg.py, its title)", svg.returncode, 0)

# The copy is the user's machine: its units, soft limits, velocities and accelerations.
mine, copy = linuxcnc.ini(user_ini), linuxcnc.ini(os.path.join(soak, "sim.ini"))
expect("units", copy.find("TRAJ", "LINEAR_UNITS"), mine.find("TRAJ", "LINEAR_UNITS"))
differ = []
joints = ["JOINT_%d" % j for j in range(int(mine.find("KINS", "JOINTS")))]
for section in ["AXIS_X", "AXIS_Y", "AXIS_Z"] + joints:
    for key in ("MIN_LIMIT", "MAX_LIMIT", "MAX_VELOCITY", "MAX_ACCELERATION"):
        if copy.find(section, key) != mine.find(section, key):
            differ.append("[%s]%s: the copy %s, the machine %s" % (
                section, key, copy.find(section, key), mine.find(section, key)))
print("the copy's limits, velocities and accelerations: %s" % (differ or "as the machine's"))
bad += differ
for b in bad:
    print("FAIL: " + b)
sys.exit(1 if bad else 0)
