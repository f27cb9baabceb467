"""GladeVCP handler of fixed_atc_probe's panel (fixed_atc_probe_panel.ui).

Makes the panel's HAL pins, turns button clicks into the pulses the
component's rising-edge inputs want, shows what the changer reports in the
machinist's words, and enables a button only when the component says it can
act. The Setup page's Teach buttons pulse the component's teach pins, which
write the machine position into config.json; Verify pocket pulses
verify-pocket, a dry run through the pocket's approach. The Touch page pulses
the touch pins (the probe in the spindle finds the pockets and the rack
datum); the status file's `datum`, why the rack datum refuses M6, is shown
in red on top. Measure all pulses
measure-all with the chosen measure-which and shows the batch's progress. The rack (each pocket, its tool, the tool's length, its approach) comes
from the component's state file and config, the paths named in
[FIXED_ATC_PROBE] of the INI; the program loaded in the GUI is checked with
`fixed_atc_probe --lint` in a subprocess, never in the GTK loop."""
import json
import os
import re

import hal
import linuxcnc
from gi.repository import Gio, GLib, Gtk

# Each button pulses the component pin of its name (the button's id in the .ui).
OPERATOR_BUTTONS = ("load", "unload", "continue", "cancel", "clear-fault", "measure-all",
                    "verify-pocket")
# The Setup page: nothing moves, config.json is written.
TEACH_BUTTONS = ("teach-pocket", "teach-loading", "teach-safe", "teach-sensor")
# The Setup page's air runs: a sequence flown above the rack, nothing taken or recorded.
AIR_BUTTONS = ("air-run-change", "air-run-load", "air-run-unload", "air-run-verify")
# The I/O page: each drives one output once (the component's io-check-* pins).
IO_BUTTONS = ("io-check-chuck-release", "io-check-chuck-clamp", "io-check-cover-open",
              "io-check-cover-close", "io-check-air-blast")
# The Touch page: the probe in the spindle touches the rack; config.json is
# written only at the Continue of the prompt that shows what was found.
TOUCH_BUTTONS = ("touch-pockets", "teach-datum", "check-datum", "clear-datum-drift")
PAGE_BUTTONS = TEACH_BUTTONS + IO_BUTTONS + AIR_BUTTONS + TOUCH_BUTTONS
BUTTONS = OPERATOR_BUTTONS + PAGE_BUTTONS
# The component polls every 20 ms at most: high and low phases it cannot miss.
PULSE_MS = 100
GAP_MS = 60

# The component's codes (docs/sequences.md#codes), as src/core/machine/status.hpp and
# src/core/motion/step.hpp have them; tests/unit/protocol/codes_test.cpp fails when they differ.
# The `state` pin: Phase.
PHASE_NOT_READY = 0
PHASE_IDLE = 1
PHASE_CHANGING = 2
PHASE_LOADING = 3
PHASE_UNLOADING = 4
PHASE_FAULT = 5
PHASE_MEASURING = 6
PHASE_VERIFYING = 7
PHASE_CHUCK = 8
PHASE_AIR_RUN = 9
PHASE_TOUCHING = 10
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
STEP_SPINDLE = 9

PHASES = {PHASE_NOT_READY: "Machine off, not homed or in estop", PHASE_IDLE: "Idle",
          PHASE_CHANGING: "Changing tool", PHASE_LOADING: "Loading tool",
          PHASE_UNLOADING: "Unloading tool",
          PHASE_FAULT: "FAULT: check spindle and rack, then Clear fault",
          PHASE_MEASURING: "Measuring tools (Cancel stops after the current one)",
          PHASE_VERIFYING: "Verifying a pocket: Continue at each stop, Cancel stops there",
          PHASE_CHUCK: "Chuck: releasing or clamping for G-code",
          PHASE_AIR_RUN: "Air run: flown above the rack, nothing taken or recorded (Stop ends it)",
          PHASE_TOUCHING: "Touching the rack with the probe: nothing written until Continue"}
