#!/usr/bin/python3
"""The simulated mill in inches: the same machine, every length and speed
divided by 25.4, for the units run (issue 42: an inch config that leaves the
feeds out moves and measures at the physical speeds of the mm one).

  to_inch.py ini FILE            rewrites a copied sim INI in place (FATC_INI_FILTER)
  to_inch.py config SRC DST      config.json in inches, the keys with a unit default left out
  to_inch.py config-mm SRC DST   the same config in mm, the same keys left out
  to_inch.py table SRC DST       the tool table in inches
"""
import json
import re
import sys

MM = 25.4
# The INI's keys that are lengths, or lengths per second (per second squared).
INI_LENGTHS = {"DEFAULT_LINEAR_VELOCITY", "MAX_LINEAR_VELOCITY", "DEFAULT_LINEAR_ACCELERATION",
               "MAX_LINEAR_ACCELERATION", "MAX_VELOCITY", "MAX_ACCELERATION", "MIN_LIMIT",
               "MAX_LIMIT", "FERROR", "MIN_FERROR", "HOME", "HOME_OFFSET", "HOME_SEARCH_VEL",
               "HOME_LATCH_VEL", "SIM_SENSOR_Z", "SIM_SENSOR_XMIN", "SIM_SENSOR_XMAX",
               "SIM_SENSOR_YMIN", "SIM_SENSOR_YMAX"}
# config.json's keys with a unit whose default the run takes: left out of both configs.
DEFAULTED = ("pocket_feed", "probe_seek_feed", "probe_latch_feed", "probe_backoff", "verify_feed")
# config.json's lengths (a point's x, y, z inside these count too).
CONFIG_LENGTHS = {"probe_length_compensation_offset", "probe_retract_offset_z",
                  "pocket_above_chuck_offset_z", "pocket_above_clearance_offset_z",
                  "probe_window", "probe_check_tolerance", "rack_keepout_margin",
                  "rack_keepout_above", "blend_tolerance"}
POINTS = {"loading", "probe_limit", "safe", "pocket_default", "pocket_side_offset"}


def inch(value):
    return round(value / MM, 6)


def ini(path):
    lines = []
    for line in open(path).read().splitlines():
        m = re.match(r"^(\w+)\s*=\s*(-?[0-9.]+)\s*$", line)
        if m and m.group(1) in INI_LENGTHS:
            line = "%s = %s" % (m.group(1), inch(float(m.group(2))))
        elif line.startswith("LINEAR_UNITS"):
            line = "LINEAR_UNITS = inch"
        elif line.startswith("INCREMENTS"):
            line = "INCREMENTS = .1in, .01in, .001in"
        lines.append(line)
    open(path, "w").write("\n".join(lines) + "\n")


def point(value):
    """A point's, an offset's or a pocket's x, y and z, and those of its own points."""
    return {k: point(v) if isinstance(v, dict) else inch(v) if k in "xyz" else v
            for k, v in value.items()}


def config(src, dst, to_inch):
    c = json.load(open(src))
    for key in DEFAULTED:
        c.pop(key, None)
    if to_inch:
        c["units"] = "inch"
        for key in list(c):
            if key in CONFIG_LENGTHS:
                c[key] = inch(c[key])
            elif key in POINTS:
                c[key] = point(c[key])
        c["pockets"] = {n: point(p) for n, p in c["pockets"].items()}
    json.dump(c, open(dst, "w"), indent=2)


def table(src, dst):
    out = []
    for line in open(src).read().splitlines():
        words = []
        for word in line.split(";")[0].split():
            if word[0] in "XYZD" and len(word) > 1:
                word = word[0] + "%.6f" % inch(float(word[1:]))
            words.append(word)
        out.append(" ".join(words) + (" ;" + line.split(";", 1)[1] if ";" in line else ""))
    open(dst, "w").write("\n".join(out) + "\n")


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) > 1 else ""
    if what == "ini" and len(sys.argv) == 3:
        ini(sys.argv[2])
    elif what in ("config", "config-mm") and len(sys.argv) == 4:
        config(sys.argv[2], sys.argv[3], what == "config")
    elif what == "table" and len(sys.argv) == 4:
        table(sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)
