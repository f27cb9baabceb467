#!/usr/bin/env python3
"""The soak (issue 36): LinuxCNC started on the simulated mill with the
simulated rack, soak.py as its display, again and again on the same files
(the state file, the tool table, the rack's truth) until the soak has made
its changes; a start ends early where soak.py stopped LinuxCNC as a fault.

    soak_run.py WORKDIR CHANGES [SEED]

Environment as run_sim.sh takes it (FATC_BINARY, FATC_INI_SED,
FATC_CONFIG_SET, FATC_CONFIG, FATC_TOOL_TABLE, FATC_SIM_INI): the machine of
tests/soak/CMakeLists.txt or scripts/soak.sh, or a user's own (scripts/rehearse.py).
The rack is the config's pockets with the tools they hold at the first start
(`"tool"`, default the pocket's number), the manual tools the table's others;
FATC_SOAK_OPERATOR_RATE: how often the operator's flows come between programs
(0.12); FATC_SOAK_TRUE_LENGTH: the length every tool measures on the simulated setter
(25 on config/sim's), FATC_SOAK_LENGTH_TOLERANCE how far a measured one may
be from it (0.01). Writes WORKDIR/soak_events.jsonl; soak_report.py turns
it into the report."""
import json
import os
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "integration", "harness"))
import tool_table  # noqa: E402  (a tool table file's lines)

work, changes = sys.argv[1], int(sys.argv[2])
seed = int(sys.argv[3]) if len(sys.argv) > 3 else 1
if os.path.exists(work):
    subprocess.run(["rm", "-rf", work], check=True)  # a fresh machine for the first start
os.makedirs(work)
root = os.path.join(here, "..", "..")
config = json.load(open(os.environ.get("FATC_CONFIG") or os.path.join(root, "config", "config.json")))
config.update(json.loads(os.environ.get("FATC_CONFIG_SET") or "{}"))
rack = {int(p): int(own.get("tool", p)) for p, own in config["pockets"].items()}
table = os.environ.get("FATC_TOOL_TABLE") or os.path.join(root, "config", "sim", "sim.tbl")
manual = sorted(t for t in tool_table.file_lines(open(table).read())
                if t > 0 and t not in rack.values())
# The rack's truth outlives a LinuxCNC start: rack_sim.py keeps it in this file
# once it exists (a fresh rack: every tool in its pocket, the spindle empty).
with open(os.path.join(work, "rack_sim.state"), "w") as f:
    json.dump({"holders": {str(p): t for p, t in rack.items()}, "spindle": 0}, f)
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
    plan = {"changes": changes, "changes_done": done, "seed": seed, "start": start,
            "faults_before": faults,
            "restarts_left": max(restarts, 0), "fault_rate": 0.35,
            "operator_rate": float(os.environ.get("FATC_SOAK_OPERATOR_RATE") or 0.12),
            "seconds_per_change": 2.5, "sensor_timeout": config.get("sensor_timeout_seconds", 1.0),
            "drawbar_seconds": 0.05,
            "true_length": float(os.environ.get("FATC_SOAK_TRUE_LENGTH") or 25.0),
            "length_tolerance": float(os.environ.get("FATC_SOAK_LENGTH_TOLERANCE") or 0.01),
            "rack": {str(p): t for p, t in rack.items()}, "manual_tools": manual,
            "fault_cycle": bool(os.environ.get("FATC_SOAK_CYCLE")),
            "collet_nut": config.get("chuck", {}).get("kind") == "collet_nut",
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