# The `measure-which` pin (docs/sequences.md#measure-all): the selector's item ids.
MEASURE_EVERY = 0
MEASURE_NEVER_MEASURED = 1
MEASURE_PROGRAM = 2
# --lint's exit codes (src/io/lint.cpp): clean, problems found, an input unreadable.
LINT_CLEAN = 0
LINT_PROBLEMS = 1
LINT_UNREADABLE = 2
# --lint stops LinuxCNC's interpreter after 15 s (src/io/interpreter.hpp); longer is a hang.
LINT_TIMEOUT_S = 20
# How often the panel asks LinuxCNC which program the GUI has loaded.
PROGRAM_POLL_MS = 500
# Problems the program page lists; the full report has them all.
SHOWN_PROBLEMS = 4
# A pocket's approach when neither it nor pocket_default names one (config.json).
DEFAULT_APPROACH = "side"
SERVED_MARK = "\u25b6 "  # before the served pocket's number: readable, not only a colour
SERVED_BACKGROUND = "#ffd54f"

STEP_KINDS = {STEP_RAPID: "rapid", STEP_FEED: "feed", STEP_PROBE: "probing",
              STEP_SET_TOOL_LENGTH: "writing the tool length",
              STEP_SET_SPINDLE_TOOL: "telling LinuxCNC the tool in the spindle",
              STEP_SPINDLE: "turning the spindle to screw a collet nut"}


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
        return "waiting for the spindle to stop, or to come up to speed over a collet nut"
    if awaiting == AWAITING_OPERATOR_CHOICE:
        return "Waiting for you: see the message, then Continue or Cancel"
    if awaiting == AWAITING_SENSOR:
        return "waiting for a sensor (drawbar, tool present, air, rack)"
    return ""


def read_rack_config(path):
    """config.json's pockets as [(pocket, first-start tool, approach)] by
    pocket number, and its units; ([], "mm") when it cannot be read. The
    first-start tool is the entry's "tool" (0: starts empty), else the pocket's
    own number; "approach" is merged from pocket_default as x/y/z are."""
    try:
        with open(path) as f:
            config = json.load(f)
        default = config.get("pocket_default", {})
        pockets = []
        for key, entry in config["pockets"].items():
            pocket = int(key)
            pockets.append((pocket, int(entry.get("tool", pocket)),
                            str(entry.get("approach", default.get("approach", DEFAULT_APPROACH)))))
        return sorted(pockets), config.get("units", "mm")
    except (TypeError, OSError, ValueError, KeyError, AttributeError):
        return [], "mm"


def rack_contents(pockets, state):
    """{pocket: (tool, sits)}: the tool each pocket is for (0 none) and whether
    it sits there now. Reads the state file's version 1 (pocket N holds tool N
    when N is in in_pocket) and version 2 (pockets: {"P": {"tool", "in_pocket"}});
    no state file (None): every pocket holds its first-start tool."""
    if state is None:
        return {pocket: (first, True) for pocket, first, _ in pockets}
    if state.get("version", 1) >= 2:
        recorded = state.get("pockets", {})
        contents = {}
        for pocket, first, _ in pockets:
            entry = recorded.get(str(pocket))
            if entry is None:  # a pocket added to config.json since: as at first start
                contents[pocket] = (first, True)
            else:
                contents[pocket] = (int(entry.get("tool", 0)), bool(entry.get("in_pocket", False)))
        return contents
    full = set(state.get("in_pocket", []))
    return {pocket: (pocket, pocket in full) for pocket, _, _ in pockets}


def rack_rows(pockets, state, spindle):
    """One row of words per pocket: (pocket, what it holds, length, approach);
    `spindle`: the tools said to be in the spindle (a set)."""
    contents = rack_contents(pockets, state)
    lengths = state.get("lengths", {}) if state else {}
    rows = []
    for pocket, _, approach in pockets:
        tool, sits = contents[pocket]
        if tool == 0:
            holds, length = "empty", ""
        else:
            if sits:
                holds = "T%d" % tool
            elif tool in spindle:
                holds = "T%d (in the spindle)" % tool
            elif state.get("version", 1) >= 2:
                holds = "T%d (out)" % tool  # lost after a fault: the operator says where
            else:
                holds = "empty"  # version 1: its tool was unloaded
            measured = lengths.get(str(tool))
            length = "%.4f" % measured if measured is not None else "never measured"
            if holds == "empty":
                length = ""
        rows.append((pocket, holds, length, approach))
    return rows


