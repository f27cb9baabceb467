#!/usr/bin/python3
"""[DISPLAY]DISPLAY of the tool-kinds run on the real LinuxCNC (issue 35).

config.json's tools: T2 a touch probe (measured when new, at its own feed),
T3 checked within 0.05 mm, T4 never measured, T5 measured when new. In one
start, in order:
  probe_program  M6 T2 fetches the probe and measures it; the program's M3 is
                 held by fatc-spindle-guard and aborted by the component
  probe_mdi      MDI M3, then M4, with the probe in the spindle
  probe_halui    halui's spindle start with the probe in the spindle
  g38_probe      G38.2 over the simulated work trips on the probe's input; G38.3
                 over the touch-off sensor does not, though the sensor trips
  kill_held      the component SIGKILLed: MDI M3 still turns nothing; restarted,
                 the component aborts the next M3
  rules          M6 T4, T5, T4, T5, T0: T4 never touches the sensor, T5 once
  check_broken   T3 measured, then 2 mm shorter: the next M6 T3 halts the program
Every attempt is sampled (spindle pins, the guard, the sensor, the probe, the
simulated spindle's speed) until what LinuxCNC reports says it ended.
tool_kinds_check.py judges. Environment: FATC_RESULTS.
"""
import json
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
import driver as d  # noqa: E402  (shares its LinuxCNC channels and HAL helpers)
import hal  # noqa: E402
import linuxcnc  # noqa: E402

P = d.COMPONENT + "."
PINS = ["spindle.0.on", "spindle.0.speed-cmd-rps", "spindle.0.speed-out", "spindle.0.inhibit", "limit_speed.out",
        "fatc-spindle-guard.spindle-on", "fatc-spindle-guard.held", "fatc-spindle-guard.refused",
        "fatc-spindle-guard.alive", "motion.probe-input", "fatc-sensor.out", "fatc-sim-probe.out",
        P + "probe-in-spindle", P + "tool-in-spindle", P + "state", P + "step-kind", P + "step-feed",
        P + "fault",
        "iocontrol.0.coolant-flood"]
# The simulated work the probe touches: a box around this XY (machine units),
# touched when the spindle nose comes down to WORK_Z.
WORK_X, WORK_Y, WORK_Z = 120.0, 80.0, -40.0


# Realtime meters (LinuxCNC's minmax, in the servo thread): the extremes of
# each signal over a whole attempt, which sampling from here could miss.
METERS = {"speed_command": "fatc-spindle-command", "speed_out": "spindle-speed-cmd",
          "drive_speed": "fatc-spindle-speed", "simulated_spindle": "spindle-speed-limited",
          "drive_run": "fatc-spindle-run", "spindle_on": "fatc-spindle-on"}
BITS = ("drive_run", "spindle_on")  # through conv_bit_float first


def halcmd(*args):
    done = d.halcmd(*args)
    if done.returncode != 0:
        raise RuntimeError("halcmd %s: %s" % (" ".join(args), done.stdout + done.stderr))


def install_meters():
    names = ["fatc-meter-" + name.replace("_", "-") for name in METERS]
    halcmd("loadrt", "minmax", "names=" + ",".join(names))
    halcmd("loadrt", "conv_bit_float", "names=" + ",".join("fatc-bit-" + b.replace("_", "-")
                                                             for b in BITS))
    for name, signal in METERS.items():
        meter = "fatc-meter-" + name.replace("_", "-")
        if name in BITS:
            bit = "fatc-bit-" + name.replace("_", "-")
            halcmd("addf", bit, "servo-thread")
            halcmd("net", signal, bit + ".in")
            halcmd("net", "fatc-meter-" + name, bit + ".out", meter + ".in")
        else:
            halcmd("net", signal, meter + ".in")
        halcmd("addf", meter, "servo-thread")


def reset_meters():
    for name in METERS:
        hal.set_p("fatc-meter-%s.reset" % name.replace("_", "-"), "1")
    d.wait_for(lambda: all(low == high for low, high in read_meters().values()), 10,
               "the meters to reset")
    for name in METERS:
        hal.set_p("fatc-meter-%s.reset" % name.replace("_", "-"), "0")


def read_meters():
    return {name: [d.pin_value("fatc-meter-%s.min" % name.replace("_", "-")),
                   d.pin_value("fatc-meter-%s.max" % name.replace("_", "-"))] for name in METERS}


def sample(result, start):
    d.stat.poll()
    d.drain_errors()
    s = {pin: d.pin_value(pin) for pin in PINS}
    s["t"] = time.monotonic() - start
    s["pos"] = list(d.stat.actual_position[:3])
    s["vel"] = d.stat.current_vel
    s["interp"] = d.stat.interp_state
    result["samples"].append(s)
    return s


