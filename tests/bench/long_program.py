#!/usr/bin/env python3
"""The inputs of the preflight benchmark (scripts/bench_lint.sh): a rack of
POCKETS top pockets in rows, its tool table, and a program of CHANGES tool
changes, each followed by a few cuts over the work (never over the rack).

    tests/bench/long_program.py FOLDER [CHANGES [POCKETS]]

writes FOLDER/config.json, FOLDER/tools.tbl, FOLDER/program.ngc and
FOLDER/machine.ini: the simulated mill's INI (config/sim/fixed_atc_sim.ini)
with the M6 remap and the project's nc_files, its limits wide enough for the
rack."""
import json
import os
import sys

folder = sys.argv[1]
changes = int(sys.argv[2]) if len(sys.argv) > 2 else 10000
pockets = int(sys.argv[3]) if len(sys.argv) > 3 else 200
per_row = 20
pitch = 60.0  # room for each pocket's keep-out column between its neighbours

root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
# The sample config, its pockets top pockets in rows of 20 beside the work.
rack = json.load(open(os.path.join(root, "config", "config.json")))
rack.update(loading={"x": -100.0, "y": -100.0, "z": -10.0},
            probe_limit={"x": -100.0, "y": -100.0, "z": -90.0},
            safe={"x": -100.0, "y": 0.0, "z": -5.0},
            pocket_default={"z": -80.0, "approach": "top"},
            pockets={str(n): {"x": 100.0 + pitch * ((n - 1) % per_row),
                              "y": 100.0 + pitch * ((n - 1) // per_row), "tool": n}
                     for n in range(1, pockets + 1)})
os.makedirs(folder, exist_ok=True)
with open(os.path.join(folder, "config.json"), "w") as f:
    json.dump(rack, f, indent=1)
with open(os.path.join(folder, "tools.tbl"), "w") as f:
    for n in range(1, pockets + 1):
        f.write(f"T{n} P{n} Z{20 + n % 30}.0 D{2 + n % 10}.0 ;tool {n}\n")
nc_files = os.path.join(root, "nc_files")
with open(os.path.join(folder, "machine.ini"), "w") as f:
    f.write(f"""[RS274NGC]
PARAMETER_FILE = sim.var
SUBROUTINE_PATH = {nc_files}
REMAP = M6 modalgroup=6 ngc=fixed_atc_probe_m6
HAL_PIN_VARS = 1
INI_VARS = 1

[FIXED_ATC_PROBE]
STATE = fixed_atc_state.json

[EMCIO]
CYCLE_TIME = 0.010
TOOL_TABLE = tools.tbl

[TRAJ]
COORDINATES = X Y Z
LINEAR_UNITS = mm
ANGULAR_UNITS = degree
MAX_LINEAR_VELOCITY = 200
MAX_LINEAR_ACCELERATION = 2000
""")
    for axis, low, high in (("X", -400, 1400), ("Y", -300, 800), ("Z", -120, 0)):
        f.write(f"\n[AXIS_{axis}]\nMAX_VELOCITY = 200\nMAX_ACCELERATION = 2000\n"
                f"MIN_LIMIT = {low}\nMAX_LIMIT = {high}\n")
with open(os.path.join(folder, "program.ngc"), "w") as f:
    f.write(f"(a long job: {changes} changes over a rack of {pockets} pockets)\nG21 G90 G17\n")
    for i in range(changes):
        tool = (i * 37) % pockets + 1  # every tool in turn, never the same twice in a row
        x = -300.0 - (i % 50) * 2.0
        f.write(f"T{tool} M6\nG43 H{tool}\nS8000 M3\nG0 X{x:.1f} Y-200.0\nG0 Z-20.0\n"
                f"G1 Z-30.0 F300\nG1 X{x - 40.0:.1f} Y-240.0 F1200\nG0 Z-5.0\nM5\n")
    f.write("M2\n")
