#!/usr/bin/python3
"""[DISPLAY]DISPLAY of the fault-matrix runs on the real LinuxCNC.

An M6 between two rack tools is cut off at each step where it waits (a move
the executor performs, a dwell the component times) by an estop, LinuxCNC's
Stop (abort), or the component killed with SIGKILL and restarted; with
FATC_MATRIX_MODE=restart, LinuxCNC itself is stopped at the step (its realtime
threads at once, the rest as LinuxCNC shuts down) and the next
start checks what it finds. After each cut the run records what LinuxCNC and
the component report: the chuck, the fault, the files, the refusals; then the
operator confirms what a machinist would find (the model below) and the run
records that LinuxCNC and the changer agree. fault_matrix_check.py judges.

Environment: FATC_RESULTS (JSON written here), FATC_MATRIX_KINDS (comma list,
default estop,abort,kill), FATC_MATRIX_MODE (matrix | restart),
FATC_MATRIX_STEPS (comma list of step numbers, "none", or unset: every step
that waits); FATC_MATRIX_<KIND>_STEPS, e.g. FATC_MATRIX_HOLD_STEPS (the steps
of that column, if not those); FATC_MATRIX_SPINDLE (non-empty: the spindle case too); FATC_MATRIX_PENDING (restart mode: the case the last start cut).

A collet-nut config (`"chuck": {"kind": "collet_nut"}`, config/sim/sim_nut.hal
loaded): what the machinist finds is the simulated magazine's (harness/sim_nut.py),
read once the cut settled, and every cut also waits for the spindle to stand.
"""
import json
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
import driver as d  # noqa: E402  (shares its LinuxCNC channels and HAL helpers)
import hal  # noqa: E402
import linuxcnc  # noqa: E402
import sim_nut  # noqa: E402

P = d.COMPONENT + "."
FIRST, SECOND = 1, 2  # adjacent pockets: the change between them is short
OTHER = 3             # what the refused M6 asks for
COLLET = []           # [the config's pockets] on a collet-nut magazine, empty on a drawbar's


def pin(name):
    return d.pin_value(name)


def plan(config):
    """--plan of the change: [(number, kind, what)], as the step-number pin counts."""
    out = subprocess.run(["fixed_atc_probe", "--plan", "--from", str(FIRST), "--to", str(SECOND),
                          "--config", config], capture_output=True, text=True, timeout=60)
    steps = []
    for line in out.stdout.splitlines()[1:]:
        words = line.split(None, 2)
        if len(words) >= 2 and words[0].isdigit():
            steps.append((int(words[0]), words[1], words[2].strip() if len(words) > 2 else ""))
    if not steps:
        raise RuntimeError("--plan printed no steps: %s %s" % (out.stdout, out.stderr))
    if COLLET:
        # --plan prints each wait for at-speed and zero-speed as a dwell row;
        # the live step-number counts none of them (it stays on the spindle
        # step): numbered as it does.
        steps = [(n + 1, kind, what) for n, (_, kind, what) in
                 enumerate(s for s in steps if s[1] != "dwell")]
    return steps


def truth(steps, at, held):
    """What a machinist finds after a change from `held` cut off at step `at`:
    the tool leaves the spindle when the chuck first opens (in its pocket), and
    the next is held only once the chuck closed on it in its pocket (the last
    close). Returns (spindle, {pocket: holds its tool})."""
    target = SECOND if held == FIRST else FIRST
    opens = [n for n, kind, what in steps if kind == "chuck" and what.startswith("open")]
    closes = [n for n, kind, what in steps if kind == "chuck" and what.startswith("close")]
    if at < opens[0]:
        return held, {held: False, target: True}
    if at < closes[-1]:
        return 0, {held: True, target: True}
    return target, {held: True, target: False}


def what_the_operator_says(steps, at, case):
    """What a machinist finds (truth), and then says: where the spindle is
    empty they put tool 1 into it by hand first, from its pocket, so that the
    next case starts without a fetch."""
    if COLLET:
        return what_the_operator_finds_on_the_magazine(case)
    spindle, pockets = truth(steps, at, case["from"])
    if spindle == 0:
        spindle, pockets = FIRST, dict(pockets, **{str(FIRST): False})
        pockets = {int(k): v for k, v in pockets.items()}
    return spindle, pockets


