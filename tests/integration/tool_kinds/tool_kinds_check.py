#!/usr/bin/python3
"""Judges one scenario of the tool-kinds run (tool_kinds.py) from what
LinuxCNC reported: usage: tool_kinds_check.py RESULTS SCENARIO."""
import json
import sys

P = "fixed_atc_probe."
SENSOR_LENGTH = 25.0  # the simulated sensor trips at Z-70, probe_length_compensation_offset -95
SENSOR_Z = -70.0
WINDOW = 10.0  # probe_window of config/config.json
problems = []


def expect(ok, what):
    if not ok:
        problems.append(what)
    return ok


def spindle_never_turned(samples, what, override_off=False):
    """Motion's speed, the drive's run and the simulated spindle, in every sample."""
    for pin in ("limit_speed.out",) + (() if override_off else ("spindle.0.speed-out",)):
        turning = [s for s in samples if s[pin]]
        expect(not turning, "%s: %s was %s at t=%.3f s" % (what, pin, turning[0][pin], turning[0]["t"])
               if turning else "")
    run = [s for s in samples if s["fatc-spindle-guard.spindle-on"]]
    expect(not run, "%s: fatc-spindle-guard.spindle-on was true at t=%.3f s" % (what, run[0]["t"])
           if run else "")


def meters_held(meters, what, override_off=False):
    """The realtime extremes of one attempt: LinuxCNC asked for the spindle,
    and nothing turned: the drive's speed and run, the simulated spindle, and
    motion's speed out unless the spindle override (and with it
    spindle.0.inhibit) was off."""
    low, high = meters["speed_command"]
    expect(low < 0 or high > 0, "%s: LinuxCNC never asked for the spindle (speed command "
                                "%g..%g rps)" % (what, low, high))
    held = ["drive_speed", "simulated_spindle", "drive_run"] + ([] if override_off else ["speed_out"])
    for name in held:
        expect(meters[name] == [0.0, 0.0], "%s: %s reached %g..%g in the servo thread" % (
            what, name, meters[name][0], meters[name][1]))
    return "asked %g..%g rps; %s 0 in every servo period; motion's speed out %g..%g, " \
           "spindle.0.on max %g" % (low, high, ", ".join(held), meters["speed_out"][0],
                                   meters["speed_out"][1], meters["spindle_on"][1])


def asked(s):
    """LinuxCNC asks for the spindle: spindle.0.on (2.9.4 on) or the commanded speed."""
    return s["spindle.0.on"] or s["spindle.0.speed-cmd-rps"] != 0


def asked_for_seconds(samples):
    """How long LinuxCNC asked for the spindle: the request until the abort."""
    high = [s["t"] for s in samples if asked(s)]
    return (max(high) - min(high)) if high else None


def on_seconds(samples):
    """How long motion's own spindle.0.on was high (2.9.0: never, the speed being inhibited)."""
    high = [s["t"] for s in samples if s["spindle.0.on"]]
    return (max(high) - min(high)) if high else 0.0


def refusals(result, tool):
    return [m for m in result["messages"]
            if "spindle held: tool %d in the spindle is a probe" % tool in m]