def sampled_until(result, start, condition, timeout, what):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition(sample(result, start)):
            return
        time.sleep(0.002)
    raise TimeoutError("timed out waiting for " + what)


def new_result(name):
    return {"name": name, "samples": [], "first_message": len(d.messages)}


def close(result):
    d.stat.poll()
    d.drain_errors()
    result["messages"] = d.messages[result.pop("first_message"):]
    result["tool_table"] = {str(t.id): t.zoffset for t in d.stat.tool_table if t.id > 0}
    result["status_file"] = d.read_json(d.state_path() + ".status")
    return result


def idle(s):
    return s["interp"] == linuxcnc.INTERP_IDLE


def run_program(name, program, timeout=240):
    result = new_result(name)
    start = time.monotonic()
    d.start_program(program)
    seen = []

    def ended(s):
        if not idle(s):
            seen.append(True)
        return idle(s) and (seen or s["t"] > 2.0)
    sampled_until(result, start, ended, timeout, "the program %s to end" % program)
    sampled_until(result, start, lambda s: not d.pin_value("iocontrol.0.tool-change"), 10,
                  "the change handshake to end")
    return result, start


def asked(s):
    """LinuxCNC asks for the spindle: its commanded speed (2.9.0 keeps
    spindle.0.on low while spindle.0.inhibit holds the speed at 0)."""
    return s["spindle.0.on"] or s["spindle.0.speed-cmd-rps"] != 0


def refusals():
    return sum("spindle held:" in m for m in d.messages)


def mdi_attempt(result, start, line, override_off=False):
    """An MDI line that starts the spindle: sampled until LinuxCNC has it off
    again and the component has said why. override_off: after M51 P0, which
    switches spindle.0.inhibit off."""
    said = refusals()
    d.command.mode(linuxcnc.MODE_MDI)
    d.command.wait_complete()
    reset_meters()
    began = time.monotonic() - start
    d.command.mdi(line)
    sampled_until(result, start, lambda s: asked(s) or refusals() > said, 20,
                  "LinuxCNC to take " + line)
    sampled_until(result, start, lambda s: not asked(s) and idle(s) and refusals() > said, 20,
                  "the spindle off and the refusal after " + line)
    result.setdefault("attempts", []).append({"line": line, "began": began,
                                              "ended": time.monotonic() - start,
                                              "meters": read_meters(),
                                              "override_off": override_off})


def probe_program():
    said = refusals()
    reset_meters()
    result, start = run_program("probe_program", "tests/integration/tool_kinds/probe_m3.ngc")
    sampled_until(result, start, lambda s: refusals() > said, 20, "the refusal of the M3")
    result["meters"] = read_meters()
    return close(result)


def probe_mdi():
    result = new_result("probe_mdi")
    start = time.monotonic()
    mdi_attempt(result, start, "S1000 M3")
    mdi_attempt(result, start, "M4 S500")
    # M51 P0: LinuxCNC's spindle override off, and with it spindle.0.inhibit.
    mdi("M51 P0")
    mdi_attempt(result, start, "S1000 M3", override_off=True)
    mdi("M51 P1")
    return close(result)


def probe_halui():
    result = new_result("probe_halui")
    start = time.monotonic()
    d.command.mode(linuxcnc.MODE_MANUAL)
    d.command.wait_complete()
    said = refusals()
    reset_meters()
    hal.set_p("halui.spindle.0.start", "1")
    try:
        sampled_until(result, start, lambda s: asked(s) or refusals() > said, 20,
                      "halui to start the spindle")
        sampled_until(result, start, lambda s: not asked(s) and refusals() > said, 20,
                      "the spindle off and the refusal after halui's start")
    finally:
        hal.set_p("halui.spindle.0.start", "0")
    result["meters"] = read_meters()
    return close(result)


def mdi(line, timeout=60):
    d.command.mode(linuxcnc.MODE_MDI)
    d.command.wait_complete()
    d.command.mdi(line)
    d.command.wait_complete(timeout)


