"""The GUIs the test runs the panel in, as an operator meets each: how the
machine is turned on in step with it, how the panel's page is brought up,
where the GUI itself shows LinuxCNC's messages, how it is closed."""
import os

import driver
from gi.repository import GLib
import linuxcnc
from desktop import application, click_at, close, geometry, windows_of
from driver import stat, wait_for


class Axis:
    """The panel on the right of AXIS: always in view. AXIS and the driver
    read the same message channel (see said_or_shown)."""
    reads_messages = True

    def gui_up(self):
        pass

    def machine_on(self):
        pass

    def show_panel(self):
        pass

    def window(self):
        return None

    def shows(self, words):
        return []

    def quit(self):
        os.system("axis-remote --quit")


class Gmoccapy:
    """The panel on the right of gmoccapy's main screen (box_right); each
    message in a popup of gmoccapy's."""
    reads_messages = False

    def gui_up(self):
        pass

    def app(self):
        return application("gmoccapy")

    def machine_on(self):
        """Out of estop and on, in step with gmoccapy: its estop and on buttons
        follow the machine's state and, toggled so, send that state again. A
        reset gmoccapy sees only once the machine is on would turn it off; so
        each step waits until gmoccapy's button shows it (over AT-SPI)."""
        wait_for(lambda: self.app() is not None, 120, "gmoccapy over AT-SPI")
        app = self.app()
        estop = app.find_described("toggle button", "Estop the machine")
        on = app.find_described("toggle button", "Turn the machine on")
        if estop is None or on is None:
            raise RuntimeError("gmoccapy's estop or on button not found over AT-SPI")
        # gmoccapy sets its estop button from the machine once its window is up.
        wait_for(lambda: self.window() is not None and estop.checked(), 120, "gmoccapy showing estop")
        driver.command.state(linuxcnc.STATE_ESTOP_RESET)
        wait_for(lambda: stat.task_state == linuxcnc.STATE_ESTOP_RESET and not estop.checked(), 60,
                 "gmoccapy showing the estop reset")
        driver.command.state(linuxcnc.STATE_ON)
        wait_for(lambda: stat.task_state == linuxcnc.STATE_ON and on.checked(), 60,
                 "gmoccapy showing the machine on")

    def show_panel(self):
        pass

    def x_window(self):
        found = windows_of("gmoccapy")
        return found[0] if found else None

    def window(self):
        """gmoccapy's main window on the screen: [x, y, width, height]."""
        window = self.x_window()
        return geometry(window) if window else None

    def shows(self, words):
        """The texts with `words` in gmoccapy's message popups: its windows
        other than the main one (searched whole, that one is large)."""
        window = self.window()
        found = []
        for top in self.app().children():
            x, y, w, h = top.extents()
            if [x, y, w, h] == window or w <= 0:
                continue
            found += [label.label() for label in top.labels() if words in label.label()]
        return found

    def quit(self):
        # gmoccapy then turns the machine off, ends its panel and quits.
        window = self.x_window()
        if window is not None:
            close(window)


class QtDragon:
    """The panel as a page of qtdragon's main area (stackedWidget_mainTab),
    shown by its USER button; messages in its machine log. Its estop and power
    buttons only show the machine's state, so the driver's bring-up turns the
    machine on as a halui button would."""
    reads_messages = False

    def __init__(self, screen):
        self.screen = screen

    def frame(self):
        app = application("qtvcp")
        return app and next((w for w in app.children() if w.label() == "QTvcp-Screen-" + self.screen), None)

    def gui_up(self):
        """qtdragon's window on the screen. Only then may the driver join the
        accessibility bus: where the driver started that bus before Qt had
        joined it, qtvcp never showed up in AT-SPI (4 of 4 runs with the bus
        started first, 1 of about 8 where the driver was quicker)."""
        wait_for(lambda: windows_of("qtvcp"), 120, "%s's window" % self.screen)

    def machine_on(self):
        try:
            wait_for(lambda: self.frame() is not None and self.frame().extents()[2] > 0, 120,
                     "%s's window over AT-SPI" % self.screen)
        except TimeoutError:
            app = application("qtvcp")
            raise TimeoutError("no %s window over AT-SPI; qtvcp's: %s" % (
                self.screen, app and [(w.role(), w.label(), w.extents()) for w in app.children()]))

    def show_panel(self):
        user = self.frame().find("check box", "USER")  # qtdragon's page buttons are checkable
        if user is None:
            raise RuntimeError("%s's USER button (the page of EMBED_TAB_LOCATION = "
                               "stackedWidget_mainTab) not found over AT-SPI" % self.screen)
        click_at(user)

    def window(self):
        x, y, w, h = self.frame().extents()
        return [x, y, w, h]

    def shows(self, words):
        """The lines with `words` in qtdragon's texts: LinuxCNC's messages go
        to its machine log (the STATUS page), and to desktop notifications
        where a notification service runs."""
        found = []
        level = [self.frame()]
        while level:
            below = []
            for node in level:
                for child in node.children():
                    if child.role() == "text":
                        try:
                            found += [line for line in child.text().splitlines() if words in line]
                        except GLib.Error:
                            pass
                    below.append(child)
            level = below
        return found

    def quit(self):
        # With the preference shutdown_check off qtvcp closes without asking.
        for window in windows_of("qtvcp"):
            close(window)


def screen_of(display_command):
    """The GUI of [DISPLAY]DISPLAY: `axis`, `gmoccapy`, `qtvcp qtdragon`, ..."""
    words = display_command.split()
    name = os.path.basename(words[-1] if os.path.basename(words[0]) == "qtvcp" else words[0])
    if name.startswith("qtdragon"):
        return name, QtDragon(name)
    return name, {"axis": Axis, "gmoccapy": Gmoccapy}[name]()