def summarize_lint(code, out, err):
    """What the program page shows of a --lint run: a dict of short lines."""
    lines = out.splitlines()
    if code not in (LINT_CLEAN, LINT_PROBLEMS) or not lines:
        said = (err.strip() or out.strip() or "exit code %s" % code).splitlines()
        return {"title": "Cannot check the program", "error": said[0], "problems": 1}
    summary = {"title": lines[-1].strip(), "problems": 0}
    order = []
    for line in lines:
        if line.startswith("tools in the order of the changes:"):
            order = line.split(":", 1)[1].split()
    where, never, never_in_rack, manual = {}, [], [], []
    section = None
    problems, unknown = [], 0
    for line in lines:
        row = re.match(r"^\s*\d+\s+\S+\s+M6 (T\d+)\s+(.*)$", line)
        if row:
            tool, rest = row.groups()
            pocket = re.match(r"pocket (\d+)", rest)
            if tool not in where:
                where[tool] = ("pocket " + pocket.group(1) if pocket
                               else "manual" if rest.startswith("manual")
                               else "refused" if rest.startswith("refused")
                               else None)
            if "never measured" in rest and tool not in never:
                never.append(tool)
            if "never measured" in rest and pocket and tool not in never_in_rack:
                never_in_rack.append(tool)
            if rest.startswith("manual") and tool not in manual:
                manual.append(tool)
            continue
        if line.startswith("problems:"):
            section = "problems"
        elif line.startswith("not known without running the program:"):
            section = "unknown"
        elif not line.startswith("  "):
            section = None
        elif section == "problems":
            problems.append(line.strip())
        elif section == "unknown":
            unknown += 1
        if line.startswith("estimated tool-change time:"):
            summary["time"] = line.split(":", 1)[1].split(", from")[0].strip()
    # The tools the program needs, once each in order of first use: the
    # summary line lists every change, repeats and T0 (an empty spindle) too.
    needed = []
    for tool in order:
        if tool != "T0" and tool not in needed:
            needed.append(tool)
    summary["tools"] = ", ".join("%s (%s)" % (t, where[t]) if where.get(t) else t for t in needed)
    summary["never"] = never
    summary["never_in_rack"] = never_in_rack  # what Measure these offers to measure
    summary["manual"] = manual
    summary["problem_lines"] = problems
    summary["problems"] = len(problems)
    summary["unknown"] = unknown
    return summary


def batch_progress(done, total):
    """batch-done counts the tools measured: the one under way is the next
    (the last stays shown while it goes back). "" when no batch runs."""
    if total <= 0:
        return ""
    return "Measuring tool %d of %d" % (min(done + 1, total), total)


def preflight_lines(summary):
    """The program page's lines from summarize_lint's dict."""
    if "error" in summary:
        return [summary["error"]]
    shown = ["Tools: " + (summary["tools"] or "no tool changes")]
    if summary["manual"]:
        shown.append("Manual: " + " ".join(summary["manual"]))
    shown.append("Never measured: " + (" ".join(summary["never"]) or "none"))
    if "time" in summary:
        shown.append("Change time: " + summary["time"])
    if summary["unknown"]:
        shown.append("Not known before running: %d (see the report)" % summary["unknown"])
    problems = summary["problem_lines"]
    for line in problems[:SHOWN_PROBLEMS]:
        shown.append("Problem: " + line)
    if len(problems) > SHOWN_PROBLEMS:
        shown.append("... and %d more problems (see the report)" % (len(problems) - SHOWN_PROBLEMS))
    return shown