def what_the_operator_finds_on_the_magazine(case):
    """A collet-nut magazine: the nuts where the simulated magazine has them
    (a nut from pocket N is tool N). An empty spindle gets tool 1's nut
    screwed on by hand from pocket 1, a nut left hanging low is screwed home."""
    found = sim_nut.truth(COLLET)
    case["found"] = found
    if found["spindle"] == 0:
        sim_nut.put_in_pocket(FIRST, False)
        sim_nut.screw_on_by_hand(FIRST)
    elif not found["seated"]:
        sim_nut.screw_on_by_hand(found["spindle"])
    now = sim_nut.truth(COLLET)
    return now["spindle"], now["pockets"]


def program(name, text):
    path = os.path.join(d.ini_dir(), name)
    with open(path, "w") as f:
        f.write(text)
    return path


def run_program(path, timeout=120, each=lambda: None):
    """Runs a program to its end, `each()` at every look at it; returns the
    messages it produced."""
    first = len(d.messages)
    d.wait_for(lambda: d.stat.interp_state == linuxcnc.INTERP_IDLE, 60, "task free")
    d.start_program(path)  # an absolute path: the driver's join keeps it
    began = time.monotonic()
    seen = []

    def ended():
        each()
        if d.stat.interp_state != linuxcnc.INTERP_IDLE:
            seen.append(True)
        return d.stat.interp_state == linuxcnc.INTERP_IDLE and (seen or time.monotonic() - began > 2)
    d.wait_for(ended, timeout, "the program %s to end" % path)
    d.wait_for(lambda: not hal.get_value("iocontrol.0.tool-change"), 10, "tool-change low")
    return d.messages[first:]


def change_to(tool):
    run_program(program("fatc_matrix_t%d.ngc" % tool, "T%d M6\nM2\n" % tool))
    d.wait_for(lambda: pin(P + "state") == 1 and pin(P + "tool-in-spindle") == tool, 30,
               "the changer idle with T%d" % tool)


def files():
    return {"state_file": d.read_json(d.state_path()),
            "status_file": d.read_json(d.state_path() + ".status"),
            "tool_table": open(os.path.join(d.ini_dir(), "sim.tbl")).read()}


def cut(kind, at, steps, case):
    """Runs the change and strikes when the step-number pin shows `at`."""
    held = pin(P + "tool-in-spindle")
    target = SECOND if held == FIRST else FIRST
    case.update({"from": held, "to": target})
    if kind == "kill":
        # The last kill's process may still be on its way out.
        d.wait_for(lambda: len(d.component_pids()) == 1, 10, "one component process")
    first = len(d.messages)
    d.start_program(program("fatc_matrix_t%d.ngc" % target, "T%d M6\nM2\n" % target))
    began = time.monotonic()
    deadline = began + 120
    seen = []  # the steps the change went through, for the error
    while time.monotonic() < deadline:
        d.stat.poll()
        d.drain_errors()
        step = pin(P + "step-number")
        if step == at:
            break
        if not seen or seen[-1][0] != step:
            seen.append((step, round(d.stat.actual_position[2], 1)))
        if d.stat.interp_state == linuxcnc.INTERP_IDLE and time.monotonic() - began > 2:
            raise RuntimeError("the change ended before step %d (steps %s, messages %s)" % (
                at, seen, d.messages[first:]))
        time.sleep(0.001)
    else:
        raise TimeoutError("step %d never came (steps %s)" % (at, seen))
    case["struck_at"] = {"t": time.monotonic() - began, "steps_before": seen, "pos": list(d.stat.actual_position[:3]),
                         "chuck": pin("fatc-chuck-guard.chuck"), "awaiting": pin(P + "awaiting"),
                         "step_ready": pin(P + "step-ready"), "step_request": pin(P + "step-request")}
    struck = time.monotonic()
    if kind == "estop":
        d.command.state(linuxcnc.STATE_ESTOP)
    elif kind == "abort":
        d.command.abort()
    elif kind == "kill":
        d.kill_component()
    return struck, first


def settle(kind, struck, case):
    """Waits for what the cut must lead to, timing the chuck and the program."""
    def since():
        return time.monotonic() - struck
    d.wait_for(lambda: not pin("fatc-chuck-guard.chuck"), 10, "the chuck closed")
    case["chuck_closed_after"] = since()
    d.wait_for(lambda: d.stat.interp_state == linuxcnc.INTERP_IDLE, 30, "the program stopped")
    case["program_stopped_after"] = since()
    if COLLET:
        spindle_stands(case, since)
    if kind == "kill":
        case["restart"] = {k: v for k, v in d.restart_component().items()
                           if k in ("load_seconds", "registered_after_hal_exit")}
        d.wait_for(lambda: pin("fatc-chuck-guard.alive"), 30, "the restarted component's heartbeat")
    if kind == "estop":
        case["task_state_after"] = d.stat.task_state
        d.machine_on()
    d.wait_for(lambda: pin(P + "fault"), 30, "the changer faulted")
    d.wait_for(lambda: not hal.get_value("iocontrol.0.tool-change"), 10, "tool-change low")