def check_probe_program(r):
    samples = r["samples"]
    spindle_never_turned(samples, "probe_program")
    asked = asked_for_seconds(samples)
    expect(asked is not None, "the program's M3 never reached motion (no speed commanded)")
    expect(len(refusals(r, 2)) == 1, "one refusal naming tool 2, got %s" % r["messages"])
    expect(not any(s["iocontrol.0.coolant-flood"] for s in samples),
           "M8 after the M3 ran: the program was not stopped")
    expect(abs(r["tool_table"]["2"] - SENSOR_LENGTH) < 0.01,
           "T2 measured %.4f, expected %.4f" % (r["tool_table"]["2"], SENSOR_LENGTH))
    # Fast (probe_seek_feed 3000 mm/min) only down to probe_window above where its
    # length puts the touch, then both probing stages at the probe's own feed
    # (tools.2.probe_feed 600 mm/min).
    approach = [s for s in samples if s[P + "step-kind"] == 3 and s[P + "step-feed"] > 600]
    probing = [abs(s["vel"]) for s in samples if s[P + "step-kind"] == 3 and s[P + "step-feed"] <= 600]
    expect(approach, "no fast approach to the sensor sampled")
    expect(probing and max(probing) > 1.0, "no probing move at the probe's feed sampled")
    expect(not probing or max(probing) <= 600 / 60.0 * 1.02,
           "the probe moved at %.2f mm/s on the sensor, above its probe_feed 10 mm/s" % max(probing or [0]))
    lowest_fast = min(s["pos"][2] for s in approach)
    expect(lowest_fast >= SENSOR_Z + WINDOW - 0.01,
           "the fast approach went down to Z%.3f, below probe_window above the touch at Z%.3f" % (
               lowest_fast, SENSOR_Z))
    status = r["status_file"] or {}
    expect(status.get("rule") == "T2 probe, spindle held, measured if new",
           "status file rule: %r" % status.get("rule"))
    expect(status.get("spindle_held") is True, "status file spindle_held: %r" % status.get("spindle_held"))
    # From the sample after the component said T2 (the guard follows in the next servo period).
    held = [s for before, s in zip(samples, samples[1:])
            if before[P + "tool-in-spindle"] == 2 and s[P + "tool-in-spindle"] == 2]
    loose = [s["t"] for s in held if not (s["fatc-spindle-guard.held"] and s["spindle.0.inhibit"])]
    expect(held and not loose, "with T2 in the spindle the guard did not hold it at t=%s" % loose[:3])
    print("probe_program: " + meters_held(r["meters"], "probe_program"))
    print("probe_program: M3 asked for the spindle %.3f s until the abort (spindle.0.on high "
          "%.3f s); %d samples, speed 0 in all; probe fastest on the sensor %.2f mm/s" % (
              asked or 0, on_seconds(samples), len(samples), max(probing or [0])))


def check_attempts(r, count):
    samples = r["samples"]
    spindle_never_turned(samples, r["name"], any(a.get("override_off") for a in r["attempts"]))
    expect(len(refusals(r, 2)) >= count, "%d refusals naming tool 2, got %s" % (count, r["messages"]))
    for attempt in r.get("attempts", []):
        inside = [s for s in samples if attempt["began"] <= s["t"] <= attempt["ended"]]
        line = attempt["line"] + (" after M51 P0" if attempt.get("override_off") else "")
        print("%s: %s: %s" % (r["name"], line, meters_held(attempt["meters"], line,
                                                              attempt.get("override_off"))))
        print("%s: %s: asked for %.3f s (spindle.0.on high %.3f s), %d samples, speed 0 in all" % (
            r["name"], attempt["line"], asked_for_seconds(inside) or 0, on_seconds(inside),
            len(inside)))


def check_probe_halui(r):
    samples = r["samples"]
    spindle_never_turned(samples, "probe_halui")
    print("probe_halui: " + meters_held(r["meters"], "probe_halui"))
    expect(len(refusals(r, 2)) >= 1, "a refusal naming tool 2, got %s" % r["messages"])
    print("probe_halui: asked for %.3f s (spindle.0.on high %.3f s), %d samples, speed 0 in all" % (
        asked_for_seconds(samples) or 0, on_seconds(samples), len(samples)))


def check_g38(r):
    work = r["work"]
    expect(work["tripped"], "G38.2 over the work did not trip: %s" % work)
    expect(abs(work["probed"][2] - work["work_z"]) < 0.05,
           "G38.2 stopped at Z%.4f, the probe's work is at Z%.4f" % (work["probed"][2], work["work_z"]))
    after = r["samples"][r["sensor"]["from_sample"]:]
    expect(any(s["fatc-sensor.out"] for s in after), "the touch-off sensor never tripped under G38.3")
    expect(not any(s["motion.probe-input"] for s in after),
           "motion.probe-input followed the touch-off sensor with the probe in the spindle")
    expect(not r["sensor"]["tripped"], "G38.3 over the sensor tripped")
    print("g38_probe: G38.2 tripped at Z%.4f (work Z%.4f); over the sensor G38.3 went to Z%.4f, "
          "the sensor tripped and motion.probe-input stayed false" % (
              work["probed"][2], work["work_z"], r["sensor"]["pos"][2]))


