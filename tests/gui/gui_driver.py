#!/usr/bin/python3
"""The GUI test's operator: started by LinuxCNC beside its GUI ([APPLICATIONS]),
AXIS, gmoccapy, qtdragon or qtdragon_hd ([DISPLAY]DISPLAY), it finds the
fixed_atc_probe panel's widgets through AT-SPI, clicks them with the X
server's test extension like a mouse would, follows the panel's HAL pins and
LinuxCNC's status, takes screenshots, then quits the GUI.
Writes FATC_RESULTS (JSON) and the screenshots into FATC_ARTIFACTS.

The panel is a GtkPlug inside AXIS (Tk), which has no accessibility tree to
hang it on, or inside gmoccapy's GtkSocket (EMBED_TAB_COMMAND): GTK names the
plug's accessible in the _XEMBED_AT_SPI_PATH property of its window. In
qtdragon it is gladevcp's own window, taken into a Qt page. The driver walks
the tree from there over D-Bus (desktop.py); what differs between the GUIs
is in screens.py.

In AXIS the whole operator run: unload and load tool 4, the program page
(a program opened with axis-remote), the Setup page's Teach loading. In the
others the part that proves the embedding: the same unload and load. AXIS
and QtDragon also look at the I/O page, and at the Touch page and the rack
datum's line on the first page (Check datum pressed with the spindle empty)."""
import json
import os
import subprocess
import sys
import time
import traceback

import gi
gi.require_version("Gdk", "3.0")
from gi.repository import Gdk, GLib  # noqa: E402

sys.path.insert(0, os.path.join(os.environ["FATC_ROOT"], "tests", "integration", "harness"))
import driver  # noqa: E402  (bring-up and waits shared with the integration runs)
import screens  # noqa: E402
from desktop import Accessible, click_at, panel_plug  # noqa: E402
from driver import hal, stat, wait_for  # noqa: E402

PANEL_PINS = ["load-enabled", "unload-enabled", "continue-enabled", "cancel-enabled",
              "clear-fault-enabled", "load", "unload", "continue", "cancel", "tool-number",
              "teach-pocket-enabled", "teach-loading-enabled", "pocket-number",
              "measure-all-enabled", "measure-which", "verify-pocket-enabled"]

# The GUIs whose run looks at the I/O page too (the issue asks for AXIS and QtDragon).
IO_PAGE_GUIS = ("axis", "qtdragon")
# And at the Touch page and the rack datum's line (issue 45); QtDragon's config
# makes the datum check due at start (tests/gui/CMakeLists.txt).
TOUCH_PAGE_GUIS = ("axis", "qtdragon")
TOUCH_BUTTONS = ("Touch all pockets", "Teach datum", "Check datum", "Clear datum")

result = {"steps": [], "messages": [], "error": None, "screenshots": []}
# The GUI LinuxCNC runs ([DISPLAY]DISPLAY): its name and how it is met.
gui_name, screen = screens.screen_of(driver.ini().find("DISPLAY", "DISPLAY"))


def gui():
    return gui_name


def note(what):
    stat.poll()
    entry = {"what": what, "t": time.monotonic(), "tool_in_spindle": stat.tool_in_spindle,
             "state": hal.get_value("fixed_atc_probe.state"),
             "changer_tool": hal.get_value("fixed_atc_probe.tool-in-spindle")}
    entry.update({"fatc-panel." + p: hal.get_value("fatc-panel." + p) for p in PANEL_PINS})
    result["steps"].append(entry)


def panel_ready():
    plug = panel_plug()
    return plug is not None and plug.find("push button", "Load / Probe") is not None


def panel_in_view():
    """The panel's Load button lies on the screen (inside the GUI's window)."""
    x, y, w, h = button("Load / Probe").extents()
    window = screen.window() or [0, 0, 1 << 16, 1 << 16]
    result["panel_view"] = {"load_button": [x, y, w, h], "gui_window": window}  # for a failure's report
    return w > 0 and h > 0 and window[0] <= x and x + w <= window[0] + window[2] \
        and window[1] <= y and y + h <= window[1] + window[3]