def spindle_stands(case, since):
    """A collet nut's cut: the spindle must stand within 10 s. Where it does
    not, what turns it is recorded, and the operator presses Stop once the
    case has looked again after the component's restart (after_cut)."""
    try:
        d.wait_for(sim_nut.spindle_still, 10, "the spindle to stand")
        case["spindle_stopped_after"] = since()
    except TimeoutError:
        d.stat.poll()
        case["spindle_stopped_after"] = None
        case["spindle_turning"] = {"after": since(), "pins": sim_nut.spindle_now(),
                                   "linuxcnc": d.stat.spindle[0]}


def after_cut(messages):
    """What LinuxCNC and the component say once a cut has settled."""
    said = {"fault": pin(P + "fault"), "state": pin(P + "state"),
            "chuck": pin("fatc-chuck-guard.chuck"), "linuxcnc_tool": d.stat.tool_in_spindle,
            "changer_tool": pin(P + "tool-in-spindle"), "cut_off_pocket": pin(P + "cut-off-pocket"),
            "files": files(), "messages": messages}
    if COLLET:
        said["spindle"] = dict(sim_nut.spindle_now(), changer_spindle=pin(P + "changer-spindle"))
        if not sim_nut.spindle_still():
            d.command.abort()  # the operator stops what still turns, for the next case
            d.wait_for(sim_nut.spindle_still, 10, "the spindle to stand after Stop")
    return said


def observe_refusals(case):
    """Faulted: M6 and the operator flows are refused with a message; nothing moves."""
    # The position now, not at the last poll: d.machine_on() may have homed since
    # (the estop column failed on master with the old poll as its baseline).
    d.stat.poll()
    before = list(d.stat.actual_position[:3])
    said = run_program(program("fatc_matrix_refused.ngc", "T%d M6\nM2\n" % OTHER), 60)
    first = len(d.messages)
    hal.set_p(P + "tool-number", "4")
    hal.set_p(P + "load", "1")
    d.wait_for(lambda: any("refused" in m for m in d.messages[first:]), 10, "the load refusal")
    hal.set_p(P + "load", "0")
    d.stat.poll()
    case["refusal"] = {"m6_messages": said, "load_messages": d.messages[first:],
                       "moved": max(abs(a - b) for a, b in zip(before, d.stat.actual_position[:3])),
                       "fault_after": pin(P + "fault"), "state_after": pin(P + "state")}


def confirm(spindle, pockets, case):
    """The operator says what they found, then presses Clear fault."""
    cut_off = pin(P + "cut-off-pocket")
    hal.set_p(P + "confirm-tool", str(spindle))
    hal.set_p(P + "confirm-pocket", str(-1 if not cut_off else int(pockets.get(cut_off, True))))
    hal.set_p(P + "clear-fault", "1")
    pressed = time.monotonic()
    d.wait_for(lambda: time.monotonic() - pressed > 0.1, 5, "the press")
    hal.set_p(P + "clear-fault", "0")
    d.wait_for(lambda: pin(P + "state") == 1, 30, "the changer idle after the confirm")
    d.wait_for(lambda: d.stat.tool_in_spindle == spindle, 30, "LinuxCNC told the confirmed tool")
    hal.set_p(P + "confirm-tool", "-1")
    hal.set_p(P + "confirm-pocket", "-1")
    case["confirmed"] = {"spindle": spindle, "cut_off_pocket": cut_off,
                         "pocket_holds_tool": pockets.get(cut_off) if cut_off else None,
                         "linuxcnc_tool": d.stat.tool_in_spindle,
                         "changer_tool": pin(P + "tool-in-spindle"), "files": files()}
    if COLLET:
        case["confirmed"]["found"] = sim_nut.truth(COLLET)


def prepare():
    """A rack tool in the spindle, the changer idle."""
    d.wait_for(lambda: pin(P + "state") in (1, 5), 60, "the changer up")
    if pin(P + "tool-in-spindle") not in (FIRST, SECOND):
        change_to(FIRST)


