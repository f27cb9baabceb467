"""GladeVCP handler of fixed_atc_probe's panel (fixed_atc_probe_panel.ui).

Makes the panel's HAL pins, turns button clicks into the pulses the
component's rising-edge inputs want, shows what the changer reports in the
machinist's words, and enables a button only when the component says it can
act. Pocket occupancy comes from the component's state file and config, the
paths named in [FIXED_ATC_PROBE] of the INI."""
import json
import os

import hal
import linuxcnc
from gi.repository import GLib, Gtk

BUTTONS = ("load", "unload", "continue", "cancel", "clear-fault")
# The component polls every 20 ms at most: high and low phases it cannot miss.
PULSE_MS = 100
GAP_MS = 60

# The component's codes (docs/sequences.md#codes), as src/core/status.hpp and
# src/core/step.hpp have them; tests/unit/codes_test.cpp fails when they differ.
# The `state` pin: Phase.
PHASE_NOT_READY = 0
PHASE_IDLE = 1
PHASE_CHANGING = 2
PHASE_LOADING = 3
PHASE_UNLOADING = 4
PHASE_FAULT = 5
# The `awaiting` pin: Awaiting.
AWAITING_NOTHING = 0
AWAITING_MOTION = 1
AWAITING_PROBE = 2
AWAITING_TIMER = 3
AWAITING_SPINDLE = 4
AWAITING_OPERATOR_CHOICE = 5
AWAITING_SENSOR = 6
# The `step-kind` pin: StepKind, those the panel names.
STEP_RAPID = 1
STEP_FEED = 2
STEP_PROBE = 3
STEP_SET_TOOL_LENGTH = 4
STEP_SET_SPINDLE_TOOL = 5

PHASES = {PHASE_NOT_READY: "Machine off, not homed or in estop", PHASE_IDLE: "Idle",
          PHASE_CHANGING: "Changing tool", PHASE_LOADING: "Loading tool",
          PHASE_UNLOADING: "Unloading tool",
          PHASE_FAULT: "FAULT: check spindle and rack, then Clear fault"}
STEP_KINDS = {STEP_RAPID: "rapid", STEP_FEED: "feed", STEP_PROBE: "probing",
              STEP_SET_TOOL_LENGTH: "writing the tool length",
              STEP_SET_SPINDLE_TOOL: "telling LinuxCNC the tool in the spindle"}


def describe_step(kind, x, y, z, inch):
    unit = "in" if inch else "mm"
    if kind in (STEP_RAPID, STEP_FEED, STEP_PROBE):
        return "%s to X%.3f Y%.3f Z%.3f %s (machine)" % (STEP_KINDS[kind], x, y, z, unit)
    return STEP_KINDS.get(kind, "")


def describe_awaiting(awaiting, kind, x, y, z, inch):
    if awaiting == AWAITING_MOTION:
        return describe_step(kind, x, y, z, inch)
    if awaiting == AWAITING_PROBE:
        return "probing the tool length on the touch-off sensor"
    if awaiting == AWAITING_TIMER:
        return "chuck and dwell"
    if awaiting == AWAITING_SPINDLE:
        return "waiting for the spindle to stop"
    if awaiting == AWAITING_OPERATOR_CHOICE:
        return "Waiting for you: see the message, then Continue or Cancel"
    if awaiting == AWAITING_SENSOR:
        return "waiting for a sensor (drawbar, tool present, air, rack)"
    return ""