def button(name):
    return panel_plug().find("push button", name)


def sensitive(name):
    return button(name).sensitive()


def click(name, node=None):
    """A left click in the middle of the button (or of `node`), through the X
    server; a button below the fold of the panel's scrolled window (QtDragon's
    USER page gives it less room than it asks) is pressed over AT-SPI instead,
    as the keyboard would."""
    node = node or button(name)
    if in_view(node):
        click_at(node)
        note("clicked " + name)
    else:
        node.call("org.a11y.atspi.Action", "DoAction", GLib.Variant("(i)", (0,)))
        note("pressed " + name)


def in_view(node):
    """`node` lies wholly inside the view of the panel's scrolled window."""
    pane_x, pane_y, pane_w, pane_h = panel_plug().find("scroll pane").extents()
    x, y, w, h = node.extents()
    return h > 0 and pane_y <= y and y + h <= pane_y + pane_h


def said_or_shown(words, said):
    """LinuxCNC's message channel said `words` since message `said`, or the
    panel shows them. AXIS reads the same channel, and NML keeps one read
    mark for all readers: a message AXIS took first never reaches the driver."""
    return any(words in m for m in driver.messages[said:]) or bool(panel_says(words))


def answer(name, next_prompt=None):
    """Clicks Continue or Cancel at a prompt and waits until the changer moved
    on: the prompt closes or, where one prompt follows another, the next is
    said (the MDI step between them can be quicker than the panel's refresh)."""
    said = len(driver.messages)
    click(name)
    if next_prompt:
        wait_for(lambda: said_or_shown(next_prompt, said), 30,
                 "the prompt '%s' after %s" % (next_prompt, name))
    else:
        wait_for(pin("fatc-panel.continue-enabled", False), 30, "the prompt to close after " + name)


def set_tool_number(number):
    panel_plug().find("spin button", "Tool number").set_value(float(number))
    wait_for(lambda: hal.get_value("fatc-panel.tool-number") == number, 10, "the tool number")
    note("tool number %d" % number)


def screenshot(name, shown, words=None):
    """The whole screen, once the panel shows `shown` (a button name and
    whether it is enabled) and, if given, `words`, and the panel alone beside
    it (`-panel.png`)."""
    wait_for(lambda: sensitive(shown[0]) == shown[1], 10, "the panel to show " + str(shown))
    if words:
        wait_for(lambda: panel_says(words), 10, "the panel to say " + words)
    time.sleep(0.3)  # the widget is updated; give GTK one frame to paint it
    root = Gdk.get_default_root_window()
    picture = Gdk.pixbuf_get_from_window(root, 0, 0, root.get_width(), root.get_height())
    path = os.path.join(os.environ["FATC_ARTIFACTS"], name + ".png")
    picture.savev(path, "png", [], [])
    x0, y0, x1, y1 = panel_region()
    panel_path = os.path.join(os.environ["FATC_ARTIFACTS"], name + "-panel.png")
    picture.new_subpixbuf(x0, y0, x1 - x0, y1 - y0).savev(panel_path, "png", [], [])
    result["screenshots"].append({"file": path, "panel_file": panel_path, "panel": [x0, y0, x1, y1],
                                  "screen": [root.get_width(), root.get_height()]})


def panel_region(margin=6):
    """The panel's area on the screen: around every widget it shows, within
    its scrolled window's view (a GUI may give it less room than it asks)."""
    boxes = []

    def walk(node):
        for child in node.children():
            if child.role() in ("push button", "label", "spin button"):
                x, y, w, h = child.extents()
                if w > 0 and h > 0 and x >= 0 and y >= 0:  # hidden widgets lie far off
                    boxes.append((x, y, x + w, y + h))
            walk(child)
    walk(panel_plug())
    x, y, w, h = panel_plug().find("scroll pane").extents()
    return (max(min(b[0] for b in boxes) - margin, x), max(min(b[1] for b in boxes) - margin, y),
            min(max(b[2] for b in boxes) + margin, x + w), min(max(b[3] for b in boxes) + margin, y + h))


