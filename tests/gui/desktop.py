"""What the GUI test's operator sees and touches: the X server (clicks like a
mouse's, through its test extension; windows) and the applications' AT-SPI
trees over the accessibility bus (GTK's and, with
QT_LINUX_ACCESSIBILITY_ALWAYS_ON, Qt's)."""
import time

import gi
gi.require_version("Gdk", "3.0")
from gi.repository import Gio, GLib  # noqa: E402

import Xlib.error  # noqa: E402
import Xlib.protocol.event  # noqa: E402
from Xlib import X, display  # noqa: E402
from Xlib.ext import xtest  # noqa: E402

STATE_CHECKED = 4  # AtspiStateType
STATE_SENSITIVE = 24
COORDS_SCREEN = 0
PANEL = "fatc-panel"  # the panel's component name, its window's title

xdisplay = display.Display()


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
        # A node may go while the tree is walked (Qt makes and drops some as
        # it repaints): it has no children then.
        try:
            return [Accessible(n, p) for n, p in self.call("org.a11y.atspi.Accessible", "GetChildren")[0]]
        except GLib.Error:
            return []

    def answer(self, *args):
        """call()'s first value, "" for a node gone while the tree is walked
        (as in children())."""
        try:
            return self.call(*args)[0]
        except GLib.Error:
            return ""

    def role(self):
        return self.answer("org.a11y.atspi.Accessible", "GetRoleName")

    def named_property(self, name):
        return self.answer("org.freedesktop.DBus.Properties", "Get",
                           GLib.Variant("(ss)", ("org.a11y.atspi.Accessible", name)))

    def label(self):
        return self.named_property("Name")

    def description(self):
        return self.named_property("Description")

    def text(self):
        """What a text widget holds (a label's words are its label())."""
        return self.call("org.a11y.atspi.Text", "GetText", GLib.Variant("(ii)", (0, -1)))[0]

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


def application(label):
    """An application's node in AT-SPI (None before it registers)."""
    registry = Accessible("org.a11y.atspi.Registry", "/org/a11y/atspi/accessible/root")
    return next((a for a in registry.children() if a.label() == label), None)


def panel_plug():
    """The panel's root accessible: from the property GTK sets on the plug
    window (AXIS, gmoccapy), else gladevcp's own window, which qtvcp took
    into its page (gladevcp --xid makes a window, not a plug)."""
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
    if where:
        name, path = where.rsplit(":", 1)
        return Accessible(name, path)
    app = application("gladevcp")
    return app and next((w for w in app.children() if w.label() == PANEL), None)




def click_at(node):
    """A left click in the middle of `node`, through the X server."""
    x, y, width, height = node.extents()
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


def windows_of(name):
    """The viewable top windows whose WM_CLASS names `name`, largest first."""
    found = []
    for window in xdisplay.screen().root.query_tree().children:
        try:
            wm_class = window.get_wm_class()
            viewable = window.get_attributes().map_state == X.IsViewable
        except Xlib.error.XError:
            continue
        if wm_class and name in (wm_class[0].lower(), wm_class[1].lower()) and viewable:
            g = window.get_geometry()
            found.append((g.width * g.height, window))
    return [w for _, w in sorted(found, key=lambda f: -f[0])]


def geometry(window):
    g = window.get_geometry()
    return [g.x, g.y, g.width, g.height]


def close(window):
    """Closes `window` as a window manager would (WM_DELETE_WINDOW)."""
    protocols = xdisplay.intern_atom("WM_PROTOCOLS")
    delete = xdisplay.intern_atom("WM_DELETE_WINDOW")
    window.send_event(Xlib.protocol.event.ClientMessage(
        window=window, client_type=protocols, data=(32, [delete, X.CurrentTime, 0, 0, 0])))
    xdisplay.sync()