def run_case(kind, at, steps):
    case = {"kind": kind, "step": at, "what": next(s for s in steps if s[0] == at)[1:]}
    try:
        began = time.monotonic()
        prepare()
        case["seconds"] = {"prepare": time.monotonic() - began}
        struck, first = cut(kind, at, steps, case)
        case["seconds"]["cut"] = time.monotonic() - began
        settle(kind, struck, case)
        case["seconds"]["settle"] = time.monotonic() - began
        case["after_cut"] = after_cut(d.messages[first:])
        observe_refusals(case)
        case["seconds"]["refusals"] = time.monotonic() - began
        spindle, pockets = what_the_operator_says(steps, at, case)
        confirm(spindle, pockets, case)
        case["seconds"]["confirm"] = time.monotonic() - began
    except Exception as e:  # the checker reports it; the next case starts afresh
        went_wrong(case, e)
    return case


def went_wrong(case, error):
    """Records what failed and brings the machine back for the next case."""
    case["error"] = "%s: %s" % (type(error).__name__, error)
    try:
        recover()
    except Exception as again:
        case["recover_error"] = "%s: %s" % (type(again).__name__, again)


def recover():
    """After a case that went wrong: the machine on, the component up, idle."""
    d.stat.poll()
    if d.stat.task_state != linuxcnc.STATE_ON:
        d.machine_on()
    if not d.component_pids():
        d.restart_component()
    d.wait_for(lambda: pin(P + "state") in (1, 5), 30, "the changer up")
    if pin(P + "fault") and COLLET:
        spindle, pockets = what_the_operator_finds_on_the_magazine({})
        confirm(spindle, pockets, {})
    elif pin(P + "fault"):
        confirm(pin(P + "tool-in-spindle"), {}, {})


def run_hold(at, steps):
    """Feed hold at the step and resume: nothing is cut off, the change ends
    with the tool it was asked for and no fault."""
    case = {"kind": "hold", "step": at, "what": next(s for s in steps if s[0] == at)[1:]}
    try:
        prepare()
        struck, first = cut("hold", at, steps, case)
        d.command.auto(linuxcnc.AUTO_PAUSE)
        d.wait_for(lambda: d.stat.paused, 10, "the program paused")
        paused = time.monotonic()
        d.wait_for(lambda: time.monotonic() - paused > 0.3, 5, "the hold")
        case["held"] = {"step_number": pin(P + "step-number"), "chuck": pin("fatc-chuck-guard.chuck"),
                        "pos": list(d.stat.actual_position[:3])}
        d.command.auto(linuxcnc.AUTO_RESUME)
        d.wait_for(lambda: d.stat.interp_state == linuxcnc.INTERP_IDLE, 60, "the program to end")
        d.wait_for(lambda: pin(P + "state") in (1, 5), 30, "the changer settled")
        case["after_hold"] = {"fault": pin(P + "fault"), "state": pin(P + "state"),
                              "linuxcnc_tool": d.stat.tool_in_spindle,
                              "changer_tool": pin(P + "tool-in-spindle"),
                              "chuck": pin("fatc-chuck-guard.chuck"), "files": files(),
                              "messages": d.messages[first:]}
    except Exception as e:  # the checker reports it; the next case starts afresh
        went_wrong(case, e)
    return case


def run_spindle_turning(steps):
    """The spindle never reports stopped (a zero-speed signal stuck low): M6
    must fault after spindle_stop_timeout_seconds with the chuck closed, having
    moved only up to safe Z and across at it (move_while_spindle_stops)."""
    case = {"kind": "spindle", "step": 0, "what": ["spindle", "does not stop"]}
    stopped = P + "spindle-stopped"
    try:
        prepare()
        case.update({"from": pin(P + "tool-in-spindle")})
        d.halcmd("unlinkp", stopped)
        d.halcmd("setp", stopped, "0")
        before = list(d.stat.actual_position[:3])
        first = len(d.messages)
        began = time.monotonic()
        lowest, chuck = [before[2]], [False]

        def watch():
            d.stat.poll()
            lowest[0] = min(lowest[0], d.stat.actual_position[2])
            chuck[0] = chuck[0] or bool(pin("fatc-chuck-guard.chuck"))
        run_program(program("fatc_matrix_t%d.ngc" % OTHER, "T%d M6\nM2\n" % OTHER), 60, watch)
        case["program_seconds"] = time.monotonic() - began
        d.stat.poll()
        case["after"] = {"fault": pin(P + "fault"), "chuck_ever": chuck[0], "lowest_z": lowest[0],
                         "start_z": before[2], "end_z": d.stat.actual_position[2],
                         "messages": d.messages[first:], "linuxcnc_tool": d.stat.tool_in_spindle}
    except Exception as e:
        case["error"] = "%s: %s" % (type(e).__name__, e)
    finally:
        d.halcmd("net", "fatc-spindle-stop", stopped)
    try:
        if pin(P + "fault"):
            confirm(case.get("from", 0), {}, case)
    except Exception as e:
        case["error"] = case.get("error", "") + " confirm: %s: %s" % (type(e).__name__, e)
    return case


