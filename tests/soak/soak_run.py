#!/usr/bin/env python3
"""The soak (issue 36): LinuxCNC started on the simulated mill with the
simulated rack, soak.py as its display, again and again on the same files
(the state file, the tool table, the rack's truth) until the soak has made
its changes; a start ends early where soak.py stopped LinuxCNC as a fault.

    soak_run.py WORKDIR CHANGES [SEED]

Environment as run_sim.sh takes it (FATC_BINARY, FATC_INI_SED,
FATC_CONFIG_SET): the machine of tests/soak/CMakeLists.txt or scripts/soak.sh.
Writes WORKDIR/soak_events.jsonl; soak_report.py turns it into the report."""
import json
import os
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
work, changes = sys.argv[1], int(sys.argv[2])
seed = int(sys.argv[3]) if len(sys.argv) > 3 else 1
if os.path.exists(work):
    subprocess.run(["rm", "-rf", work], check=True)  # a fresh machine for the first start
os.makedirs(work)
# The rack's truth outlives a LinuxCNC start: rack_sim.py keeps it in this file
# once it exists (a fresh rack: every tool in its pocket, the spindle empty).
with open(os.path.join(work, "rack_sim.state"), "w") as f:
    json.dump({"holders": {str(p): p for p in range(1, 7)}, "spindle": 0}, f)
budget = max(1, changes // 300)  # LinuxCNC stopped mid-change this often, at most
began = time.time()
for start in range(1, 2 * budget + 20):
    events = os.path.join(work, "soak_events.jsonl")
    done = 0
    faults = 0
    restarts = budget
    if os.path.exists(events):
        for line in open(events):
            event = json.loads(line)
            done = max(done, event.get("changes", 0))
            faults += event["kind"] == "fault"
            if event["kind"] == "fault" and event.get("fault") == "restart_linuxcnc":
                restarts -= 1
    config = json.loads(os.environ.get("FATC_CONFIG_SET", "{}"))
    plan = {"changes": changes, "changes_done": done, "seed": seed, "start": start,
            "faults_before": faults,
            "restarts_left": max(restarts, 0), "fault_rate": 0.35, "operator_rate": 0.12,
            "seconds_per_change": 2.5, "sensor_timeout": config.get("sensor_timeout_seconds", 1.0),
            "drawbar_seconds": 0.05, "true_length": 25.0,
            "fault_cycle": bool(os.environ.get("FATC_SOAK_CYCLE")),
            "quiet_tail": 300 if changes >= 600 else 0}
    with open(os.path.join(work, "soak_plan.json"), "w") as f:
        json.dump(plan, f)
    env = dict(os.environ, FATC_KEEP_STATE="1")
    run = subprocess.run([os.path.join(here, "..", "integration", "harness", "run_sim.sh"), work,
                          os.path.join(here, "soak.py")],
                         env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                         timeout=7200)
    with open(os.path.join(work, "linuxcnc_starts.log"), "a") as log:
        log.write("==== start %d (exit %d)\n%s\n" % (start, run.returncode, run.stdout[-20000:]))
    if not os.path.exists(events):
        sys.exit("soak_run.py: LinuxCNC's start %d ran no soak; see %s" % (
            start, os.path.join(work, "linuxcnc_starts.log")))
    last = [json.loads(line) for line in open(events)][-3:]
    if any(e["kind"] in ("done", "error") for e in last):
        break
print("soak_run.py: %d starts, %.0f s; events in %s" % (start, time.time() - began, events))
