#!/usr/bin/python3
"""The GUI test's operator: started by LinuxCNC beside its GUI ([APPLICATIONS]),
AXIS or gmoccapy ([DISPLAY]DISPLAY), it finds the fixed_atc_probe panel's
widgets through AT-SPI, clicks them with the X server's test extension like a
mouse would, follows the panel's HAL pins and LinuxCNC's status, takes
screenshots, then quits the GUI.
Writes FATC_RESULTS (JSON) and the screenshots into FATC_ARTIFACTS.

The panel is a GtkPlug inside AXIS (Tk), which has no accessibility tree to
hang it on, or inside gmoccapy's GtkSocket (EMBED_TAB_COMMAND); GTK names the
plug's accessible in the _XEMBED_AT_SPI_PATH property of its window, and the
driver walks the tree from there over D-Bus, in either GUI.

In AXIS the whole operator run: unload and load tool 4, the program page
(a program opened with axis-remote), the Setup page's Teach loading. In
gmoccapy the part that proves the embedding: the same unload and load."""
import json
import os
import subprocess
import sys
import time
import traceback

import gi
gi.require_version("Gdk", "3.0")
from gi.repository import Gdk, Gio, GLib  # noqa: E402

import Xlib.protocol.event  # noqa: E402
import Xlib.error  # noqa: E402
from Xlib import X, display  # noqa: E402

sys.path.insert(0, os.path.join(os.environ["FATC_ROOT"], "tests", "integration", "harness"))
import driver  # noqa: E402  (bring-up and waits shared with the integration runs)
import linuxcnc  # noqa: E402
from driver import hal, stat, wait_for  # noqa: E402
from Xlib.ext import xtest  # noqa: E402

STATE_CHECKED = 4  # AtspiStateType
STATE_SENSITIVE = 24
COORDS_SCREEN = 0

PANEL_PINS = ["load-enabled", "unload-enabled", "continue-enabled", "cancel-enabled",
              "clear-fault-enabled", "load", "unload", "continue", "cancel", "tool-number",
              "teach-pocket-enabled", "teach-loading-enabled", "pocket-number",
              "measure-all-enabled", "measure-which", "verify-pocket-enabled"]

xdisplay = display.Display()
result = {"steps": [], "messages": [], "error": None, "screenshots": []}


def gui():
    """The GUI LinuxCNC runs: axis or gmoccapy."""
    return os.path.basename(driver.ini().find("DISPLAY", "DISPLAY").split()[0])


def note(what):
    stat.poll()
    entry = {"what": what, "t": time.monotonic(), "tool_in_spindle": stat.tool_in_spindle,
             "state": hal.get_value("fixed_atc_probe.state"),
             "changer_tool": hal.get_value("fixed_atc_probe.tool-in-spindle")}
    entry.update({"fatc-panel." + p: hal.get_value("fatc-panel." + p) for p in PANEL_PINS})
    result["steps"].append(entry)


class Accessible:
    """One node of an application's AT-SPI tree, reached over the a11y bus."""
    bus = None

    def __init__(self, name, path):
        self.name, self.path = name, path

    @classmethod
    def connect(cls):
        session = Gio.bus_get_sync(Gio.BusType.SESSION)
        address = session.call_sync("org.a11y.Bus", "/org/a11y/bus", "org.a11y.Bus", "GetAddress",
                                    None, None, 0, 5000, None).unpack()[0]
        cls.bus = Gio.DBusConnection.new_for_address_sync(
            address, Gio.DBusConnectionFlags.AUTHENTICATION_CLIENT |
            Gio.DBusConnectionFlags.MESSAGE_BUS_CONNECTION, None, None)

    def call(self, interface, method, args=None):
        return self.bus.call_sync(self.name, self.path, interface, method, args, None, 0, 5000,
                                  None).unpack()

    def children(self):
        return [Accessible(n, p) for n, p in self.call("org.a11y.atspi.Accessible", "GetChildren")[0]]

    def role(self):
        return self.call("org.a11y.atspi.Accessible", "GetRoleName")[0]

    def label(self):
        return self.call("org.freedesktop.DBus.Properties", "Get",
                         GLib.Variant("(ss)", ("org.a11y.atspi.Accessible", "Name")))[0]

    def description(self):
        return self.call("org.freedesktop.DBus.Properties", "Get",
                         GLib.Variant("(ss)", ("org.a11y.atspi.Accessible", "Description")))[0]

    def sensitive(self):
        low, _ = self.call("org.a11y.atspi.Accessible", "GetState")[0]
        return bool(low & (1 << STATE_SENSITIVE))

    def checked(self):
        low, _ = self.call("org.a11y.atspi.Accessible", "GetState")[0]
        return bool(low & (1 << STATE_CHECKED))

    def find_described(self, role, words):
        """The first node (breadth first) of `role` whose description (its
        tooltip) starts with `words`."""
        level = [self]
        while level:
            below = []
            for node in level:
                for child in node.children():
                    if child.role() == role and child.description().startswith(words):
                        return child
                    below.append(child)
            level = below
        return None

    def extents(self):
        return self.call("org.a11y.atspi.Component", "GetExtents", GLib.Variant("(u)", (COORDS_SCREEN,)))[0]

    def set_value(self, value):
        self.call("org.freedesktop.DBus.Properties", "Set",
                  GLib.Variant("(ssv)", ("org.a11y.atspi.Value", "CurrentValue", GLib.Variant("d", value))))

    def find_named(self, label):
        for child in self.children():
            if child.label() == label:
                return child
            found = child.find_named(label)
            if found:
                return found
        return None

    def labels(self):
        """Every label below this node, in the tree's order."""
        found = []
        for child in self.children():
            if child.role() == "label":
                found.append(child)
            found += child.labels()
        return found

    def find(self, role, label=None):
        for child in self.children():
            if child.role() == role and (label is None or child.label() == label):
                return child
            found = child.find(role, label)
            if found:
                return found
        return None