def check_kill_held(r):
    first, last = r["held_window"]
    window = r["samples"][first:last]
    expect(len(window) >= 300, "held window of %d samples" % len(window))
    spindle_never_turned(window, "kill_held (component dead)")
    expect(all(asked(s) for s in window), "M3 was not standing during the window")
    print("kill_held: " + meters_held(r["meters"], "kill_held (component dead)"))
    expect(all(s["fatc-spindle-guard.held"] and not s["fatc-spindle-guard.alive"] for s in window),
           "the guard was not holding with the component gone")
    after = [s for s in r["samples"] if s["t"] >= r["restarted_at"]]
    spindle_never_turned(after, "kill_held (restarted)")
    expect(len(refusals(r, 2)) >= 1, "the restarted component did not refuse M3: %s" % r["messages"])
    print("kill_held: component dead %.2f s of M3 (%d samples), nothing turned; restarted, M3 "
          "aborted" % (window[-1]["t"] - window[0]["t"], len(window)))


def check_rules(r):
    samples = r["samples"]
    touches = []  # rising edges of the touch-off sensor, with the tool in the spindle
    for before, now in zip(samples, samples[1:]):
        if now["fatc-sensor.out"] and not before["fatc-sensor.out"]:
            touches.append(now[P + "tool-in-spindle"])
    expect(touches == [5, 5], "the sensor was touched by %s, expected T5's seek and latch once" % touches)
    expect(abs(r["tool_table"]["4"] - 25.0) < 1e-6, "T4 (never) length %.4f, the table had 25.0" %
           r["tool_table"]["4"])
    expect(abs(r["tool_table"]["5"] - SENSOR_LENGTH) < 0.01, "T5 (new) measured %.4f" % r["tool_table"]["5"])
    expect(r["samples"][-1][P + "state"] == 1, "the changer not idle after the program")
    print("rules: sensor touches by tool %s; T4 %.4f (table), T5 %.4f (measured)" % (
        touches, r["tool_table"]["4"], r["tool_table"]["5"]))


def check_broken(r):
    said = [m for m in r["messages"] if "2.0000 mm shorter" in m]
    expect(said and "tool 3 measures 22.99" in said[0] and
           "tools.3.check_tolerance 0.0500 mm" in said[0], "the fault's words: %s" % r["messages"])
    expect(r["samples"][-1][P + "fault"], "the changer did not fault")
    expect(not any(s["iocontrol.0.coolant-flood"] for s in r["samples"]),
           "M8 after the failed check ran: the program was not halted")
    expect(abs(r["first_tool_table"]["3"] - SENSOR_LENGTH) < 0.01, "T3's first measure %.4f" %
           r["first_tool_table"]["3"])
    expect(abs(r["tool_table"]["3"] - r["first_tool_table"]["3"]) < 1e-6, "the failed check wrote T3")
    print("check_broken: %s" % (said[0] if said else "-"))


CHECKS = {"probe_program": check_probe_program, "probe_mdi": lambda r: check_attempts(r, 3),
          "probe_halui": check_probe_halui, "g38_probe": check_g38, "kill_held": check_kill_held,
          "rules": check_rules, "check_broken": check_broken}


def main():
    results = json.load(open(sys.argv[1]))
    name = sys.argv[2]
    found = [s for s in results["scenarios"] if s["name"] == name]
    if not found:
        print("FAIL: %s did not run: %s" % (name, results["error"]))
        return 1
    CHECKS[name](found[0])
    problems[:] = [p for p in problems if p]
    for problem in problems:
        print("FAIL: " + problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
