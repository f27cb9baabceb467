#!/usr/bin/python3
"""[DISPLAY]DISPLAY of one LinuxCNC start of the soak (issue 36; soak_run.py
starts LinuxCNC again and again on the same files until the soak is done).

It reads soak_plan.json in LinuxCNC's folder: how many tool changes the whole
soak makes, the seed, which start this is. Then, on the simulated mill with
every sensor wired to the simulated rack (tests/integration/sensors/rack_sim.py,
the physical truth: which holder is where), it runs random programs of M6
over the whole rack (repeats, T0, manual tools handed in and out at
`loading`), operator flows between them (unload, verify the empty pocket,
load; measure all), and injects faults: a tool-present flicker of one servo
period to tens of milliseconds, a drawbar that reports late (past half the
sensor timeout), a grip that never comes (the fault path), E-stop, LinuxCNC's
Stop, the component killed and restarted, LinuxCNC itself stopped (this start
ends; the next one recovers). After each, the operator's recovery as the docs
say it: machine on, look, confirm what the spindle and the cut-off pocket
hold, clear. After every change and every recovery the changer's belief (its
state file, LinuxCNC's tool in spindle, the tool table's lengths) is held
against the truth; a difference the changer did not flag as uncertain is a
mismatch. Everything goes to soak_events.jsonl, one JSON object a line;
soak_report.py reads it.
"""
import json
import os
import random
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "integration",
                                "harness"))
import driver as d  # noqa: E402  (its LinuxCNC channels, HAL helpers, kill and restart)
import hal  # noqa: E402
import linuxcnc  # noqa: E402

P = "fixed_atc_probe."
RACK = "fatc-rack-sim."
PLAN = json.load(open("soak_plan.json"))
# The rack as soak_run.py read it from the config: each pocket and the tool
# it holds at the first start (0 empty); the table's other tools go by hand.
HOME_POCKET = {t: int(p) for p, t in PLAN["rack"].items() if t}
POCKETS = sorted(int(p) for p in PLAN["rack"])
RACK_TOOLS = sorted(HOME_POCKET)
MANUAL_TOOLS = PLAN["manual_tools"]
# Injected into a program at a random moment, with what the operator then does.
FAULTS = ["flicker", "late", "never", "estop", "abort", "kill", "restart_linuxcnc"]
CUTS = ("estop", "abort", "kill", "restart_linuxcnc")  # those that cut a sequence off


class Stopped(Exception):
    """This start ends: LinuxCNC is stopped mid-change (the restart fault)."""