class Handler:
    def __init__(self, halcomp, builder):
        self.comp = halcomp
        self.builder = builder
        self.pulses = {}
        for name in BUTTONS:
            halcomp.newpin(name, hal.HAL_BIT, hal.HAL_OUT)
            halcomp.newpin(name + "-enabled", hal.HAL_BIT, hal.HAL_OUT)
        halcomp.newpin("tool-number", hal.HAL_S32, hal.HAL_OUT)
        halcomp.newpin("pocket-number", hal.HAL_S32, hal.HAL_OUT)
        halcomp.newpin("measure-which", hal.HAL_S32, hal.HAL_OUT)
        halcomp.newpin("rack-keepout-lift", hal.HAL_BIT, hal.HAL_OUT)
        halcomp.newpin("air-height", hal.HAL_FLOAT, hal.HAL_OUT)
        halcomp.newpin("air-feed", hal.HAL_FLOAT, hal.HAL_OUT)
        halcomp.newpin("air-from-tool", hal.HAL_S32, hal.HAL_OUT)
        halcomp["air-from-tool"] = -1
        halcomp.newpin("io-check-holding-tool", hal.HAL_BIT, hal.HAL_OUT)
        halcomp.newpin("step-by-step", hal.HAL_BIT, hal.HAL_OUT)
        for name in ("state", "awaiting", "tool-in-spindle", "step-kind", "cut-off-pocket",
                     "pocket-served", "batch-done", "batch-total"):
            halcomp.newpin(name, hal.HAL_S32, hal.HAL_IN)
        halcomp.newpin("confirm-tool", hal.HAL_S32, hal.HAL_OUT)
        halcomp.newpin("confirm-pocket", hal.HAL_S32, hal.HAL_OUT)
        halcomp["confirm-tool"] = -1
        halcomp["confirm-pocket"] = -1
        for name in ("waiting-for-operator", "accepting", "can-cancel", "units-inch", "chuck-held"):
            halcomp.newpin(name, hal.HAL_BIT, hal.HAL_IN)
        for name in ("last-length", "step-x", "step-y", "step-z"):
            halcomp.newpin(name, hal.HAL_FLOAT, hal.HAL_IN)
        self.ini_path = os.environ.get("INI_FILE_NAME")
        self.config_path, self.state_path, self.tool_table_path = self.paths(self.ini_path)
        self.state_stamp = None
        self.state = None
        self.status_path = self.state_path + ".status" if self.state_path else None
        self.status_stamp = None
        self.status = None
        self.was_faulted = False
        self.pockets, self.units = read_rack_config(self.config_path)
        self.rack_cells = self.make_rack()
        self.rack_shown = None
        self.linuxcnc_stat = linuxcnc.stat()
        self.lint_key = None  # what the shown preflight was made from
        self.lint_run = None  # (subprocess, its timeout source) while one runs
        self.never_in_rack = []  # the preflight's never-measured tools that sit in the rack
        GLib.timeout_add(100, self.refresh)
        GLib.timeout_add(PROGRAM_POLL_MS, self.watch_program)

    @staticmethod
    def paths(ini):
        """[FIXED_ATC_PROBE]CONFIG and STATE and [EMCIO]TOOL_TABLE, relative to
        the INI as halcmd and LinuxCNC read them."""
        if not ini:
            return None, None, None
        inifile = linuxcnc.ini(ini)
        folder = os.path.dirname(os.path.abspath(ini))

        def where(section, key):
            value = inifile.find(section, key)
            return os.path.join(folder, value) if value else None
        return (where("FIXED_ATC_PROBE", "CONFIG"), where("FIXED_ATC_PROBE", "STATE"),
                where("EMCIO", "TOOL_TABLE"))

    def on_tool_number_changed(self, spin):
        self.comp["tool-number"] = spin.get_value_as_int()

    def on_pocket_number_changed(self, spin):
        pocket = spin.get_value_as_int()
        self.comp["pocket-number"] = pocket
        self.builder.get_object("teach-pocket").set_label(
            "Teach pocket %d" % pocket if pocket > 0 else "Teach pocket")
        self.builder.get_object("verify-pocket").set_label(
            "Verify pocket %d" % pocket if pocket > 0 else "Verify pocket")
        self.builder.get_object("touch-pockets").set_label(
            "Touch pocket %d" % pocket if pocket > 0 else "Touch all pockets")

    def on_measure_which_changed(self, combo):
        self.comp["measure-which"] = int(combo.get_active_id() or MEASURE_EVERY)

    def on_measure_these_clicked(self, _button):
        """The program page's offer: Measure all with the program's tools (those
        in the rack; the component skips the others and says so)."""
        self.builder.get_object("measure_which").set_active_id(str(MEASURE_PROGRAM))
        self.on_button_clicked(self.builder.get_object("measure-all"))

    def on_air_height_changed(self, spin):
        self.comp["air-height"] = spin.get_value()

    def on_air_feed_changed(self, spin):
        self.comp["air-feed"] = spin.get_value()

    def on_air_from_tool_changed(self, spin):
        self.comp["air-from-tool"] = spin.get_value_as_int()

    def on_keepout_lift_toggled(self, button):
        self.comp["rack-keepout-lift"] = button.get_active()

    def on_holding_tool_toggled(self, button):
        self.comp["io-check-holding-tool"] = button.get_active()

    def on_step_by_step_toggled(self, button):
        # A level the component takes at the start of each sequence: the words of each
        # held step are the activity the panel shows (step_words).
        self.comp["step-by-step"] = button.get_active()

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
        words = PHASES.get(state, "state %d" % state)
        if state == PHASE_IDLE and c["chuck-held"]:
            words = "Chuck held open (G-code, or the I/O page): no motion, no spindle until it is clamped"
        get("state_words").set_text(words)
        status = self.read_status()
        if status is not None:
            # The words themselves: the prompt, the fault, what moves where.
            get("step_words").set_text(status.get("activity", ""))
            # Prompts are the activity already: the last other message.
            said = [m["text"] for m in status.get("messages", []) if m.get("kind") != "prompt"]
            get("said_words").set_text(said[-1] if said else " ")
            get("keepout_words").set_text(status.get("keepout", " "))
            # The measuring rule of the tool the change is about, or the spindle's:
            # "T3 checked ±0.05", "T99 probe, spindle held, measured if new".
            get("rule_words").set_text(status.get("rule") or " ")
        else:
            get("step_words").set_text(describe_awaiting(c["awaiting"], c["step-kind"], c["step-x"],
                                                         c["step-y"], c["step-z"], c["units-inch"]))
        # Why M6 is refused, on the first page: a drift found or a check due.
        datum = (status or {}).get("datum") or ""
        get("datum_words").set_text("M6 refused: " + datum if datum else " ")
        get("datum_words").set_visible(bool(datum))
        self.show_recovery(state == PHASE_FAULT)
        get("spindle_tool").set_text("T%d" % c["tool-in-spindle"] if c["tool-in-spindle"] else "empty")
        length = c["last-length"]
        get("last_length").set_text("%.4f %s" % (length, "in" if c["units-inch"] else "mm") if length else "-")
        self.show_rack()
        progress = batch_progress(c["batch-done"], c["batch-total"])
        get("batch_progress").set_text(progress)
        get("batch_progress").set_visible(bool(progress))
        get("measure_these").set_visible(bool(self.never_in_rack))
        get("measure_these").set_sensitive(bool(self.never_in_rack) and c["accepting"])
        # Each input read once: every button of one refresh sees the same changer.
        accepting = c["accepting"]
        wanted = c["tool-number"] > 0
        pocket = c["pocket-number"] > 0
        # A teach while a program or MDI runs would take the position of a
        # moving machine: only when Load could start (idle, task free).
        teach = accepting
        enabled = {"load": accepting and wanted, "unload": accepting and wanted,
                   "continue": c["waiting-for-operator"], "cancel": c["can-cancel"],
                   "clear-fault": state == PHASE_FAULT, "measure-all": accepting,
                   "teach-pocket": teach and pocket, "teach-loading": teach,
                   "verify-pocket": accepting and pocket,
                   "teach-safe": teach, "teach-sensor": teach}
        flies = accepting and c["air-height"] > 0
        enabled.update({"air-run-change": flies and wanted, "air-run-load": flies and wanted,
                        "air-run-unload": flies and wanted, "air-run-verify": flies and pocket})
        # Each touch moves the machine: only when Load could start. Clear datum
        # only while the datum refuses M6: otherwise the component has nothing to clear.
        enabled.update({"touch-pockets": accepting, "teach-datum": accepting,
                        "check-datum": accepting, "clear-datum-drift": accepting and bool(datum)})
        enabled.update(self.show_io_check(status))
        for name, on in enabled.items():
            get(name).set_sensitive(bool(on))
        # The pins after the screen, Load and Continue last: a reader that
        # waits for either finds the others of the same refresh already set.
        for name in sorted(enabled, key=lambda name: (name == "load", name == "continue")):
            c[name + "-enabled"] = bool(enabled[name])
        return True

    def show_io_check(self, status):
        """The I/O page: the sensor lines, why each refused output is refused,
        the last answer; which of its buttons may be pressed."""
        get = self.builder.get_object
        io = (status or {}).get("io_check") or {}
        get("io_sensors").set_text("\n".join(io.get("sensors", [])) or "no sensor wired")
        refusals = io.get("refusals", {})
        get("io_refusals").set_text("\n".join(
            "%s: %s" % (get(button).get_label(), refusals[button[len("io-check-"):]])
            for button in IO_BUTTONS if refusals.get(button[len("io-check-"):])) or " ")
        get("io_last").set_text(io.get("last") or " ")
        # No words from the component (not started yet): nothing to press.
        return {button: bool(refusals) and not refusals.get(button[len("io-check-"):])
                for button in IO_BUTTONS}

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

    def make_rack(self):
        """The rack page's grid: a header and one row of labels per pocket."""
        grid = self.builder.get_object("rack")
        header = ("Pocket", "Tool", "Length (%s)" % ("in" if self.units == "inch" else "mm"), "Approach")
        rows = [header] + [(str(pocket), "", "", "") for pocket, _, _ in self.pockets]
        if not self.pockets:
            rows.append(("-", "config.json not read", "", ""))
        cells = []
        for top, row in enumerate(rows):
            labels = []
            for left, text in enumerate(row):
                label = Gtk.Label(label=text, xalign=0, visible=True)
                if top == 0:
                    label.set_markup("<b>%s</b>" % GLib.markup_escape_text(text))
                grid.attach(label, left, top, 1, 1)
                labels.append(label)
            cells.append(labels)
        return cells[1:]

    def read_state(self):
        """The state file into self.state when it changed (None: not written yet)."""
        try:
            stamp = os.stat(self.state_path).st_mtime_ns
        except (TypeError, OSError):
            if self.state_stamp != "missing":
                self.state, self.state_stamp = None, "missing"
            return
        if stamp == self.state_stamp:
            return
        try:
            with open(self.state_path) as f:
                self.state = json.load(f)
            self.state_stamp = stamp
        except (OSError, ValueError):
            pass  # caught mid-write: the next refresh reads it

    def show_rack(self):
        """Each pocket with its tool, length and approach; the pocket being
        served during a change highlighted, the cut-off one in fault marked."""
        c = self.comp
        self.read_state()
        busy = c["state"] in (PHASE_CHANGING, PHASE_LOADING, PHASE_UNLOADING, PHASE_MEASURING,
                              PHASE_VERIFYING)
        served = c["pocket-served"] or (self.status or {}).get("pocket", 0)
        if not served and busy and self.state:
            # What the sequence under way recorded before it moved.
            served = (self.state.get("in_progress") or {}).get("pocket", 0)
        cut_off = c["cut-off-pocket"] if c["state"] == PHASE_FAULT else 0
        uncertain = bool(self.state and self.state.get("uncertain"))
        # A tool out of its pocket is in the spindle when the component's pin,
        # the state file or LinuxCNC says so: in the load flow LinuxCNC is told
        # at the insertion (M61), the pin and the file with the flow's end.
        try:
            told = self.linuxcnc_stat.tool_in_spindle  # polled by watch_program
        except (AttributeError, linuxcnc.error):
            told = 0
        spindle = frozenset({c["tool-in-spindle"], (self.state or {}).get("spindle", 0), told}) - {0}
        key = (self.state_stamp, served, cut_off, uncertain, spindle)
        if key == self.rack_shown or not self.pockets:
            return
        self.rack_shown = key
        try:
            rows = rack_rows(self.pockets, self.state, spindle)
        except (TypeError, ValueError, AttributeError):
            return  # a state file the component would refuse: it says so itself
        for labels, (pocket, holds, length, approach) in zip(self.rack_cells, rows):
            mark, background = "", None
            if pocket == served:
                mark, background = SERVED_MARK, SERVED_BACKGROUND
            elif pocket == cut_off:
                mark, background = "? ", "#ff8a65"
            texts = (mark + str(pocket), holds, length, approach)
            for label, text in zip(labels, texts):
                text = GLib.markup_escape_text(text)
                if background:
                    text = '<span background="%s" weight="bold">%s</span>' % (background, text)
                label.set_markup(text)
        note = self.builder.get_object("rack_note")
        note.set_text("Uncertain: look at the spindle and the rack" if uncertain else "")
        note.set_visible(uncertain)

    def watch_program(self):
        """Starts a preflight when the GUI's program, the state file, the tool
        table or the config changed; not while a program runs (the preflight
        is about its start)."""
        try:
            self.linuxcnc_stat.poll()
            program = self.linuxcnc_stat.file
            running = self.linuxcnc_stat.interp_state != linuxcnc.INTERP_IDLE
        except linuxcnc.error:
            return True
        if running or self.lint_run is not None:
            return True

        def stamp(path):
            try:
                return os.stat(path).st_mtime_ns
            except (TypeError, OSError):
                return None
        key = (program, stamp(program), self.state_stamp, stamp(self.tool_table_path),
               stamp(self.config_path))
        if key != self.lint_key:
            self.lint_key = key
            self.start_lint(program)
        return True

    def start_lint(self, program):
        """fixed_atc_probe --lint over the program, found on the PATH as the
        HAL file's loadusr finds the component; its end arrives in lint_done."""
        self.never_in_rack = []  # nothing to offer until this program is checked
        if not program:
            self.show_preflight("No program loaded", [], "")
            return
        binary = GLib.find_program_in_path("fixed_atc_probe")
        if not binary or not self.config_path:
            self.show_preflight("Cannot check the program",
                                ["fixed_atc_probe is not on the PATH" if not binary
                                 else "no [FIXED_ATC_PROBE]CONFIG in the INI"], "", trouble=True)
            return
        argv = [binary, "--lint", program, "--config", self.config_path, "--state", self.state_path,
                "--ini", self.ini_path]
        if self.tool_table_path:
            argv += ["--tool-table", self.tool_table_path]
        self.show_preflight("Checking %s ..." % os.path.basename(program), [], "")
        try:
            process = Gio.Subprocess.new(argv, Gio.SubprocessFlags.STDOUT_PIPE |
                                         Gio.SubprocessFlags.STDERR_PIPE)
        except GLib.Error as e:
            self.show_preflight("Cannot check the program", [e.message], "", trouble=True)
            return
        timeout = GLib.timeout_add_seconds(LINT_TIMEOUT_S, self.lint_timed_out, process)
        self.lint_run = (process, timeout, program, [False])
        process.communicate_async(None, None, self.lint_done, None)

    def lint_timed_out(self, process):
        if self.lint_run and self.lint_run[0] is process:
            self.lint_run[3][0] = True
            process.force_exit()
        return False

    def lint_done(self, process, result, _data):
        if not self.lint_run or self.lint_run[0] is not process:
            return
        _, timeout, program, timed_out = self.lint_run
        self.lint_run = None
        if not timed_out[0]:
            GLib.source_remove(timeout)
        try:
            _, out, err = process.communicate_finish(result)
        except GLib.Error as e:
            self.show_preflight("Cannot check the program", [e.message], "", trouble=True)
            return

        def text(data):
            # Without the program's folder (AXIS's temporary copy): the names are enough.
            words = data.get_data().decode("utf-8", "replace") if data else ""
            return words.replace(os.path.dirname(program) + "/", "")
        if timed_out[0]:
            self.show_preflight("Cannot check the program",
                                ["fixed_atc_probe --lint took over %d s: stopped" % LINT_TIMEOUT_S],
                                "", trouble=True)
            return
        code = process.get_exit_status() if process.get_if_exited() else None
        summary = summarize_lint(code, text(out), text(err))
        self.never_in_rack = summary.get("never_in_rack", [])
        self.show_preflight(summary["title"], preflight_lines(summary), text(out) + text(err),
                            trouble=summary["problems"] > 0)

    def show_preflight(self, title, lines, report, trouble=False):
        get = self.builder.get_object
        get("preflight_title").set_text(title)
        get("preflight_lines").set_text("\n".join(lines))
        get("preflight_lines").set_visible(bool(lines))
        get("preflight_report").set_text(report)
        get("preflight_more").set_visible(bool(report))
        get("program_tab").set_text("Program \u26a0" if trouble else "Program")


def get_handlers(halcomp, builder, useropts):
    return [Handler(halcomp, builder)]
