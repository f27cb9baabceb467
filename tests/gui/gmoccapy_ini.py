#!/usr/bin/env python3
"""Turns the simulated mill's INI (as run_sim.sh copied it) into the same
machine shown in gmoccapy with fixed_atc_probe's panel embedded: the
[DISPLAY] section is replaced, everything else stays as the sim has it.
   gmoccapy_ini.py SIM_INI

The panel's command comes from the AXIS line, [DISPLAY]GLADEVCP (its
component name, handler and .ui), the panel's HAL file from
[HAL]POSTGUI_HALFILE. gmoccapy starts an embedded panel as a child and runs
the POSTGUI_HALFILE right after its own window is built, without waiting for
the child: the panel's pins may not exist yet. So the HAL file moves onto
the panel's command line (gladevcp -H runs it once the pins exist) and out of
POSTGUI_HALFILE. Also writes gmoccapy's preference file beside the INI
(docs/gmoccapy.md says why each setting)."""
import os
import re
import shlex
import sys

PANEL_HAL = "fixed_atc_probe_panel.hal"
# The machine's [DISPLAY] keys both GUIs read the same way; the rest is AXIS's.
KEEP = ("POSITION_OFFSET", "POSITION_FEEDBACK", "MAX_FEED_OVERRIDE", "PROGRAM_PREFIX", "INCREMENTS")
# gmoccapy's window fills the test's 1400x1000 virtual screen (there is no window
# manager to maximise it); tool reloading at homing is off: the changer tells
# LinuxCNC the tool in the spindle itself (M61 from its state file).
PREFERENCES = {"screen1": "window", "x_pos": 0, "y_pos": 0, "width": 1400, "height": 1000,
               "reload_tool": False, "use_toolmeasurement": False}


def fail(why):
    sys.exit("gmoccapy_ini.py: " + why)


def main():
    path = sys.argv[1]
    folder = os.path.dirname(os.path.abspath(path))
    text = open(path).read()
    sections = re.split(r"(?m)^(?=\[)", text)
    display = [s for s in sections if s.startswith("[DISPLAY]")]
    if len(display) != 1:
        fail("expected one [DISPLAY] section in %s" % path)
    keys = {}
    for line in display[0].splitlines()[1:]:
        m = re.match(r"\s*([A-Z_0-9]+)\s*=\s*(.*?)\s*$", line)
        if m:
            keys.setdefault(m.group(1), m.group(2))
    if "GLADEVCP" not in keys:
        fail("no [DISPLAY]GLADEVCP (the panel's AXIS line) in %s" % path)

    def absolute(p):
        return p if os.path.isabs(p) else os.path.normpath(os.path.join(folder, p))

    hal_line = re.compile(r"(?m)^POSTGUI_HALFILE\s*=\s*(\S*%s)\s*\n" % re.escape(PANEL_HAL))
    found = hal_line.search(text)
    if not found:
        fail("no [HAL]POSTGUI_HALFILE naming %s in %s" % (PANEL_HAL, path))
    panel_hal = absolute(found.group(1))
    # GLADEVCP = -c NAME -u HANDLER.py PANEL.ui: the files made absolute (gmoccapy
    # splits the command on spaces, so no path may hold one).
    words = shlex.split(keys["GLADEVCP"])
    words = [absolute(w) if w.endswith((".py", ".ui")) else w for w in words]
    command = ["gladevcp", "-x", "{XID}", "-H", panel_hal] + words
    if any(" " in w for w in command):
        fail("gmoccapy splits EMBED_TAB_COMMAND on spaces; a path has one: %s" % command)

    # CYCLE_TIME: gmoccapy wants milliseconds as an integer, AXIS seconds.
    cycle = float(keys.get("CYCLE_TIME", "0.1"))
    lines = ["[DISPLAY]", "DISPLAY = gmoccapy",
             "CYCLE_TIME = %d" % round(cycle * 1000 if cycle < 5 else cycle)]
    lines += ["%s = %s" % (k, keys[k]) for k in KEEP if k in keys]
    preferences = os.path.join(folder, "gmoccapy.pref")
    lines += ["PREFERENCE_FILE_PATH = " + preferences,
              "# fixed_atc_probe: its panel, on the right of gmoccapy (docs/gmoccapy.md)",
              "EMBED_TAB_NAME = Tool changer",
              "EMBED_TAB_LOCATION = box_right",
              "EMBED_TAB_COMMAND = " + " ".join(command)]
    sections[sections.index(display[0])] = "\n".join(lines) + "\n\n"
    text = hal_line.sub("# fixed_atc_probe: the panel's HAL file runs from EMBED_TAB_COMMAND (gladevcp -H)\n",
                        "".join(sections))
    with open(path, "w") as f:
        f.write(text)
    with open(preferences, "w") as f:
        f.write("[DEFAULT]\n" + "".join("%s = %s\n" % kv for kv in PREFERENCES.items()))


if __name__ == "__main__":
    main()
