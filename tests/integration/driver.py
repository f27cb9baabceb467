#!/usr/bin/python3
"""[DISPLAY]DISPLAY of the integration runs: brings the simulated machine up,
runs each scenario's G-code, samples what LinuxCNC reports (position, tool in
spindle, HAL pins) and writes it all to FATC_RESULTS as JSON. LinuxCNC shuts
down when this exits."""
import json
import os
import sys
import time

import hal
import linuxcnc

PINS = ["fixed_atc_probe.chuck", "fixed_atc_probe.waiting-for-operator", "fixed_atc_probe.last-length", "fixed_atc_probe.state", "fixed_atc_probe.fault",
        "fixed_atc_probe.busy", "fixed_atc_probe.tool-in-spindle", "fixed_atc_probe.step-ready",
        "fixed_atc_probe.step-request", "iocontrol.0.tool-prepare", "iocontrol.0.tool-prepared",
        "iocontrol.0.tool-change", "iocontrol.0.tool-changed", "iocontrol.0.tool-number",
        "motion.probe-input", "spindle.0.on", "iocontrol.0.coolant-flood", "fatc-chuck-guard.chuck"]

stat = linuxcnc.stat()
command = linuxcnc.command()
errors = linuxcnc.error_channel()
messages = []


def drain_errors():
    while True:
        error = errors.poll()
        if not error:
            return
        messages.append(error[1])