def rack():
    """The rack page as the panel shows it: its labels read over AT-SPI, put
    in rows and columns by where they are on the screen (header first); read
    again while the panel is laying them out (two readings differ)."""
    last = None
    for _ in range(20):
        rows = rack_once()
        if rows == last and all(len(row) == 4 for row in rows):
            return rows
        last = rows
        time.sleep(0.05)
    return last


def rack_once():
    cells = []
    for label in panel_plug().find_named("Rack pockets").labels():
        x, y, w, h = label.extents()
        cells.append((y + h / 2, x, label.label()))
    rows = []  # a cell whose middle is within a few pixels of a row's is in that row
    for middle, x, text in sorted(cells):
        if rows and middle - rows[-1][0] < 4:
            rows[-1][1].append((x, text))
        else:
            rows.append((middle, [(x, text)]))
    return [[text for _, text in sorted(row)] for _, row in rows]


def rack_shows(pocket, tool, timeout=5):
    """Waits (at most `timeout`) for the rack to show `tool` in `pocket`; the
    rows it showed last either way, for the checker to judge."""
    deadline = time.monotonic() + timeout
    while True:
        rows = rack()
        if any(row[0].split()[-1] == str(pocket) and row[1] == tool for row in rows[1:]) \
                or time.monotonic() > deadline:
            return rows
        time.sleep(0.1)


def panel_says(words):
    """The panel's labels that say `words` (the last message is one of them)."""
    return [label.label() for label in panel_plug().labels() if words in label.label()]


def preflight():
    """The program page's words, as the panel shows them."""
    return "\n".join(label.label() for label in panel_plug().find_named("Program preflight").labels())


def show_page(name):
    """Clicks the page's tab; where the GUI gives the panel too little room to
    show the tabs (QtDragon's USER page: they lie below the fold of its
    scrolled window), the tab is selected over AT-SPI instead, as the
    keyboard would."""
    tab = panel_plug().find("page tab", name)
    if in_view(tab):
        click(name, tab)
        return
    tabs = panel_plug().find("page tab list")
    index = [t.label() for t in tabs.children()].index(name)
    tabs.call("org.a11y.atspi.Selection", "SelectChild", GLib.Variant("(i)", (index,)))
    note("selected " + name)

def pin(name, value):
    return lambda: hal.get_value(name) == value