def panel_plug():
    """The panel's root accessible, from the property GTK sets on the plug window."""
    atom = xdisplay.intern_atom("_XEMBED_AT_SPI_PATH")

    def search(window):
        # A window may close while the tree is walked (AXIS opens and closes
        # some while it starts): that one holds no panel.
        try:
            value = window.get_full_property(atom, X.AnyPropertyType)
            children = [] if value else window.query_tree().children
        except Xlib.error.XError:
            return None
        if value:
            return value.value.decode() if isinstance(value.value, bytes) else bytes(value.value).decode()
        for child in children:
            found = search(child)
            if found:
                return found
        return None
    where = search(xdisplay.screen().root)
    if not where:
        return None
    name, path = where.rsplit(":", 1)
    return Accessible(name, path)


def panel_ready():
    plug = panel_plug()
    return plug is not None and plug.find("push button", "Load / Probe") is not None


def button(name):
    return panel_plug().find("push button", name)


def sensitive(name):
    return button(name).sensitive()


def click(name, node=None):
    """A left click in the middle of the button (or of `node`), through the X server."""
    x, y, width, height = (node or button(name)).extents()
    x, y = x + width // 2, y + height // 2
    # From outside the panel, as a hand moves the mouse: GTK only takes the
    # click of a button the pointer has entered.
    xtest.fake_input(xdisplay, X.MotionNotify, x=1, y=1)
    xdisplay.sync()
    time.sleep(0.05)
    xtest.fake_input(xdisplay, X.MotionNotify, x=x, y=y)
    xdisplay.sync()
    time.sleep(0.05)
    xtest.fake_input(xdisplay, X.ButtonPress, 1)
    xdisplay.sync()
    time.sleep(0.05)
    xtest.fake_input(xdisplay, X.ButtonRelease, 1)
    xdisplay.sync()
    note("clicked " + name)


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
    """The panel's area on the screen: around every widget it shows."""
    boxes = []

    def walk(node):
        for child in node.children():
            if child.role() in ("push button", "label", "spin button"):
                x, y, w, h = child.extents()
                if w > 0 and h > 0 and x >= 0 and y >= 0:  # hidden widgets lie far off
                    boxes.append((x, y, x + w, y + h))
            walk(child)
    walk(panel_plug())
    return (min(b[0] for b in boxes) - margin, min(b[1] for b in boxes) - margin,
            max(b[2] for b in boxes) + margin, max(b[3] for b in boxes) + margin)


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
    click(name, panel_plug().find("page tab", name))


def pin(name, value):
    return lambda: hal.get_value(name) == value


def quit_gui():
    if gui() == "axis":
        os.system("axis-remote --quit")
        return
    # gmoccapy: its window closed as a window manager would (WM_DELETE_WINDOW);
    # gmoccapy then turns the machine off, ends its panel and quits.
    window = gmoccapy_window()
    if window is None:
        return
    protocols = xdisplay.intern_atom("WM_PROTOCOLS")
    delete = xdisplay.intern_atom("WM_DELETE_WINDOW")
    window.send_event(Xlib.protocol.event.ClientMessage(
        window=window, client_type=protocols, data=(32, [delete, X.CurrentTime, 0, 0, 0])))
    xdisplay.sync()


