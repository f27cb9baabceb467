#!/usr/bin/env python3
"""Turns the simulated mill's INI (as run_sim.sh copied it) into a machine
that changes tools with LinuxCNC's own rack-toolchange remap example, on the
rack of the config beside the INI: the peer of scripts/bench_changes.sh.
   peer_ini.py SIM_INI

The example is used where linuxcnc-uspace installed it, never copied. Its
rack is a row of pockets along Y: [CHANGE_POSITION] is pocket 0, each next
pocket [TOOL_SLOT_DELTA]Y further; so the config's pockets must lie along Y
at one spacing, and they are top pockets (the example goes straight down
into a pocket and straight up out of it). Its clear position is our safe.
Its dwells are our chuck_seconds. Its lock and flush are motion outputs
0 and 1, wired to nothing."""
import json
import os
import re
import sys

EXAMPLE = "/usr/share/doc/linuxcnc/examples/sample-configs/sim/axis/remap/rack-toolchange"
STDGLUE = "/usr/share/linuxcnc/ncfiles/remap_lib"


def fail(why):
    sys.exit("peer_ini.py: " + why)


def rack(config):
    """([CHANGE_POSITION] x, y, z, [TOOL_SLOT_DELTA] y) of the config's pockets."""
    default = config.get("pocket_default", {})
    pockets = {int(n): dict(default, **p) for n, p in config["pockets"].items()}
    if any(p.get("approach") != "top" for p in pockets.values()):
        fail("the example's rack has top pockets only; give every pocket \"approach\": \"top\"")
    numbers = sorted(pockets)
    if len(numbers) < 2:
        fail("the example's row needs two pockets at least, to know their spacing")
    delta = pockets[numbers[1]]["y"] - pockets[numbers[0]]["y"]
    first = pockets[numbers[0]]
    for n in numbers:
        p = pockets[n]
        off = [p["x"] - first["x"], p["z"] - first["z"], p["y"] - first["y"] - (n - numbers[0]) * delta]
        if any(abs(v) > 1e-6 for v in off):
            fail("pocket %d is not on the example's row (one X and Z, Y every %g)" % (n, delta))
    return first["x"], first["y"] - numbers[0] * delta, first["z"], delta


def main():
    ini_path = sys.argv[1]
    ini = open(ini_path).read()
    folder = os.path.dirname(os.path.abspath(ini_path))
    config = json.load(open(os.path.join(folder, "config.json")))
    x, y, z, delta = rack(config)
    safe, dwell = config["safe"], config["chuck_seconds"]
    ini = re.sub(r"^SUBROUTINE_PATH = .*$", "SUBROUTINE_PATH = %s/nc_subroutines:%s/common_nc_subs"
                 % (EXAMPLE, STDGLUE), ini, flags=re.M)
    # The example's abort handler instead of ours (LinuxCNC takes one).
    ini = re.sub(r"^ON_ABORT_COMMAND = .*fixed_atc_probe.*\n", "", ini, flags=re.M)
    ini = re.sub(r"^REMAP = M6 .*$", "REMAP = M6 modalgroup=6 prolog=change_prolog ngc=rack_change "
                 "epilog=change_epilog\nON_ABORT_COMMAND = O <on_abort> call", ini, flags=re.M)
    # Our component, its panel, its wiring, touch-off sensor and simulated rack out: basic_sim.tcl's own loops
    # answer tool-prepare and tool-change at once.
    ini = re.sub(r"^(POSTGUI_)?HALFILE = .*(fixed_atc_probe|touchoff_sensor|sim_rack|spindle_sim).*\.hal\n", "", ini, flags=re.M)
    ini = re.sub(r"^GLADEVCP = .*\n", "", ini, flags=re.M)
    ini += """
[PYTHON]
PATH_PREPEND = {example}/python
PATH_APPEND = {stdglue}/python-stdglue
TOPLEVEL = {example}/python/toplevel.py

[CHANGE_POSITION]
X = {x}
Y = {y}
Z = {z}

[TOOL_SLOT_DELTA]
X = 0
Y = {delta}
Z = 0

[TOOL_HOLDER_CLEAR]
X = {sx}
Y = {sy}
Z = {sz}

[DWELL]
LOCK_TIME = {dwell}
MYSTERY = 0
NEW_TOOL = {dwell}
POST_UNLOCK = {dwell}

[PINS]
LOCK = 0
FLUSH = 1
""".format(example=EXAMPLE, stdglue=STDGLUE, x=x, y=y, z=z, delta=delta,
           sx=safe["x"], sy=safe["y"], sz=safe["z"], dwell=dwell)
    open(ini_path, "w").write(ini)


if __name__ == "__main__":
    main()