def wait_for(condition, timeout, what):
    """Waits on a condition LinuxCNC reports, generously: these machines are shared."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        stat.poll()
        drain_errors()
        if condition():
            return
        time.sleep(0.01)
    raise TimeoutError("timed out waiting for " + what)


def bring_up():
    wait_for(lambda: stat.task_state in (linuxcnc.STATE_ESTOP, linuxcnc.STATE_ESTOP_RESET,
                                         linuxcnc.STATE_ON, linuxcnc.STATE_OFF), 120, "task")
    command.state(linuxcnc.STATE_ESTOP_RESET)
    command.state(linuxcnc.STATE_ON)
    wait_for(lambda: stat.task_state == linuxcnc.STATE_ON, 60, "machine on")
    command.mode(linuxcnc.MODE_MANUAL)
    command.wait_complete()
    command.home(-1)
    wait_for(lambda: all(stat.homed[i] for i in range(stat.joints)), 120, "homing")
    wait_for(lambda: hal.get_value("fixed_atc_probe.state") == 1, 60, "fixed_atc_probe idle")


def sample(start):
    values = {pin: hal.get_value(pin) for pin in PINS}
    values["t"] = time.monotonic() - start
    values["pos"] = list(stat.actual_position[:3])
    values["cmd"] = list(stat.position[:3])
    values["tool_in_spindle"] = stat.tool_in_spindle
    values["interp"] = stat.interp_state
    values["paused"] = stat.paused
    return values


def run_scenario(scenario):
    result = {"name": scenario["name"], "samples": [], "messages": []}
    first_message = len(messages)
    for pin, value in scenario.get("set_pins", {}).items():
        hal.set_p(pin, value)
    for line in scenario.get("mdi", []):
        command.mode(linuxcnc.MODE_MDI)
        command.wait_complete()
        command.mdi(line)
        command.wait_complete(60)
    command.mode(linuxcnc.MODE_AUTO)
    command.wait_complete()
    command.program_open(os.path.join(os.environ["FATC_ROOT"], scenario["program"]))
    command.wait_complete()
    command.auto(linuxcnc.AUTO_RUN, 0)
    start = time.monotonic()
    wait_for(lambda: stat.interp_state != linuxcnc.INTERP_IDLE or stat.exec_state != 0, 30,
             "the program to start")
    acted = set()
    releases = []  # (time, pin): buttons pressed during the program, released 100 ms later
    deadline = start + scenario.get("timeout", 300)
    while time.monotonic() < deadline:
        stat.poll()
        drain_errors()
        s = sample(start)
        result["samples"].append(s)
        for at, pin in [r for r in releases if time.monotonic() - r[0] > 0.1]:
            hal.set_p(pin, "0")
            releases.remove((at, pin))
        for action in scenario.get("actions", []):
            key = json.dumps(action)
            if key in acted or not when(action, s, result):
                continue
            acted.add(key)
            if action["do"] == "press":
                hal.set_p(action["pin"], "1")
                releases.append((time.monotonic(), action["pin"]))
                result.setdefault("pressed", []).append([action["pin"], s["t"]])
            elif action["do"] == "pause":
                command.auto(linuxcnc.AUTO_PAUSE)
                result["paused_at"] = s["t"]
            elif action["do"] == "resume":
                command.auto(linuxcnc.AUTO_RESUME)
                result["resumed_at"] = s["t"]
            elif action["do"] == "abort":
                command.abort()
                result["aborted_at"] = s["t"]
            elif action["do"] == "snapshot_abort":
                result["snapshot"] = {"gcodes": list(stat.gcodes),
                                      "tool_offset": list(stat.tool_offset[:3]),
                                      "program_units": stat.program_units,
                                      "pos": list(stat.actual_position[:3])}
                command.abort()
        if stat.interp_state == linuxcnc.INTERP_IDLE and s["t"] > 0.5 and not releases:
            break
        time.sleep(0.002)
    if scenario.get("settle_pin"):
        pin, value = scenario["settle_pin"]
        try:
            wait_for(lambda: hal.get_value(pin) == value, 10, pin)
        except TimeoutError:
            pass  # the checker reports what it finds
    # Let the level handshakes fall back before the last sample.
    wait_for(lambda: not hal.get_value("iocontrol.0.tool-change") and
             not hal.get_value("iocontrol.0.tool-changed"), 10, "the change handshake to end")
    finish(result, start, first_message)
    for pin in scenario.get("set_pins", {}):
        hal.set_p(pin, "0")
    for step in scenario.get("after", []):
        if step == "clear_fault":
            # The operator has checked the spindle: it holds what LinuxCNC says.
            hal.set_p("fixed_atc_probe.clear-fault", "1")
            wait_for(lambda: hal.get_value("fixed_atc_probe.state") == 1, 30, "the fault to clear")
            hal.set_p("fixed_atc_probe.clear-fault", "0")
    return result


def run_operator(scenario):
    """An operator at the panel: buttons are HAL pins, waits are on what LinuxCNC
    and the component report, all sampled like a program run."""
    result = {"name": scenario["name"], "samples": [], "messages": []}
    first_message = len(messages)
    start = time.monotonic()

    def sampled_wait(condition, timeout, what):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            stat.poll()
            drain_errors()
            result["samples"].append(sample(start))
            if condition():
                return
            time.sleep(0.002)
        raise TimeoutError("timed out waiting for " + what)

    for step in scenario["operator"]:
        if "set" in step:
            for pin, value in step["set"].items():
                hal.set_p(pin, str(value))
        elif "press" in step:
            # A press is a pulse the component's 20 ms poll cannot miss: 100 ms
            # down, then 100 ms up before anything else may press again.
            hal.set_p(step["press"], "1")
            pressed = time.monotonic()
            sampled_wait(lambda: time.monotonic() - pressed > 0.1, 5, "the press")
            hal.set_p(step["press"], "0")
            released = time.monotonic()
            sampled_wait(lambda: time.monotonic() - released > 0.1, 5, "the release")
        elif "wait" in step:
            pin, value = step["wait"]
            sampled_wait(lambda: hal.get_value(pin) == value, step.get("timeout", 180),
                         "%s == %s" % (pin, value))
        elif "wait_message" in step:
            sampled_wait(lambda: any(step["wait_message"] in m for m in messages[first_message:]), 60,
                         "a message saying " + step["wait_message"])
        elif "wait_idle" in step:
            sampled_wait(lambda: hal.get_value("fixed_atc_probe.state") == 1 and
                         stat.interp_state == linuxcnc.INTERP_IDLE, 180, "the changer idle")
        elif step.get("machine") == "off":
            command.state(linuxcnc.STATE_OFF)  # task then reports ESTOP_RESET or OFF
            sampled_wait(lambda: stat.task_state != linuxcnc.STATE_ON and
                         hal.get_value("fixed_atc_probe.state") == 0, 30, "the machine off")
        elif step.get("machine") == "on":
            command.state(linuxcnc.STATE_ON)  # homing survives machine off
            sampled_wait(lambda: hal.get_value("fixed_atc_probe.state") == 1, 30, "the changer idle")
        elif "wait_z_below" in step:
            sampled_wait(lambda: stat.actual_position[2] < step["wait_z_below"], 60,
                         "Z below %s" % step["wait_z_below"])
        elif "jog" in step:
            axis, distance = step["jog"]
            command.mode(linuxcnc.MODE_MANUAL)
            command.wait_complete()
            target = stat.actual_position[axis] + distance
            command.jog(linuxcnc.JOG_INCREMENT, False, axis, 20.0, distance)
            sampled_wait(lambda: abs(stat.actual_position[axis] - target) < 1e-3, 60, "the jog")
            result["jogged_to"] = list(stat.actual_position[:3])
        elif "mdi" in step:
            command.mode(linuxcnc.MODE_MDI)
            command.wait_complete()
            command.mdi(step["mdi"])
            command.wait_complete(60)
    finish(result, start, first_message)
    return result


def finish(result, start, first_message):
    """The last sample and what LinuxCNC says after the scenario."""
    stat.poll()
    drain_errors()
    result["samples"].append(sample(start))
    result["messages"] = messages[first_message:]
    result["start_pos"] = result["samples"][0]["pos"]
    result["duration"] = time.monotonic() - start
    result["tool_table_file"] = open(os.path.join(os.path.dirname(sys.argv[2]), "sim.tbl")).read()


def when(action, s, result):
    """An action fires on a condition of the sample: e.g. chuck open, or a pin value."""
    condition = action["when"]
    if "pin" in condition:
        # "nth": the condition's nth start (an operator wait that comes twice).
        key = "seen %s" % json.dumps(condition)
        now = s[condition["pin"]] == condition["value"]
        if now and not result.get(key + " last"):
            result[key] = result.get(key, 0) + 1
        result[key + " last"] = now
        return now and result.get(key, 0) == condition.get("nth", 1)
    if "after_start" in condition:
        return s["t"] > condition["after_start"]
    if "program_paused" in condition:
        return s["paused"]
    if "after_paused" in condition:
        return "paused_at" in result and s["t"] > result["paused_at"] + condition["after_paused"]
    return False


def main():
    driver = hal.component("fatc-driver")  # hal.get_value needs a component of our own
    driver.ready()
    scenarios = json.load(open(os.environ["FATC_SCENARIOS"]))
    results = {"scenarios": [], "error": None}
    try:
        bring_up()
        for scenario in scenarios:
            run = run_operator if "operator" in scenario else run_scenario
            results["scenarios"].append(run(scenario))
    except Exception as e:  # the checker reports it; LinuxCNC must still shut down
        results["error"] = "%s: %s (last messages: %s)" % (type(e).__name__, e, messages[-4:])
    json.dump(results, open(os.environ["FATC_RESULTS"], "w"))


if __name__ == "__main__":
    main()
