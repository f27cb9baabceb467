#!/usr/bin/python3
"""[DISPLAY]DISPLAY of the step-by-step run (issue 44) on the real LinuxCNC,
its STEP_TIMEOUT cut to 2 s. In one start, in order:
  first_tool     T1 M6, step by step off: T1 in the spindle
  step_change    --plan of M6 T2 with T1 in; then, the step-by-step pin on, a
                 program's T2 M6: at each prompt the driver samples LinuxCNC,
                 the first step of each kind for HOLD_S past STEP_TIMEOUT (the
                 very first for LONG_HOLD_S), the others for QUICK_HOLD_S, and
                 presses Continue
  step_cancel    the pin on, T3 M6: Continue up to the first chuck action
                 (the release of T2 into pocket 2), Cancel there; the program
                 ends; then the fault is cleared with LinuxCNC's tool
  operator_step  `fixed_atc_probe --operator unload:2 --step --yes`
step_mode_check.py judges. Environment: FATC_RESULTS.
"""
import json
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
import driver as d  # noqa: E402  (shares its LinuxCNC channels and HAL helpers)
import hal  # noqa: E402
import linuxcnc  # noqa: E402
import operator_command  # noqa: E402

P = d.COMPONENT + "."
HOLD_S = 2.5  # past the run's STEP_TIMEOUT of 2 s: the operator thinks
LONG_HOLD_S = 5.0  # the first, twice as long
QUICK_HOLD_S = 0.3  # a step of a kind already held long: answered at once
FOLDER = "tests/integration/step_mode/"
STEP_WORDS = re.compile(r"^Step by step, .*?, step (\d+): (.*)$")


def status_activity():
    return (d.read_json(d.state_path() + ".status") or {}).get("activity", "")


def plan(from_tool, to_tool):
    """--plan of that change on the running machine's config, rack and INI."""
    done = subprocess.run(["fixed_atc_probe", "--plan", "--config", d.config_path(), "--from",
                           str(from_tool), "--to", str(to_tool), "--state", d.state_path(), "--ini",
                           os.environ["INI_FILE_NAME"]], capture_output=True, text=True)
    return {"code": done.returncode, "out": done.stdout, "err": done.stderr}


def step_kind(words):
    """rapid, feed, open the chuck or close the chuck: a held step's action."""
    return next(kind for kind in ("rapid", "feed", "open the chuck", "close the chuck", "")
                if words.startswith(kind))


def step_through(name, program, cancel_here=None):
    """Runs `program` with the step-by-step pin on: at each step held (the
    status file's words name it) samples LinuxCNC, then presses Continue, or
    Cancel at the first step `cancel_here(its words)` says so of."""
    result = {"name": name, "samples": [], "prompts": [], "messages": []}
    first_message = len(d.messages)
    hal.set_p(P + "step-by-step", "1")
    d.start_program(FOLDER + program)
    start = time.monotonic()

    def sample():
        d.stat.poll()
        d.drain_errors()
        s = d.sample(start)
        result["samples"].append(s)
        return s

    def sample_for(seconds):
        until = time.monotonic() + seconds
        while time.monotonic() < until:
            sample()
            time.sleep(0.002)

    d.wait_for(lambda: d.stat.interp_state != linuxcnc.INTERP_IDLE, 30, "the program to start")
    answered = None
    held_kinds = set()
    deadline = start + 300
    while time.monotonic() < deadline:
        s = sample()
        match = STEP_WORDS.match(status_activity()) if s[P + "waiting-for-operator"] else None
        if match and int(match.group(1)) != answered:
            answered = int(match.group(1))
            prompt = {"number": answered, "words": match.group(0), "action": match.group(2),
                      "t": s["t"], "pos": s["pos"], "chuck": s[P + "chuck"]}
            # The first step of each kind (rapid, feed, chuck opened, closed)
            # held past STEP_TIMEOUT: each kind's wait counted from the answer.
            kind = step_kind(match.group(2))
            if not result["prompts"]:
                sample_for(LONG_HOLD_S)
            elif kind not in held_kinds:
                sample_for(HOLD_S)
            else:
                sample_for(QUICK_HOLD_S)
            held_kinds.add(kind)
            cancel = cancel_here is not None and cancel_here(match.group(2))
            prompt["answer"] = "cancel" if cancel else "continue"
            prompt["answered_at"] = time.monotonic() - start
            result["prompts"].append(prompt)
            pin = P + prompt["answer"]
            hal.set_p(pin, "1")
            sample_for(0.1)
            hal.set_p(pin, "0")
            continue
        if d.stat.interp_state == linuxcnc.INTERP_IDLE and s["t"] > 0.5:
            break
        time.sleep(0.002)
    hal.set_p(P + "step-by-step", "0")
    d.wait_for(lambda: not hal.get_value("iocontrol.0.tool-change") and
               not hal.get_value("iocontrol.0.tool-changed"), 10, "the change handshake to end")
    d.finish(result, start, first_message)
    result["fault_pin"] = hal.get_value(P + "fault")
    result["chuck_pins"] = [hal.get_value(P + "chuck"), hal.get_value("fatc-chuck-guard.chuck")]
    return result


def a_chuck_action(words):
    return words.startswith(("open the chuck", "close the chuck"))


def clear_fault():
    """The operator checked the spindle: it holds what LinuxCNC says."""
    hal.set_p(P + "clear-fault", "1")
    d.wait_for(lambda: hal.get_value(P + "state") == 1, 30, "the fault to clear")
    hal.set_p(P + "clear-fault", "0")


def operator_step():
    result = {"name": "operator_step", "samples": [], "messages": []}
    operator_command.perform({"operator_command": ["unload:2", "--step", "--yes"],
                              "name": "unload"}, result, {})
    result["switch_after"] = hal.get_value(P + "step-by-step")
    d.wait_for(lambda: hal.get_value(P + "state") == 1 and
               d.stat.interp_state == linuxcnc.INTERP_IDLE, 60, "the changer idle")
    result["state_file"] = d.read_json(d.state_path())
    d.stat.poll()
    result["tool_in_spindle"] = d.stat.tool_in_spindle
    return result


def main():
    component = hal.component("fatc-driver")  # hal.get_value needs a component of our own
    component.ready()
    results = {"scenarios": [], "error": None}
    try:
        d.bring_up()
        results["scenarios"].append(d.run_scenario({"name": "first_tool",
                                                    "program": FOLDER + "first_tool.ngc"}))
        planned = plan(1, 2)
        change = step_through("step_change", "step_change.ngc")
        change["plan"] = planned
        results["scenarios"].append(change)
        cancelled = step_through("step_cancel", "step_cancel.ngc", a_chuck_action)
        clear_fault()
        d.stat.poll()
        cancelled["cleared_tool_in_spindle"] = d.stat.tool_in_spindle
        cancelled["cleared_state_file"] = d.read_json(d.state_path())
        results["scenarios"].append(cancelled)
        results["scenarios"].append(operator_step())
    except Exception as e:  # the checker reports it; LinuxCNC must still shut down
        results["error"] = "%s: %s (last messages: %s)" % (type(e).__name__, e, d.messages[-4:])
    json.dump(results, open(os.environ["FATC_RESULTS"], "w"))


if __name__ == "__main__":
    main()