def waiting_steps(steps):
    """Every step but the chuck actions (they take no time: the dwell after one
    is where a cut finds the chuck as it left it) and the final done. A collet
    nut's spindle step is where the changer waits for the spindle to come up
    to speed or stand."""
    return [n for n, kind, _ in steps if kind not in ("chuck", "done")]


def main():
    comp = hal.component("fatc-matrix")
    comp.ready()
    results = {"cases": [], "error": None}
    out = os.environ["FATC_RESULTS"]
    try:
        bring_up()
        config = os.path.join(d.ini_dir(), "config.json")
        if json.load(open(config)).get("chuck", {}).get("kind") == "collet_nut":
            # A fresh magazine: every pocket's nut in it, as the state file starts.
            COLLET.extend(sorted(int(p) for p in json.load(open(config))["pockets"]))
            for pocket in COLLET:
                sim_nut.put_in_pocket(pocket, True)
        results["collet_nut"] = bool(COLLET)
        steps = plan(config)
        results["plan"] = steps
        chosen = os.environ.get("FATC_MATRIX_STEPS")
        if chosen == "none":
            at_steps = []
        else:
            at_steps = [int(s) for s in chosen.split(",")] if chosen else waiting_steps(steps)
        if os.environ.get("FATC_MATRIX_MODE") == "restart":
            restart_mode(steps, at_steps, results)
        else:
            kinds = os.environ.get("FATC_MATRIX_KINDS", "estop,abort,kill").split(",")
            began = time.monotonic()
            for kind in kinds:
                # FATC_MATRIX_HOLD_STEPS, FATC_MATRIX_KILL_STEPS ...: a kind's own steps.
                own_steps = os.environ.get("FATC_MATRIX_%s_STEPS" % kind.upper())
                steps_of_kind = [int(n) for n in own_steps.split(",")] if own_steps else at_steps
                for at in steps_of_kind:
                    if kind == "hold":
                        results["cases"].append(run_hold(at, steps))
                    else:
                        results["cases"].append(run_case(kind, at, steps))
                    json.dump(results, open(out, "w"))
            if os.environ.get("FATC_MATRIX_SPINDLE"):
                results["cases"].append(run_spindle_turning(steps))
            results["seconds"] = time.monotonic() - began
    except Exception as e:  # the checker reports it; LinuxCNC must still shut down
        results["error"] = "%s: %s (last messages: %s)" % (type(e).__name__, e, d.messages[-4:])
    json.dump(results, open(out, "w"))


def bring_up():
    """As the driver's, but the changer may come up faulted (a restart case)."""
    d.wait_for(lambda: d.stat.task_state in (linuxcnc.STATE_ESTOP, linuxcnc.STATE_ESTOP_RESET,
                                             linuxcnc.STATE_ON, linuxcnc.STATE_OFF), 120, "task")
    d.machine_on()
    d.wait_for(lambda: pin(P + "state") in (1, 5), 60, "fixed_atc_probe up")


def restart_mode(steps, at_steps, results):
    """One LinuxCNC start of the restart cases: check and confirm what the last
    start left (FATC_MATRIX_PENDING names its case), then cut the next case's
    change and leave, which stops LinuxCNC under it."""
    pending = os.environ.get("FATC_MATRIX_PENDING")
    if pending:
        case = json.loads(pending)
        d.wait_for(lambda: pin(P + "fault"), 30, "the changer faulted after the restart")
        d.stat.poll()
        case["after_cut"] = after_cut(list(d.messages))
        try:
            observe_refusals(case)
            spindle, pockets = what_the_operator_says(steps, case["step"], case)
            confirm(spindle, pockets, case)
        except Exception as e:
            case["error"] = "%s: %s" % (type(e).__name__, e)
        results["cases"].append(case)
    if at_steps:
        at = at_steps[0]
        case = {"kind": "restart", "step": at, "what": next(s for s in steps if s[0] == at)[1:]}
        prepare()
        cut("restart", at, steps, case)
        # Stop the realtime threads at once, as a crash of LinuxCNC would:
        # LinuxCNC's own shutdown, which follows when this display exits,
        # lets the program run on for a moment first.
        case["halcmd_stop"] = d.halcmd("stop").returncode
        results["next"] = case
        results["left"] = at_steps[1:]


if __name__ == "__main__":
    main()