class Soak:
    FAULTS = FAULTS  # the kinds this soak injects: its cycle's, in order

    def __init__(self):
        self.rng = random.Random(PLAN["seed"] * 1000 + PLAN["start"])
        self.events = open("soak_events.jsonl", "a")
        self.changes = PLAN["changes_done"]
        self.last_tool = None
        self.change_began = None  # the changer's state pin went to changing
        self.change_seconds = None
        self.faulted_since_change = False
        self.pending_fault = None
        self.programs = 0
        self.checks = 0
        self.counting = False  # only a program's M6 count; a flow's M61 and a recovery's do not
        self.faults = 0  # injected in this start
        self.fault_active = False  # one was injected in the program under way: its changes are not timed
        self.first_of_program = False  # the next change is a program's first: it starts from anywhere
        self.prompt_serial = None  # the component and status file serial of the last prompt answered

    # ------------------------------------------------------------ record
    def event(self, kind, **details):
        self.events.write(json.dumps({"t": time.time(), "kind": kind, "start": PLAN["start"],
                                      "changes": self.changes, **details}) + "\n")
        self.events.flush()

    def usage(self):
        """The component's resident memory, open files and CPU seconds."""
        pids = d.component_pids()
        if len(pids) != 1:
            return None
        pid = pids[0]
        try:
            status = open("/proc/%d/status" % pid).read()
            rss = int(status.split("VmRSS:")[1].split()[0])
            fds = len(os.listdir("/proc/%d/fd" % pid))
            fields = open("/proc/%d/stat" % pid).read().rsplit(")", 1)[1].split()
            cpu = (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
        except (OSError, IndexError, ValueError):
            return None
        log = "fixed_atc_state.json.log"
        return {"pid": pid, "rss_kib": rss, "fds": fds, "cpu_s": cpu,
                "log_bytes": os.path.getsize(log) if os.path.exists(log) else 0,
                "log_old_bytes": os.path.getsize(log + ".1") if os.path.exists(log + ".1") else 0}

    # ------------------------------------------------------------ watch
    def poll(self):
        d.stat.poll()
        d.drain_errors()
        state = d.pin_value(P + "state")
        now = time.monotonic()
        if state == 2 and self.change_began is None:
            self.change_began = now
        elif state != 2 and self.change_began is not None:
            self.change_seconds = now - self.change_began
            self.change_began = None
        if state == 5:
            self.faulted_since_change = True
        tool = d.stat.tool_in_spindle
        if self.last_tool is None:
            self.last_tool = tool
        elif tool != self.last_tool and not self.counting:
            self.last_tool = tool
        elif tool != self.last_tool:
            self.changes += 1
            clean = not self.faulted_since_change and not self.fault_active
            self.check_change(tool)
            self.event("change", frm=self.last_tool, to=tool, seconds=self.change_seconds,
                       clean=clean, first=self.first_of_program, checked=True,
                       manual=self.last_tool in MANUAL_TOOLS or tool in MANUAL_TOOLS)
            self.last_tool = tool
            self.change_seconds = None
            self.faulted_since_change = False
            self.first_of_program = False
        return state

    def wait(self, condition, timeout, what):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            self.poll()
            fault = self.pending_fault
            if fault and fault["at"] != float("inf") and (
                    self.worst_moment() if fault["at_chuck"] else fault["at"] <= time.monotonic()):
                self.inject()
            if condition():
                return
            time.sleep(0.005)
        raise TimeoutError("timed out waiting for " + what)

    def worst_moment(self):
        """Where half the cuts strike: as the chuck opens, a tool half out."""
        return d.pin_value(P + "chuck")

    # ------------------------------------------------------------ the rack's truth
    def truth(self):
        return {"spindle": d.pin_value(RACK + "spindle-tool"),
                "pockets": {p: d.pin_value(RACK + "pocket-tool-%d" % p) for p in POCKETS}}

    def rack_problems(self, state, truth):
        """Where the state file and the rack disagree. A sequence cut off
        (`uncertain`, or `in_progress` saved) excuses the spindle and the pocket
        it was at, which the changer said it does not know; nothing else."""
        if "unreadable" in state:
            return ["the state file: %s" % state["unreadable"]]
        cut = state.get("in_progress")
        flagged = state.get("uncertain") or cut is not None
        excused = str(cut["pocket"]) if flagged and cut else None
        problems = []
        if state["spindle"] != truth["spindle"] and not flagged:
            problems.append("state spindle T%s, the rack T%s" % (state["spindle"], truth["spindle"]))
        for pocket, entry in state["pockets"].items():
            there = truth["pockets"][int(pocket)]
            believed = entry["tool"] if entry["in_pocket"] else 0
            if believed != there and pocket != excused and not (flagged and there == state["spindle"]):
                problems.append("pocket %s: state T%s, the rack T%s" % (pocket, believed, there))
        return problems

    def check_change(self, tool):
        """Right after a change: the state file's rack and LinuxCNC's new tool against the rack."""
        truth = self.truth()
        problems = self.rack_problems(d.read_json(d.state_path()), truth)
        if tool != truth["spindle"]:
            problems.append("LinuxCNC's tool in spindle T%d, the rack T%s" % (tool, truth["spindle"]))
        self.checks += 1
        if problems:
            self.event("mismatch", where="change %d" % self.changes, what=problems, truth=truth)

    def compare(self, where):
        """The changer's whole belief against the rack, the tool table included."""
        truth = self.truth()
        state = d.read_json(d.state_path())
        problems = self.rack_problems(state, truth)
        if "unreadable" in state:
            self.event("mismatch", where=where, what=problems)
            return
        if state["uncertain"] or state.get("in_progress"):
            self.event("uncertain", where=where, truth=truth)
        # LinuxCNC is told the changer's tool once the changer is idle and task
        # free: in a fault only once the operator said what the spindle holds.
        if d.pin_value(P + "state") != 5:
            try:
                self.wait(lambda: d.stat.tool_in_spindle == truth["spindle"], 10,
                          "LinuxCNC's tool in spindle")
            except TimeoutError:
                problems.append("LinuxCNC's tool in spindle T%d, the rack T%s" % (
                    d.stat.tool_in_spindle, truth["spindle"]))
        table = {t.id: t.zoffset for t in d.stat.tool_table if t.id > 0}
        for tool, length in state["lengths"].items():
            if abs(table.get(int(tool), 0.0) - length) > 1e-3:
                problems.append("T%s: state %.4f, LinuxCNC's table %.4f" % (
                    tool, length, table.get(int(tool), 0.0)))
            if abs(length - PLAN["true_length"]) > PLAN["length_tolerance"]:
                problems.append("T%s measured %.4f, its true length %.4f" % (
                    tool, length, PLAN["true_length"]))
        if problems:
            self.event("mismatch", where=where, what=problems, truth=truth, state=state)
        else:
            self.event("agree", where=where)

    # ------------------------------------------------------------ faults
    def plan_fault(self, program_seconds):
        """Perhaps a fault at a random moment of the next program. A kind that
        the program ended before is tried again by the next (cycle mode)."""
        if PLAN["fault_cycle"]:  # each kind in turn, one a program
            kind = FAULTS[(PLAN["faults_before"] + self.faults) % len(FAULTS)]
        elif self.rng.random() >= PLAN["fault_rate"]:
            return
        else:
            kind = self.rng.choice(FAULTS)
        if kind == "restart_linuxcnc" and not PLAN["restarts_left"]:
            kind = "abort"
        # The last stretch keeps one component process and one LinuxCNC: its
        # memory and files at its 50th change and at its last say whether it leaks.
        if kind in ("kill", "restart_linuxcnc") and self.changes >= PLAN["changes"] - PLAN["quiet_tail"]:
            kind = "abort"
        # Half the cuts at the worst moment: as the chuck opens, a tool half out.
        at = time.monotonic() + self.rng.uniform(0.1, 0.5) * program_seconds
        self.pending_fault = {"kind": kind, "at": at,
                              "at_chuck": kind in CUTS and self.rng.random() < 0.5}
        if kind == "late":  # for the whole program: the drawbar reports past half its timeout
            hal.set_p(RACK + "drawbar-seconds", str(0.6 * PLAN["sensor_timeout"]))
            self.injected(kind, seconds=0.6 * PLAN["sensor_timeout"])
        elif kind == "never":  # the next grip never comes
            hal.set_p(RACK + "grip-fails", "1")
            self.injected(kind)

    def injected(self, kind, **details):
        self.faults += 1
        self.fault_active = True
        self.pending_fault["at"] = float("inf")
        self.event("fault", fault=kind, **details)

    def inject(self):
        kind = self.pending_fault["kind"]
        state = d.pin_value(P + "state")
        if kind == "flicker":
            width = self.rng.choice([0.001, 0.002, 0.005, 0.01, 0.02, 0.05])
            hal.set_p("fatc-flicker.width", str(width))
            hal.set_p("fatc-flicker.in", "1")  # held until the oneshot took the edge
            pulsed = time.monotonic()
            while d.pin_value("fatc-flicker.time-left") <= 0 and time.monotonic() - pulsed < 1:
                if d.pin_value("fatc-flicker.out"):
                    break
                time.sleep(0.0002)
            fired = bool(d.pin_value("fatc-flicker.out") or d.pin_value("fatc-flicker.time-left") > 0)
            hal.set_p("fatc-flicker.in", "0")
            self.injected(kind, width=width, fired=fired, changer_state=state)
        elif kind == "estop":
            d.command.state(linuxcnc.STATE_ESTOP)
            self.injected(kind, changer_state=state, at_chuck=self.pending_fault["at_chuck"])
        elif kind == "abort":
            d.command.abort()
            self.injected(kind, changer_state=state, at_chuck=self.pending_fault["at_chuck"])
        elif kind == "kill":
            pid, _ = d.kill_component()
            self.injected(kind, pid=pid, changer_state=state, at_chuck=self.pending_fault["at_chuck"])
            self.event("restart", report=d.restart_component()["new"])
        elif kind == "restart_linuxcnc":
            self.injected(kind, changer_state=state, at_chuck=self.pending_fault["at_chuck"])
            raise Stopped()

    def end_faults(self):
        """What a fault left set is put back once the program is over."""
        hal.set_p(RACK + "drawbar-seconds", str(PLAN["drawbar_seconds"]))
        hal.set_p(RACK + "grip-fails", "0")
        self.pending_fault = None
        self.fault_active = False

    # ------------------------------------------------------------ the operator
    def press(self, pin):
        hal.set_p(P + pin, "1")
        pressed = time.monotonic()
        self.wait(lambda: time.monotonic() - pressed > 0.1, 5, "the press")  # the component polls at 20 ms
        hal.set_p(P + pin, "0")
        released = time.monotonic()
        self.wait(lambda: time.monotonic() - released > 0.1, 5, "the release")

    def answer_prompt(self):
        """A prompt: the operator puts in or takes out what it asks, then Continue.
        Its words are read once the status file shows this prompt (each prompt is
        said, and its serial counts up), not the one before."""
        self.hand(self.prompt_words())
        self.press("continue")

    def prompt_words(self):
        """The words of the prompt now shown, once the status file has them."""
        status = {}
        pid = d.component_pids()  # a restarted component counts its serials from 0 again

        def shown():
            status.update(d.read_json(d.state_path() + ".status"))
            return (pid, status.get("serial")) != self.prompt_serial and \
                "press continue" in status.get("activity", "").lower()
        self.wait(shown, 10, "the prompt's words in the status file")
        self.prompt_serial = (pid, status["serial"])
        return status.get("activity", "").lower()

    def hand(self, words):
        """What the prompt asks, done by hand on the simulated rack."""
        spindle = d.pin_value(RACK + "spindle-tool")
        if "insert tool " in words and spindle == 0:
            tool = int(words.split("insert tool ")[1].split()[0])
            hal.set_p(RACK + "hand", str(tool))
            self.wait(lambda: d.pin_value(RACK + "spindle-tool") == tool, 5, "the hand-in")
        elif "remove tool " in words and spindle:
            hal.set_p(RACK + "hand", "-1")
            self.wait(lambda: d.pin_value(RACK + "spindle-tool") == 0, 5, "the hand-out")
        hal.set_p(RACK + "hand", "0")

    def recover(self, where, provoked=False):
        """As docs/operating.md#faults says: machine on, look, confirm, clear.
        `provoked`: a fault was injected; a fault without one is the changer's own."""
        d.stat.poll()
        if d.stat.task_state != linuxcnc.STATE_ON or \
                not all(d.stat.homed[i] for i in range(d.stat.joints)):
            d.machine_on()
        self.wait(lambda: d.stat.interp_state == linuxcnc.INTERP_IDLE and
                  d.pin_value(P + "state") in (1, 5) and d.pin_value(P + "awaiting") == 0, 60,
                  "the changer idle or in fault")
        for look in range(3):
            if d.pin_value(P + "state") != 5:
                break
            # The operator looks once the machine stands: a chuck the component
            # left open is closed by its guard within half a second, and may grip
            # the tool again where the spindle stands.
            self.wait(lambda: not d.pin_value("fatc-chuck-guard.chuck") and
                      not d.pin_value(RACK + "drawbar-open"), 10, "the chuck closed")
            self.compare("in fault, before the confirm: " + where)
            truth = self.truth()
            pocket = d.pin_value(P + "cut-off-pocket")
            holds = -1
            if pocket:
                state = d.read_json(d.state_path())
                own = state.get("pockets", {}).get(str(pocket), {}).get("tool", pocket)
                holds = 1 if truth["pockets"].get(pocket) == own else 0
            hal.set_p(P + "confirm-tool", str(truth["spindle"]))
            hal.set_p(P + "confirm-pocket", str(holds))
            self.press("clear-fault")
            # Cleared, the changer compares its sensors with what it was told: a
            # fault again if they disagree, and the operator looks once more.
            self.wait(lambda: d.pin_value(P + "state") in (1, 5) and d.pin_value(P + "awaiting") == 0,
                      60, "the changer idle after the confirm")
            hal.set_p(P + "confirm-tool", "-1")
            hal.set_p(P + "confirm-pocket", "-1")
            self.event("recovery", where=where, spindle=truth["spindle"], pocket=pocket, holds=holds,
                       provoked=provoked, look=look + 1)
        self.compare(where)

    # ------------------------------------------------------------ work
    def program(self):
        # No more than the soak has left to make: it ends on exactly its number.
        n = min(self.rng.randint(3, 12), PLAN["changes"] - self.changes)
        # One manual tool a program, however many the table has besides the rack's.
        manual = MANUAL_TOOLS if len(MANUAL_TOOLS) <= 1 else [self.rng.choice(MANUAL_TOOLS)]
        tools = [self.rng.choice(RACK_TOOLS + RACK_TOOLS + [0] + manual) for _ in range(n)]
        self.programs += 1
        path = os.path.abspath("soak_program_%d.ngc" % (self.programs % 2))
        with open(path, "w") as f:
            f.write("(soak: %s)\nG21 G90\n" % " ".join("T%d" % t for t in tools))
            for t in tools:
                f.write("T%d M6\n" % t)
            f.write("M2\n")
        self.event("program", tools=tools)
        self.plan_fault(PLAN["seconds_per_change"] * n)
        before = self.usage()
        changes = self.changes
        d.start_program(path)
        self.counting = True
        self.first_of_program = True
        self.wait(lambda: d.stat.interp_state != linuxcnc.INTERP_IDLE or
                  d.pin_value(P + "state") != 1, 30, "the program to start")
        deadline = time.monotonic() + 60 * (n + 2)
        while True:
            self.wait(lambda: d.stat.interp_state == linuxcnc.INTERP_IDLE or
                      d.pin_value(P + "waiting-for-operator"), max(deadline - time.monotonic(), 1),
                      "the program or a prompt")
            if d.stat.interp_state == linuxcnc.INTERP_IDLE:
                break
            self.answer_prompt()
        self.counting = False
        after = self.usage()
        if before and after and before["pid"] == after["pid"]:
            self.event("program cpu", cpu_s=after["cpu_s"] - before["cpu_s"],
                       changes=self.changes - changes)
        fault = self.pending_fault
        reached = fault is not None and fault["at"] == float("inf")
        if fault and not reached:
            self.event("fault not reached", fault=fault["kind"])
        self.end_faults()
        self.recover("after a program" + (" with %s" % fault["kind"] if reached else ""),
                     provoked=reached)
        self.event("usage", **(after or {}))

    def operator_flow(self):
        if d.pin_value(P + "tool-in-spindle") in MANUAL_TOOLS:
            return  # the flows refuse to start with a tool of no pocket in the spindle
        choice = self.rng.random()
        if choice < 0.2:
            self.event("operator", flow="measure all")
            hal.set_p(P + "measure-which", "0")
            self.press("measure-all")
            self.wait(lambda: d.pin_value(P + "state") != 1, 30, "measure all to start")
            self.wait(lambda: d.pin_value(P + "state") in (1, 5) and
                      d.stat.interp_state == linuxcnc.INTERP_IDLE, 600, "measure all")
            self.recover("after measure all")
            return
        tool = self.rng.choice(RACK_TOOLS)
        self.event("operator", flow="unload, verify, load", tool=tool)
        hal.set_p(P + "tool-number", str(tool))
        hal.set_p(P + "pocket-number", str(HOME_POCKET[tool]))
        for flow in ("unload", "verify-pocket", "load"):
            self.wait(lambda: d.pin_value(P + "accepting"), 60, "accepting for " + flow)
            self.press(flow)
            self.wait(lambda: d.pin_value(P + "state") != 1, 10, flow + " to start")
            while True:
                self.wait(lambda: d.pin_value(P + "state") in (1, 5) or
                          d.pin_value(P + "waiting-for-operator"), 600, flow)
                if d.pin_value(P + "state") in (1, 5):
                    break
                self.answer_prompt()
            self.recover("after " + flow)

    def run(self):
        # As driver.bring_up, but a start after LinuxCNC was stopped mid-change
        # finds the changer in fault: recover() confirms what the rack holds.
        d.wait_for(lambda: d.stat.task_state in (linuxcnc.STATE_ESTOP, linuxcnc.STATE_ESTOP_RESET,
                                                 linuxcnc.STATE_ON, linuxcnc.STATE_OFF), 120, "task")
        self.event("fault kinds", kinds=self.FAULTS)
        self.recover("at the start", provoked=PLAN["start"] > 1)
        self.event("usage", **(self.usage() or {}))
        while self.changes < PLAN["changes"]:
            if self.rng.random() < PLAN["operator_rate"]:
                self.operator_flow()
            else:
                self.program()
        self.event("usage", **(self.usage() or {}))
        self.event("done")


def main():
    driver = hal.component("fatc-driver")
    driver.ready()
    if PLAN.get("collet_nut"):
        from soak_collet import ColletSoak  # the collet-nut magazine's truth and faults
        soak = ColletSoak()
    else:
        soak = Soak()
    try:
        soak.run()
    except Stopped:
        soak.event("stopping linuxcnc")
    except Exception as e:  # the report says it; LinuxCNC must still shut down
        soak.event("error", what="%s: %s" % (type(e).__name__, e), messages=d.messages[-6:])
    finally:
        soak.event("messages", messages=d.messages)
    subprocess.run(["sync"])


if __name__ == "__main__":
    main()