class Handler:
    def __init__(self, halcomp, builder):
        self.comp = halcomp
        self.builder = builder
        self.pulses = {}
        for name in BUTTONS:
            halcomp.newpin(name, hal.HAL_BIT, hal.HAL_OUT)
            halcomp.newpin(name + "-enabled", hal.HAL_BIT, hal.HAL_OUT)
        halcomp.newpin("tool-number", hal.HAL_S32, hal.HAL_OUT)
        for name in ("state", "awaiting", "tool-in-spindle", "step-kind", "cut-off-pocket"):
            halcomp.newpin(name, hal.HAL_S32, hal.HAL_IN)
        halcomp.newpin("confirm-tool", hal.HAL_S32, hal.HAL_OUT)
        halcomp.newpin("confirm-pocket", hal.HAL_S32, hal.HAL_OUT)
        halcomp["confirm-tool"] = -1
        halcomp["confirm-pocket"] = -1
        for name in ("waiting-for-operator", "accepting", "can-cancel", "units-inch"):
            halcomp.newpin(name, hal.HAL_BIT, hal.HAL_IN)
        for name in ("last-length", "step-x", "step-y", "step-z"):
            halcomp.newpin(name, hal.HAL_FLOAT, hal.HAL_IN)
        self.config_path, self.state_path = self.paths()
        self.state_stamp = None
        self.status_path = self.state_path + ".status" if self.state_path else None
        self.status_stamp = None
        self.status = None
        self.was_faulted = False
        self.pocket_tools = self.read_pockets()
        GLib.timeout_add(100, self.refresh)

    @staticmethod
    def paths():
        """[FIXED_ATC_PROBE]CONFIG and STATE, relative to the INI as halcmd reads them."""
        ini = os.environ.get("INI_FILE_NAME")
        if not ini:
            return None, None
        inifile = linuxcnc.ini(ini)
        folder = os.path.dirname(os.path.abspath(ini))

        def where(key):
            value = inifile.find("FIXED_ATC_PROBE", key)
            return os.path.join(folder, value) if value else None
        return where("CONFIG"), where("STATE")

    def read_pockets(self):
        try:
            with open(self.config_path) as f:
                return sorted(int(tool) for tool in json.load(f)["pockets"])
        except (TypeError, OSError, ValueError, KeyError):
            return []

    def on_tool_number_changed(self, spin):
        self.comp["tool-number"] = spin.get_value_as_int()

    def on_button_clicked(self, button):
        name = Gtk.Buildable.get_name(button)
        if name in self.pulses:
            # Still high from the click before (Continue twice in quick
            # succession): the new click needs a low phase to be an edge.
            GLib.source_remove(self.pulses[name])
            self.comp[name] = False
            self.pulses[name] = GLib.timeout_add(GAP_MS, self.press, name)
        else:
            self.press(name)

    def press(self, name):
        self.comp[name] = True
        self.pulses[name] = GLib.timeout_add(PULSE_MS, self.release, name)
        return False

    def release(self, name):
        self.comp[name] = False
        del self.pulses[name]
        return False

    def refresh(self):
        c = self.comp
        get = self.builder.get_object
        state = c["state"]
        get("state_words").set_text(PHASES.get(state, "state %d" % state))
        status = self.read_status()
        if status is not None:
            # The words themselves: the prompt, the fault, what moves where.
            get("step_words").set_text(status.get("activity", ""))
            # Prompts are the activity already: the last other message.
            said = [m["text"] for m in status.get("messages", []) if m.get("kind") != "prompt"]
            get("said_words").set_text(said[-1] if said else " ")
        else:
            get("step_words").set_text(describe_awaiting(c["awaiting"], c["step-kind"], c["step-x"],
                                                         c["step-y"], c["step-z"], c["units-inch"]))
        self.show_recovery(state == PHASE_FAULT)
        get("spindle_tool").set_text("T%d" % c["tool-in-spindle"] if c["tool-in-spindle"] else "empty")
        length = c["last-length"]
        get("last_length").set_text("%.4f %s" % (length, "in" if c["units-inch"] else "mm") if length else "-")
        self.show_pockets()
        wanted = c["tool-number"] > 0
        enabled = {"load": c["accepting"] and wanted, "unload": c["accepting"] and wanted,
                   "continue": c["waiting-for-operator"], "cancel": c["can-cancel"],
                   "clear-fault": state == PHASE_FAULT}
        for name, on in enabled.items():
            get(name).set_sensitive(bool(on))
            c[name + "-enabled"] = bool(on)
        return True

    def read_status(self):
        """The component's words (STATE.status): None when it cannot be read."""
        try:
            stamp = os.stat(self.status_path).st_mtime_ns
        except (TypeError, OSError):
            return None
        if stamp != self.status_stamp:
            try:
                with open(self.status_path) as f:
                    self.status = json.load(f)
                self.status_stamp = stamp
            except (OSError, ValueError):
                pass  # replaced while read: the next refresh reads it
        return self.status

    def show_recovery(self, faulted):
        """In fault: what the operator confirms before Clear fault."""
        get = self.builder.get_object
        c = self.comp
        if faulted and not self.was_faulted:
            # Offer the last known tool; the operator corrects it if need be.
            get("confirm_tool").set_value(c["tool-in-spindle"])
            get("confirm_pocket").set_active(False)
        self.was_faulted = faulted
        get("recovery").set_visible(faulted)
        pocket = c["cut-off-pocket"]
        get("confirm_pocket").set_visible(faulted and pocket > 0)
        get("confirm_pocket").set_label("Pocket %d holds its tool" % pocket)
        c["confirm-tool"] = get("confirm_tool").get_value_as_int() if faulted else -1
        c["confirm-pocket"] = (1 if get("confirm_pocket").get_active() else 0) if faulted and pocket > 0 else -1

    def show_pockets(self):
        try:
            stamp = os.stat(self.state_path).st_mtime_ns
        except (TypeError, OSError):
            return
        if stamp == self.state_stamp:
            return
        try:
            with open(self.state_path) as f:
                state = json.load(f)
        except (OSError, ValueError):
            return  # caught mid-write: the next refresh reads it
        self.state_stamp = stamp
        full = set(state.get("in_pocket", []))
        lengths = state.get("lengths", {})
        lines = []
        for tool in self.pocket_tools:
            mark = "in pocket" if tool in full else ("in spindle" if tool == state.get("spindle") else "out")
            length = lengths.get(str(tool))
            lines.append("T%-3d %-10s %s" % (tool, mark, "%.4f" % length if length is not None else "not measured"))
        self.builder.get_object("pockets").set_markup("<tt>%s</tt>" % GLib.markup_escape_text("\n".join(lines)))


def get_handlers(halcomp, builder, useropts):
    return [Handler(halcomp, builder)]
