#!/usr/bin/python3
"""A stand-in for a piece of hardware a hal/wiring snippet nets to: a
userspace HAL component with the real driver's pin names, as
stand_ins.json lists them (the only place they are written).

Its output pins take the values the test writes into DRIVE (a JSON object
of full pin names), as the card's inputs or the drive's feedback would; an
input-NN-not follows its input-NN inverted, as hostmot2's does.
    stand_in.py STAND_INS.json KEY NAME DRIVE

With --snippet it writes a copy of SNIPPET to OUT, line for line, each
loadusr of a driver stand_ins.json replaces made a loadusr of its stand-in
(named as the line's -Wn names it), the loads of the machine's own
stand-ins ("before") to OUT.before, and prints the names of all the
stand-ins, comma-separated:
    stand_in.py --snippet STAND_INS.json SNIPPET OUT DRIVE"""
import json
import os
import re
import signal
import sys
import time

import hal

TYPES = {"bit": hal.HAL_BIT, "float": hal.HAL_FLOAT, "s32": hal.HAL_S32, "u32": hal.HAL_U32}
DIRECTIONS = {"in": hal.HAL_IN, "out": hal.HAL_OUT}
running = True


def stop(*_):
    global running
    running = False


def expand(pattern):
    """7i76.0.0.input-{00..31}: one name a number, with the digits written."""
    m = re.search(r"\{(\d+)\.\.(\d+)\}", pattern)
    if not m:
        return [pattern]
    width = len(m.group(1))
    return [pattern[:m.start()] + str(n).zfill(width) + pattern[m.end():]
            for n in range(int(m.group(1)), int(m.group(2)) + 1)]


def pins_of(entry):
    return [(name, kind, direction) for kind, direction, pattern in entry["pins"]
            for name in expand(pattern)]


def load_line(stand_ins, key, name, drive):
    return "loadusr -Wn %s /usr/bin/python3 %s %s %s %s %s\n" % (
        name, os.path.abspath(__file__), stand_ins, key, name, drive)


def replace_loads(stand_ins, snippet, out, drive):
    """OUT: SNIPPET with the drivers' loadusr lines made the stand-ins',
    line for line, so halcmd's line numbers are the snippet's; OUT.before:
    the loads of the machine's own stand-ins. Prints every stand-in's name."""
    entries = json.load(open(stand_ins))
    entries.pop("about")
    before = [(k, e["component"]) for k, e in entries.items() if e.get("before")]
    with open(out + ".before", "w") as f:
        f.writelines(load_line(stand_ins, k, name, drive) for k, name in before)
    names = [name for _, name in before]
    lines = []
    for line in open(snippet):
        for key, entry in entries.items():
            if "replaces" in entry and re.match(entry["replaces"], line):
                m = re.search(r"-Wn\s+(\S+)", line)
                name = m.group(1) if m else entry["component"]
                names.append(name)
                line = load_line(stand_ins, key, name, drive)
        lines.append(line)
    with open(out, "w") as f:
        f.writelines(lines)
    print(",".join(names))


def main():
    if sys.argv[1] == "--snippet":
        replace_loads(*sys.argv[2:6])
        return
    signal.signal(signal.SIGTERM, stop)
    signal.signal(signal.SIGINT, stop)
    stand_ins, key, name, drive = sys.argv[1:5]
    entry = json.load(open(stand_ins))[key]
    c = hal.component(name)
    outputs = []
    for pin, kind, direction in pins_of(entry):
        c.newpin(pin, TYPES[kind], DIRECTIONS[direction])
        if direction == "out":
            outputs.append(pin)
            if pin.endswith("-not"):
                c[pin] = True
    c.ready()
    seen = None
    while running:
        try:
            stamp = os.stat(drive).st_mtime_ns
        except FileNotFoundError:
            stamp = None
        if stamp is not None and stamp != seen:
            seen = stamp
            values = json.load(open(drive))
            for pin in outputs:
                full = name + "." + pin
                if full in values:
                    c[pin] = values[full]
                elif full.endswith("-not") and full[:-4] in values:
                    c[pin] = not values[full[:-4]]
        time.sleep(0.005)


if __name__ == "__main__":
    main()
