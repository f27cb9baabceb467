#!/usr/bin/env python3
"""Turns the simulated mill's INI (as run_sim.sh copied it) into the same
machine shown in gmoccapy, qtdragon or qtdragon_hd with fixed_atc_probe's
panel embedded: the [DISPLAY] section is replaced, everything else stays as
the sim has it.
   embed_ini.py GUI SIM_INI

The panel's command comes from the AXIS line, [DISPLAY]GLADEVCP (its
component name, handler and .ui), the panel's HAL file from
[HAL]POSTGUI_HALFILE. These GUIs start an embedded panel as a child and run
the POSTGUI_HALFILE right after their own window is built, without waiting
for the child: the panel's pins may not exist yet. So the HAL file moves onto
the panel's command line (gladevcp -H runs it once the pins exist) and out of
POSTGUI_HALFILE. Also writes the GUI's preference file beside the INI
(docs/gmoccapy.md and docs/qtdragon.md say why each setting)."""
import os
import re
import shlex
import sys

PANEL_HAL = "fixed_atc_probe_panel.hal"
# The machine's [DISPLAY] keys these GUIs read as AXIS does; the rest is AXIS's.
KEEP = ("POSITION_OFFSET", "POSITION_FEEDBACK", "MAX_FEED_OVERRIDE", "PROGRAM_PREFIX", "INCREMENTS")


def qtdragon(screen):
    # qtdragon reads the speeds its sliders offer from [DISPLAY]; the
    # preferences: no closing question (the test closes the window), no desktop
    # notifications (the test's D-Bus session has no notification daemon).
    return {"display": "qtvcp " + screen,
            "location": "stackedWidget_mainTab",
            "keys": {"MAX_LINEAR_VELOCITY": "[TRAJ]MAX_LINEAR_VELOCITY", "DEFAULT_LINEAR_VELOCITY": 50,
                     "MAX_SPINDLE_0_SPEED": 24000, "DEFAULT_SPINDLE_0_SPEED": 12000,
                     "MAX_SPINDLE_POWER": 2200},
            "preferences": {"SCREEN_OPTIONS": {"shutdown_check": False, "desktop_notify": False}}}


GUIS = {
    # gmoccapy's window fills the test's 1400x1000 virtual screen (there is no
    # window manager to maximise it); tool reloading at homing is off: the
    # changer tells LinuxCNC the tool in the spindle itself (M61 from its state
    # file). gmoccapy wants CYCLE_TIME in milliseconds.
    "gmoccapy": {"display": "gmoccapy", "location": "box_right", "keys": {},
                 "preferences": {"DEFAULT": {"screen1": "window", "x_pos": 0, "y_pos": 0, "width": 1400,
                                             "height": 1000, "reload_tool": False,
                                             "use_toolmeasurement": False}}},
    "qtdragon": qtdragon("qtdragon"),
    "qtdragon_hd": qtdragon("qtdragon_hd"),
}


def fail(why):
    sys.exit("embed_ini.py: " + why)


def sections_of(text):
    return re.split(r"(?m)^(?=\[)", text)


def keys_of(section):
    keys = {}
    for line in section.splitlines()[1:]:
        m = re.match(r"\s*([A-Z_0-9]+)\s*=\s*(.*?)\s*$", line)
        if m:
            keys.setdefault(m.group(1), m.group(2))
    return keys


def lookup(sections, value):
    """A value, or `[SECTION]KEY` read from the INI."""
    m = re.match(r"\[(\w+)\](\w+)$", str(value))
    if not m:
        return value
    found = [keys_of(s).get(m.group(2)) for s in sections if s.startswith("[%s]" % m.group(1))]
    if not found or found[0] is None:
        fail("no %s in the INI" % value)
    return found[0]


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in GUIS:
        fail("usage: embed_ini.py %s SIM_INI" % "|".join(GUIS))
    gui, path = GUIS[sys.argv[1]], sys.argv[2]
    folder = os.path.dirname(os.path.abspath(path))
    text = open(path).read()
    sections = sections_of(text)
    display = [s for s in sections if s.startswith("[DISPLAY]")]
    if len(display) != 1:
        fail("expected one [DISPLAY] section in %s" % path)
    keys = keys_of(display[0])
    if "GLADEVCP" not in keys:
        fail("no [DISPLAY]GLADEVCP (the panel's AXIS line) in %s" % path)

    def absolute(p):
        return p if os.path.isabs(p) else os.path.normpath(os.path.join(folder, p))

    hal_line = re.compile(r"(?m)^POSTGUI_HALFILE\s*=\s*(\S*%s)\s*\n" % re.escape(PANEL_HAL))
    found = hal_line.search(text)
    if not found:
        fail("no [HAL]POSTGUI_HALFILE naming %s in %s" % (PANEL_HAL, path))
    panel_hal = absolute(found.group(1))
    # GLADEVCP = -c NAME -u HANDLER.py PANEL.ui: the files made absolute (the
    # GUIs split the command on spaces, so no path may hold one).
    words = shlex.split(keys["GLADEVCP"])
    words = [absolute(w) if w.endswith((".py", ".ui")) else w for w in words]
    command = ["gladevcp", "-x", "{XID}", "-H", panel_hal] + words
    if any(" " in w for w in command):
        fail("EMBED_TAB_COMMAND is split on spaces; a path has one: %s" % command)

    # CYCLE_TIME: gmoccapy and qtvcp take milliseconds, AXIS seconds.
    cycle = float(keys.get("CYCLE_TIME", "0.1"))
    lines = ["[DISPLAY]", "DISPLAY = " + gui["display"],
             "CYCLE_TIME = %d" % round(cycle * 1000 if cycle < 5 else cycle)]
    lines += ["%s = %s" % (k, keys[k]) for k in KEEP if k in keys]
    lines += ["%s = %s" % (k, lookup(sections, v)) for k, v in gui["keys"].items()]
    preferences = os.path.join(folder, sys.argv[1] + ".pref")
    lines += ["PREFERENCE_FILE_PATH = " + preferences,
              "# fixed_atc_probe: its panel embedded (docs/gmoccapy.md, docs/qtdragon.md)",
              "EMBED_TAB_NAME = Tool changer",
              "EMBED_TAB_LOCATION = " + gui["location"],
              "EMBED_TAB_COMMAND = " + " ".join(command)]
    sections[sections.index(display[0])] = "\n".join(lines) + "\n\n"
    text = hal_line.sub("# fixed_atc_probe: the panel's HAL file runs from EMBED_TAB_COMMAND (gladevcp -H)\n",
                        "".join(sections))
    with open(path, "w") as f:
        f.write(text)
    with open(preferences, "w") as f:
        for section, values in gui["preferences"].items():
            f.write("[%s]\n" % section + "".join("%s = %s\n" % kv for kv in values.items()))


if __name__ == "__main__":
    main()