def run():
    screen.gui_up()
    Accessible.connect()
    wait_for(panel_ready, 120, "the panel's buttons over AT-SPI")
    # A GUI that shows each message itself reads them: left to it, as to an operator's.
    driver.read_messages = screen.reads_messages
    screen.machine_on()
    screen.show_panel()
    wait_for(panel_in_view, 30, "the panel in view in " + gui())
    note("panel in view in " + gui())
    driver.bring_up()
    # Task settles a moment after homing; the panel follows `accepting`.
    wait_for(pin("fatc-panel.accepting", True), 60, "the changer accepting requests")
    wait_for(pin("fatc-panel.measure-all-enabled", True), 10, "Measure all enabled once the changer accepts")
    note("idle, tool number 0")
    result["idle_tool0_sensitive"] = {b: sensitive(b) for b in ("Load / Probe", "Unload", "Continue", "Cancel")}
    result["rack_start"] = rack()
    result["gui_window"] = screen.window()

    if gui() == "axis":
        # The demo program opened in AXIS: the panel checks it with --lint.
        subprocess.run(["axis-remote", os.path.join(os.environ["FATC_ROOT"], "nc_files", "demo.ngc")],
                       check=True, timeout=30)
        wait_for(lambda: "Tools:" in preflight(), 30, "the preflight of demo.ngc")
        note("program opened")
    result["measure_all_sensitive_idle"] = sensitive("Measure all")

    # Unload tool 4, then load it back and measure it, all from the panel.
    set_tool_number(4)
    wait_for(pin("fatc-panel.unload-enabled", True), 10, "Unload enabled")
    click("Unload")
    # While the changer fetches tool 4, its pocket is highlighted.
    served = set()
    deadline = time.monotonic() + 180
    while not hal.get_value("fatc-panel.continue-enabled"):
        if time.monotonic() > deadline:
            raise TimeoutError("the removal prompt")
        served.update(row[0] for row in rack()[1:] if row and not row[0].isdigit())
        time.sleep(0.2)
    result["served_during_unload"] = sorted(served)
    note("removal prompt")
    result["waiting_sensitive"] = {b: sensitive(b) for b in ("Load / Probe", "Unload", "Continue", "Cancel")}
    answer("Continue")
    wait_for(pin("fatc-panel.load-enabled", True), 180, "idle after the unload")
    note("unloaded")
    result["rack_unloaded"] = rack_shows(4, "empty")

    click("Load / Probe")
    wait_for(pin("fatc-panel.continue-enabled", True), 180, "the insert prompt")
    note("insert prompt")
    screenshot("insert_prompt", ("Continue", True), "Insert tool 4")
    result["insert_prompt_shown"] = panel_says("Insert tool 4")
    if gui() != "axis":
        wait_for(lambda: screen.shows("Insert tool 4"), 10, gui() + " showing the insert prompt")
        result["gui_shows"] = screen.shows("Insert tool 4")
    answer("Continue", next_prompt="Jog it closer")
    wait_for(pin("fatc-panel.continue-enabled", True), 180, "the jog prompt")
    note("jog prompt")
    # Inserted, not yet measured. State file version 1 keeps pocket 4 for tool 4;
    # version 2 frees it at the unload and gives it again at the end of the load.
    version = json.load(open(driver.state_path())).get("version", 1)
    result["rack_jog"] = rack_shows(4, "T4 (in the spindle)" if version == 1 else "empty")
    answer("Continue")
    wait_for(lambda: hal.get_value("fixed_atc_probe.awaiting") == 2, 60, "the probe")
    note("probing")
    result["probing_sensitive"] = {b: sensitive(b) for b in ("Load / Probe", "Unload", "Continue", "Cancel")}
    wait_for(pin("fatc-panel.load-enabled", True), 180, "idle after the load")
    note("loaded")
    result["rack_loaded"] = rack_shows(4, "T4")
    screenshot("after_load", ("Load / Probe", True))
    result["io_checked"] = gui() in IO_PAGE_GUIS
    if result["io_checked"]:
        io_page()
    result["touch_checked"] = gui() in TOUCH_PAGE_GUIS
    if result["touch_checked"]:
        touch_page()
    if gui() == "axis":
        program_and_setup()
    result["tool_table_file"] = open(os.path.join(os.getcwd(), "sim.tbl")).read()
    result["state_file"] = json.load(open(os.path.join(os.getcwd(), "fixed_atc_state.json")))


def io_page():
    """The I/O page (the GUI test's config wires zero-speed, which the sim's
    spindle feeds): its sensor line against the belief, its buttons enabled
    as the component allows them. Nothing is pressed: the integration run of
    the sensors drives each output."""
    show_page("I/O")
    wait_for(lambda: panel_says("zero-speed: on, expected on"), 10, "the I/O page's sensor line")
    result["io_shown"] = panel_says("zero-speed: ")
    result["io_sensitive"] = {b: sensitive(b) for b in ("Release chuck", "Clamp chuck", "Open cover")}
    screenshot("io", ("Clamp chuck", True), "zero-speed: on")
    note("I/O page")