def g38_probe():
    result = new_result("g38_probe")
    start = time.monotonic()
    for pin, value in (("x-min", WORK_X - 5), ("x-max", WORK_X + 5), ("y-min", WORK_Y - 5),
                       ("y-max", WORK_Y + 5), ("z-trip", WORK_Z)):
        hal.set_p("fatc-sim-probe." + pin, str(value))
    mdi("G10 L2 P1 X0 Y0 Z0")
    mdi("G54 G49 G90 G21")
    mdi("G53 G0 Z-5")
    mdi("G53 G0 X%.3f Y%.3f" % (WORK_X, WORK_Y))
    # Down fast to 5 mm over the work: the probing feed only for the last of it.
    mdi("G53 G0 Z%.3f" % (WORK_Z + 5))
    said = len(d.messages)
    d.command.mdi("G38.2 Z%.3f F300" % (WORK_Z - 20))
    sampled_until(result, start, lambda s: idle(s) and s["t"] > 0.2, 60, "G38.2 on the work")
    d.stat.poll()
    result["work"] = {"tripped": d.stat.probe_tripped, "probed": list(d.stat.probed_position[:3]),
                      "work_z": WORK_Z, "errors": d.messages[said:]}
    # Over the touch-off sensor: it trips, and G38.3 does not see it.
    ini = d.ini()
    sx = (float(ini.find("FIXED_ATC_PROBE", "SIM_SENSOR_XMIN")) +
          float(ini.find("FIXED_ATC_PROBE", "SIM_SENSOR_XMAX"))) / 2
    sy = (float(ini.find("FIXED_ATC_PROBE", "SIM_SENSOR_YMIN")) +
          float(ini.find("FIXED_ATC_PROBE", "SIM_SENSOR_YMAX"))) / 2
    sz = float(ini.find("FIXED_ATC_PROBE", "SIM_SENSOR_Z"))
    mdi("G53 G0 Z-5")
    mdi("G53 G0 X%.3f Y%.3f" % (sx, sy))
    mdi("G53 G0 Z%.3f" % (sz + 5))  # 5 mm over the sensor, as over the work
    mark = len(result["samples"])
    d.command.mdi("G38.3 Z%.3f F300" % (sz - 3))
    sampled_until(result, start, lambda s: idle(s) and s["t"] > 0.2 and
                  len(result["samples"]) > mark + 5, 60, "G38.3 over the sensor")
    d.stat.poll()
    result["sensor"] = {"tripped": d.stat.probe_tripped, "from_sample": mark, "sensor_z": sz,
                        "pos": list(d.stat.actual_position[:3])}
    mdi("G53 G0 Z-5")
    return close(result)


def kill_held():
    result, start = run_program("kill_held", "tests/integration/tool_kinds/fetch_probe.ngc")
    result["killed_pid"], _ = d.kill_component()
    result["killed_at"] = time.monotonic() - start
    d.command.mode(linuxcnc.MODE_MDI)
    d.command.wait_complete()
    reset_meters()
    d.command.mdi("S1000 M3")
    # The guard's heartbeat watch gives up on the dead component; the spindle stays held.
    sampled_until(result, start, lambda s: asked(s) and not s["fatc-spindle-guard.alive"],
                  30, "M3 with the component dead")
    mark = len(result["samples"])
    # A few hundred polls with LinuxCNC asking for the spindle: nothing may turn.
    sampled_until(result, start, lambda s: len(result["samples"]) > mark + 300, 60, "the samples")
    result["held_window"] = [mark, len(result["samples"])]
    result["meters"] = read_meters()
    mdi("M5")
    result["restart"] = d.restart_component()
    sampled_until(result, start, lambda s: s[P + "state"] == 1, 60, "the restarted changer idle")
    result["restarted_at"] = time.monotonic() - start
    mdi_attempt(result, start, "S1000 M3")
    return close(result)


def rules():
    result, _ = run_program("rules", "tests/integration/tool_kinds/rules.ngc")
    return close(result)


def check_broken():
    result, start = run_program("check_broken", "tests/integration/tool_kinds/check_first.ngc")
    result["first_tool_table"] = {str(t.id): t.zoffset for t in d.stat.tool_table if t.id > 0}
    trip = d.pin_value("fatc-sensor.z-trip")
    hal.set_p("fatc-sensor.z-trip", str(trip - 2.0))  # the tool broke: 2 mm shorter
    try:
        d.start_program("tests/integration/tool_kinds/check_again.ngc")
        sampled_until(result, start, lambda s: s[P + "fault"] and idle(s), 240,
                      "the check to halt the program")
    finally:
        hal.set_p("fatc-sensor.z-trip", str(trip))
    result["faulted_at"] = time.monotonic() - start
    closed = close(result)
    # The operator finds tool 3 in the spindle and clears the fault.
    d.perform({"do": "confirm", "tool": 3, "pocket": -1}, {"samples": []}, start)
    return closed


def main():
    driver = hal.component("fatc-driver")
    driver.ready()
    results = {"scenarios": [], "error": None}
    try:
        d.bring_up()
        install_meters()
        for scenario in (probe_program, probe_mdi, probe_halui, g38_probe, kill_held, rules,
                         check_broken):
            results["scenarios"].append(scenario())
    except Exception as e:  # the checker reports it; LinuxCNC must still shut down
        results["error"] = "%s: %s (last messages: %s)" % (type(e).__name__, e, d.messages[-4:])
    json.dump(results, open(os.environ["FATC_RESULTS"], "w"))


if __name__ == "__main__":
    main()
