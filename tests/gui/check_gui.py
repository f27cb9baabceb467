#!/usr/bin/env python3
"""Checks the GUI test's results: the panel's HAL outputs and its buttons'
enabled state at each stage of an unload and a load flow clicked in AXIS,
gmoccapy, qtdragon or qtdragon_hd, the tool LinuxCNC has in the spindle at
each stage, the prompt the panel shows (and the GUI, in its own way), the
rack page as the panel showed it at each stage, the measured length in
LinuxCNC's tool table, and the screenshots (the panel on the screen,
inside the GUI's window); in AXIS also the program page's preflight of the
program opened in AXIS and Teach loading; in AXIS and QtDragon the I/O page,
the rack datum's line and the Touch page's refusal of Check datum.
   check_gui.py RESULTS.json"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "integration", "harness"))
from check import fail, measured_to_truth, ok  # noqa: E402

CONFIG = os.path.join(os.path.dirname(__file__), "..", "..", "config", "config.json")

ENABLED = ("load-enabled", "unload-enabled", "continue-enabled", "cancel-enabled")


def stage(r, what):
    found = [s for s in r["steps"] if s["what"] == what]
    if not found:
        fail("the run never reached '%s'" % what)
    return found[0]


def expect_enabled(r, what, **wanted):
    s = stage(r, what)
    got = {name: s["fatc-panel." + name] for name in ENABLED}
    expected = {name: wanted.get(name.replace("-", "_"), False) for name in ENABLED}
    if got != expected:
        fail("at '%s' the panel's pins say %s, expected %s" % (what, got, expected))
    ok("at '%s': enabled %s" % (what, [n for n in ENABLED if got[n]] or "nothing"))


def expect_rack(r, key, what, holds, measured=()):
    """The rack page at `key`: pockets 1-6 (the sim's config) holding `holds`
    ({pocket: words}, else T<pocket>), side approach, a length exactly for the
    tools in `measured`."""
    rows = r.get(key)
    if not rows:
        fail("the rack was not read %s" % what)
    if rows[0] != ["Pocket", "Tool", "Length (mm)", "Approach"]:
        fail("the rack's header %s is %s" % (what, rows[0]))
    got = {}
    for row in rows[1:]:
        if len(row) != 4 and not (len(row) == 3 and row[1] == "empty"):
            fail("a rack row %s has %d cells: %s" % (what, len(row), row))
        pocket, tool, approach = row[0], row[1], row[-1]
        length = row[2] if len(row) == 4 else ""
        if approach != "side":
            fail("pocket %s %s: approach %r, expected side" % (pocket, what, approach))
        if tool.startswith("T"):
            tool_number = tool.split()[0][1:]
            if (tool_number in measured) != (length not in ("", "never measured")):
                fail("pocket %s %s: length %r; measured are %s" % (pocket, what, length, measured))
        got[pocket] = tool
    expected = {str(p): holds.get(p, "T%d" % p) for p in range(1, 7)}
    if got != expected:
        fail("the rack %s shows %s, expected %s" % (what, got, expected))
    ok("the rack %s: %s" % (what, ", ".join("%s %s" % (p, got[p]) for p in sorted(got))))


def expect_spindle(r):
    """LinuxCNC's tool in the spindle (linuxcnc.stat) and the changer's at each
    stage: tool 4 from the removal prompt of the unload on, then none; tool 4
    again once inserted (the jog prompt) until the load puts it away."""
    for what, tool in (("idle, tool number 0", 0), ("removal prompt", 4), ("unloaded", 0),
                       ("insert prompt", 0), ("jog prompt", 4), ("loaded", 0)):
        s = stage(r, what)
        if s["tool_in_spindle"] != tool or s["changer_tool"] != tool:
            fail("at '%s' LinuxCNC has T%s in the spindle, the changer T%s, expected T%d" % (
                what, s["tool_in_spindle"], s["changer_tool"], tool))
    ok("LinuxCNC and the changer agree on the spindle's tool at each stage (T4 while inserted, none after the load)")


def expect_on_screen(r):
    """Each screenshot's panel lies on the screen and, in a GUI it is embedded in, inside its window."""
    window = r.get("gui_window")
    for shot in r["screenshots"]:
        x0, y0, x1, y1 = shot["panel"]
        width, height = shot["screen"]
        if x0 < 0 or y0 < 0 or x1 > width or y1 > height or x1 - x0 < 300 or y1 - y0 < 300:
            fail("%s: the panel at %s is not wholly on the %dx%d screen" % (shot["file"], shot["panel"], width, height))
        if r["gui"] != "axis":
            if not window:
                fail("%s's window was not found on the screen" % r["gui"])
            wx, wy, ww, wh = window
            if x0 < wx or y0 < wy or x1 > wx + ww or y1 > wy + wh:
                fail("%s: the panel at %s is not inside %s's window %s" % (shot["file"], shot["panel"], r["gui"], window))


def main():
    r = json.load(open(sys.argv[1]))
    if r["error"]:
        fail("the GUI run failed: %s (messages: %s)" % (r["error"], r["messages"][-3:]))
    axis = r["gui"] == "axis"
    ok("the panel in %s" % r["gui"])
    expect_enabled(r, "idle, tool number 0")
    expect_enabled(r, "unloaded", load_enabled=True, unload_enabled=True)
    expect_enabled(r, "removal prompt", continue_enabled=True, cancel_enabled=True)
    expect_enabled(r, "insert prompt", continue_enabled=True, cancel_enabled=True)
    expect_enabled(r, "jog prompt", continue_enabled=True, cancel_enabled=True)
    expect_enabled(r, "probing", cancel_enabled=True)
    expect_enabled(r, "loaded", load_enabled=True, unload_enabled=True)
    for key, wanted in (("idle_tool0_sensitive", {"Load / Probe": False, "Unload": False, "Continue": False, "Cancel": False}),
                        ("waiting_sensitive", {"Load / Probe": False, "Unload": False, "Continue": True, "Cancel": True}),
                        ("probing_sensitive", {"Load / Probe": False, "Unload": False, "Continue": False, "Cancel": True})):
        if r[key] != wanted:
            fail("the buttons' sensitivity (%s) is %s, expected %s" % (key, r[key], wanted))
    ok("the buttons on screen are enabled exactly as the panel's pins say")
    expect_spindle(r)
    shown = r.get("insert_prompt_shown")
    if not shown or not shown[0].startswith("Insert tool 4 into the spindle"):
        fail("at the insert prompt the panel shows %r, not the prompt" % shown)
    ok("at the insert prompt the panel shows %r" % shown[0])
    if not axis:
        shows = r.get("gui_shows")
        if not shows or "Insert tool 4 into the spindle" not in shows[0]:
            fail("at the insert prompt %s shows %r, not the prompt" % (r["gui"], shows))
        ok("%s shows the prompt too (its own message display): %r" % (r["gui"], shows[0]))
    opened = "program opened" if axis else "idle, tool number 0"
    for what, teach in ((opened, True), ("removal prompt", False),
                        ("probing", False), ("loaded", True)):
        s = stage(r, what)
        got = (s["fatc-panel.teach-loading-enabled"], s["fatc-panel.teach-pocket-enabled"],
               s["fatc-panel.verify-pocket-enabled"])
        if got != (teach, False, False):
            fail("at '%s' Teach loading/Teach pocket/Verify pocket enabled %s, expected %s (pocket 0)"
                 % (what, got, (teach, False, False)))
    ok("Teach loading enabled only while the changer is idle; Teach and Verify pocket never (pocket 0)")
    for what, measure in (("idle, tool number 0", True), (opened, True),
                          ("removal prompt", False), ("probing", False)):
        s = stage(r, what)
        if s["fatc-panel.measure-all-enabled"] != measure or s["fatc-panel.measure-which"] != 0:
            fail("at '%s' Measure all enabled %s (measure-which %s), expected %s (0)" % (
                what, s["fatc-panel.measure-all-enabled"], s["fatc-panel.measure-which"], measure))
    if r.get("measure_all_sensitive_idle") is not True:
        fail("the Measure all button on screen once the program opened: sensitive %s" % r.get("measure_all_sensitive_idle"))
    ok("Measure all on screen and enabled while the changer is idle (every tool), off during a flow")
    clicks = [s["what"] for s in r["steps"] if s["what"].startswith(("clicked", "pressed"))]
    ok("clicked in %s: %s" % (r["gui"], ", ".join(c[8:] for c in clicks)))

    expect_rack(r, "rack_start", "at the start", {})
    if r["served_during_unload"] != ["\u25b6 4"]:
        fail("while tool 4 was fetched the rack highlighted %s, expected pocket 4 only"
             % r["served_during_unload"])
    ok("while tool 4 was fetched the rack highlighted pocket 4")
    expect_rack(r, "rack_unloaded", "after the unload", {4: "empty"})
    # State file version 1 keeps pocket 4 for tool 4; version 2 frees it at
    # the unload and gives it again when the load flow puts the tool away.
    version = r["state_file"].get("version", 1)
    expect_rack(r, "rack_jog", "at the jog prompt (state file version %d)" % version,
                {4: "T4 (in the spindle)" if version == 1 else "empty"})
    expect_rack(r, "rack_loaded", "after the load", {}, measured=("4",))
    measured_to_truth(r, json.load(open(CONFIG)), 4, "measured through the panel")
    if axis:
        program_and_setup(r)
    state = r["state_file"]
    if version == 1:
        in_pocket = 4 in state["in_pocket"]
    else:
        in_pocket = state["pockets"].get("4") == {"tool": 4, "in_pocket": True}
    if not in_pocket or state["spindle"] != 0:
        fail("after the load, tool 4 should be in its pocket and the spindle empty: %s" % state)
    ok("tool 4 back in its pocket, the spindle empty")

    for shot in r["screenshots"]:
        for path in (shot["file"], shot["panel_file"]):
            with open(path, "rb") as f:
                head = f.read(8)
            if head != b"\x89PNG\r\n\x1a\n" or os.path.getsize(path) < 2000:
                fail("%s is not a screenshot" % path)
        ok("screenshot %s (panel at %s)" % (shot["file"], shot["panel"]))
    io = r.get("io_checked")
    shown = r.get("io_shown")
    if io and shown != ["zero-speed: on, expected on (LinuxCNC has the spindle off)"]:
        fail("the I/O page shows %r, not the zero-speed line" % shown)
    if io:
        ok("the I/O page in %s shows %r" % (r["gui"], shown[0]))
    # No rack_cover in the sim's config: Open cover refused, the chuck's allowed (spindle empty, off).
    if io and r["io_sensitive"] != {"Release chuck": True, "Clamp chuck": True, "Open cover": False}:
        fail("the I/O buttons' sensitivity is %s" % r["io_sensitive"])
    if io:
        ok("the I/O buttons enabled as the component allows them: %s" % r["io_sensitive"])
    if r.get("touch_checked"):
        touch_page(r)
    expect_on_screen(r)
    wanted = (4 if axis else 2) + (1 if io else 0) + (1 if r.get("touch_checked") else 0)
    if len(r["screenshots"]) != wanted:
        fail("expected %d screenshots, got %d" % (wanted, len(r["screenshots"])))
    ok("the panel wholly on the screen%s in every screenshot" % ("" if axis else " and inside %s's window" % r["gui"]))


def touch_page(r):
    """The rack datum's line and the Touch page with the spindle empty. The
    config of the run says whether the datum check was due at start
    (rack_touch.check_at_start): then M6 is refused, the panel says why in red
    and Clear datum is enabled; else the line is hidden, Clear datum not."""
    due = r["config_rack_touch"].get("check_at_start", False)
    datum = r["status_datum"]
    if due != datum.startswith("the rack datum check is due at start (rack_touch.check_at_start)"):
        fail("the status file's datum is %r; check_at_start is %s" % (datum, due))
    line = r["datum_line"]
    if not due and line is not None:
        fail("the rack datum's line shows %s while the datum refuses nothing" % line)
    if due:
        if not line or line["text"] != "M6 refused: " + datum:
            fail("the rack datum's line shows %s, expected 'M6 refused: %s'" % (line, datum))
        # The .ui's #c62828, as ATK gives a Pango colour: 16 bits per channel.
        if line["attributes"].get("fg-color") != "50886,10280,10280":
            fail("the rack datum's line is not red: its attributes are %s" % line["attributes"])
        ok("the first page says in red %r" % line["text"])
    else:
        ok("the rack datum refuses nothing: its line is hidden")
    wanted = {"Touch all pockets": True, "Teach datum": True, "Check datum": True, "Clear datum": due}
    if r["touch_sensitive"] != wanted:
        fail("the Touch page's buttons' sensitivity is %s, expected %s" % (r["touch_sensitive"], wanted))
    ok("the Touch page's buttons enabled: %s" % r["touch_sensitive"])
    shown = r.get("check_datum_shown")
    expected = ("checking the rack datum refused: the spindle is empty: put the probe "
                "(a tool of \"kind\": \"probe\") in the spindle first")
    if not shown or shown[0] != expected:
        fail("after Check datum with the spindle empty the panel shows %r, expected %r" % (shown, expected))
    ok("Check datum with the spindle empty: the panel shows %r" % shown[0])


def program_and_setup(r):
    """AXIS: the program page of the program opened in AXIS, Teach loading."""
    text = r["preflight"]
    for wanted in ("demo.ngc: 5 tool changes (M6), 0 M61, 0 problems, 0 not known",
                   "Tools: T1 (pocket 1), T3 (pocket 3), T5 (pocket 5)",
                   "Never measured: none", "Change time: "):
        if wanted not in text:
            fail("the program page does not say %r: %r" % (wanted, text))
    ok("the program page checked demo.ngc: %s" % text.splitlines()[:3])
    shown = r["teach_shown"]
    if not shown or not shown[0].startswith("taught loading: x "):
        fail("after Teach loading the panel shows %r, not the component's message" % shown)
    ok("Teach loading: the panel shows %r" % shown[0][:80])
    loading = [r["config_after_teach"]["loading"][a] for a in "xyz"]
    if any(abs(got - round(at, 4)) > 1e-4 for got, at in zip(loading, r["teach_at"])):
        fail("config.json's loading is %s, the machine was at %s" % (loading, r["teach_at"]))
    ok("config.json's loading is now %s, where the machine was" % loading)


if __name__ == "__main__":
    main()