def datum_line():
    """The rack datum's line as the panel shows it, with its attributes (its
    colour among them); None while it is hidden (hidden widgets lie far off)."""
    label = panel_plug().find_named("Rack datum")
    if label is None:
        return None
    x, y, w, h = label.extents()
    if w <= 0 or h <= 0 or x < 0 or y < 0:
        return None
    attributes = label.call("org.a11y.atspi.Text", "GetAttributes", GLib.Variant("(i)", (0,)))[0]
    return {"text": label.text(), "attributes": dict(attributes)}


def touch_page():
    """The rack datum's line on the first page, as the status file's `datum`
    says (empty: hidden), then the Touch page with the spindle empty: its
    buttons enabled as the panel's rules say, and Check datum refused, the
    component's words in the panel's message area. Nothing moves."""
    with open(driver.config_path()) as f:
        result["config_rack_touch"] = json.load(f).get("rack_touch", {})
    with open(driver.state_path() + ".status") as f:
        result["status_datum"] = json.load(f).get("datum", "")
    result["datum_line"] = datum_line()
    show_page("Touch")
    result["touch_sensitive"] = {b: sensitive(b) for b in TOUCH_BUTTONS}
    said = len(driver.messages)
    click("Check datum")
    refused = "checking the rack datum refused: "
    wait_for(lambda: said_or_shown(refused, said), 30, "the refusal of Check datum")
    wait_for(lambda: panel_says(refused), 10, "the panel to show the refusal of Check datum")
    result["check_datum_shown"] = panel_says(refused)
    screenshot("touch", ("Check datum", True), refused)
    note("check datum refused")


def program_and_setup():
    """AXIS only: the program page of the program opened in AXIS, and Teach loading."""
    show_page("Program")
    result["preflight"] = preflight()
    screenshot("program", ("Load / Probe", True))

    # Teach loading where the spindle is now, from the Setup page: nothing
    # moves, config.json is written, the component's message shows on the panel.
    show_page("Setup")
    stat.poll()
    result["teach_at"] = list(stat.actual_position[:3])
    said = len(driver.messages)
    click("Teach loading")
    wait_for(lambda: said_or_shown("taught loading", said), 30, "the message of the teach")
    wait_for(lambda: panel_says("taught loading"), 10, "the panel to show the teach's message")
    result["teach_shown"] = panel_says("taught loading")
    note("taught loading")
    screenshot("setup", ("Teach loading", True))
    with open(os.path.join(os.getcwd(), "config.json")) as f:
        result["config_after_teach"] = json.load(f)


def main():
    own = hal.component("fatc-gui-driver")  # hal.get_value needs a component of our own
    own.ready()
    try:
        result["gui"] = gui()
        run()
    except Exception as e:  # the checker reports it; the GUI must still quit
        result["error"] = "%s: %s\n%s" % (type(e).__name__, e, traceback.format_exc())
    result["messages"] = driver.messages
    with open(os.environ["FATC_RESULTS"], "w") as f:
        json.dump(result, f, indent=1)
    try:
        screen.quit()
    finally:  # quit() may fail where the window never came up
        end_gui_left_open()


def end_gui_left_open(timeout=60):
    """A GUI whose window never came up for quit() to close (qtvcp under a busy
    machine) would keep LinuxCNC up until ctest's time-out: ended, once it has
    had `timeout` seconds to close; a qtvcp stuck before its window may not
    take SIGTERM, so SIGKILL after ten more."""
    program = os.path.basename(driver.ini().find("DISPLAY", "DISPLAY").split()[0])
    mine = ["-x", "-u", str(os.getuid()), program]

    def gone_within(seconds):
        deadline = time.monotonic() + seconds
        while subprocess.run(["pgrep"] + mine, stdout=subprocess.DEVNULL).returncode == 0:
            if time.monotonic() > deadline:
                return False
            time.sleep(0.5)
        return True

    for signal_name, grace in ((None, timeout), ("-TERM", 10), ("-KILL", 10)):
        if signal_name:
            subprocess.run(["pkill", signal_name] + mine)
        if gone_within(grace):
            return


if __name__ == "__main__":
    sys.exit(main())