def gmoccapy_window():
    """gmoccapy's main window: its largest window on the screen."""
    found = []
    for window in xdisplay.screen().root.query_tree().children:
        wm_class = window.get_wm_class()
        if wm_class and "gmoccapy" in (wm_class[0].lower(), wm_class[1].lower()) \
                and window.get_attributes().map_state == X.IsViewable:
            g = window.get_geometry()
            found.append((g.width * g.height, window))
    return max(found, key=lambda f: f[0])[1] if found else None


def gui_window():
    """gmoccapy's main window on the screen: [x, y, width, height]."""
    window = gmoccapy_window()
    if window is None:
        return None
    g = window.get_geometry()
    return [g.x, g.y, g.width, g.height]


def gmoccapy_app():
    """gmoccapy's application node in AT-SPI (None before it registers)."""
    registry = Accessible("org.a11y.atspi.Registry", "/org/a11y/atspi/accessible/root")
    return next((a for a in registry.children() if a.label() == "gmoccapy"), None)


def gmoccapy_popups(words):
    """The texts with `words` that gmoccapy shows in its message popups: its
    windows other than the main one (searched whole, that one is large)."""
    window = gui_window()
    found = []
    for top in gmoccapy_app().children():
        x, y, w, h = top.extents()
        if [x, y, w, h] == window or w <= 0:
            continue
        found += [label.label() for label in top.labels() if words in label.label()]
    return found


def gmoccapy_machine_on():
    """Out of estop and on, in step with gmoccapy: its estop and on buttons
    follow the machine's state and, toggled so, send that state again. A
    reset gmoccapy sees only once the machine is on would turn it off; so
    each step waits until gmoccapy's button shows it (over AT-SPI)."""
    wait_for(lambda: gmoccapy_app() is not None, 120, "gmoccapy over AT-SPI")
    app = gmoccapy_app()
    estop = app.find_described("toggle button", "Estop the machine")
    on = app.find_described("toggle button", "Turn the machine on")
    if estop is None or on is None:
        raise RuntimeError("gmoccapy's estop or on button not found over AT-SPI")
    # gmoccapy sets its estop button from the machine once its window is up.
    wait_for(lambda: gui_window() is not None and estop.checked(), 120, "gmoccapy showing estop")
    driver.command.state(linuxcnc.STATE_ESTOP_RESET)
    wait_for(lambda: stat.task_state == linuxcnc.STATE_ESTOP_RESET and not estop.checked(), 60,
             "gmoccapy showing the estop reset")
    driver.command.state(linuxcnc.STATE_ON)
    wait_for(lambda: stat.task_state == linuxcnc.STATE_ON and on.checked(), 60, "gmoccapy showing the machine on")
    note("machine on in gmoccapy")


def run():
    Accessible.connect()
    wait_for(panel_ready, 120, "the panel's buttons over AT-SPI")
    if gui() == "gmoccapy":
        # gmoccapy shows each message in a popup: left to it, as to an operator's GUI.
        driver.read_messages = False
        gmoccapy_machine_on()
    driver.bring_up()
    # Task settles a moment after homing; the panel follows `accepting`.
    wait_for(pin("fatc-panel.accepting", True), 60, "the changer accepting requests")
    wait_for(pin("fatc-panel.measure-all-enabled", True), 10, "Measure all enabled once the changer accepts")
    note("idle, tool number 0")
    result["idle_tool0_sensitive"] = {b: sensitive(b) for b in ("Load / Probe", "Unload", "Continue", "Cancel")}
    result["rack_start"] = rack()
    if gui() == "gmoccapy":
        result["gui_window"] = gui_window()

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
    if gui() == "gmoccapy":
        wait_for(lambda: gmoccapy_popups("Insert tool 4"), 10, "gmoccapy's popup of the insert prompt")
        result["gmoccapy_popup"] = gmoccapy_popups("Insert tool 4")
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
    if gui() == "axis":
        program_and_setup()
    result["tool_table_file"] = open(os.path.join(os.getcwd(), "sim.tbl")).read()
    result["state_file"] = json.load(open(os.path.join(os.getcwd(), "fixed_atc_state.json")))


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
    quit_gui()


if __name__ == "__main__":
    sys.exit(main())
