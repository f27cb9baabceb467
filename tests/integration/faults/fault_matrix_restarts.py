#!/usr/bin/env python3
"""The restart column of the fault matrix: LinuxCNC itself stopped in the
middle of a change, at each step, and started again on the same files.

    fault_matrix_restarts.py WORKDIR RESULTS.json

Each LinuxCNC start (run_sim.sh with fault_matrix.py as its display, files
kept) checks and confirms what the last start left, then cuts the next case's
change at its step and leaves, which stops LinuxCNC under it. One start more
than there are cases."""
import json
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
work, out = sys.argv[1], sys.argv[2]
steps = os.environ.get("FATC_MATRIX_STEPS")
results = {"cases": [], "error": None, "starts": 0}
pending = None
if os.path.exists(work):
    # A fresh machine for the first start; the later ones keep its files.
    subprocess.run(["rm", "-rf", work], check=True)
while True:
    env = dict(os.environ, FATC_KEEP_STATE="1", FATC_MATRIX_MODE="restart",
               FATC_RESULTS=os.path.join(work, "start.json"),
               FATC_MATRIX_PENDING=json.dumps(pending) if pending else "")
    if steps is not None:
        env["FATC_MATRIX_STEPS"] = steps
    run = subprocess.run([os.path.join(here, "..", "harness", "run_sim.sh"), work, os.path.join(here, "fault_matrix.py")],
                         env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                         timeout=600)
    results["starts"] += 1
    try:
        start = json.load(open(env["FATC_RESULTS"]))
    except (OSError, ValueError) as e:
        results["error"] = "start %d wrote no results (%s): %s" % (results["starts"], e, run.stdout[-3000:])
        break
    results.setdefault("plan", start.get("plan"))
    results["cases"] += start["cases"]
    if start["error"]:
        results["error"] = "start %d: %s" % (results["starts"], start["error"])
        break
    pending = start.get("next")
    if pending is None:
        break
    steps = ",".join(str(n) for n in start["left"]) or "none"
json.dump(results, open(out, "w"))
