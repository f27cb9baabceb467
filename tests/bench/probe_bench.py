#!/usr/bin/python3
"""[DISPLAY]DISPLAY of the probe benchmark: on the simulated mill, measures
one tool N times with fixed_atc_probe's two-stage probe (seek, back off,
latch; through the component and its step executor, as an operator's
Load/Probe does) and N times with the prototype's method (down 0.2 mm per
move, the sensor read between moves), both from loading Z at the same feed.
Then a touch probe (T3, config.json's tools: "kind": "probe", measured at
probe_latch_feed) N times through Load/Probe - fast to the window above where
its length puts the touch, slowly from there (issue 42) - and N times as it
was measured before, at that feed all the way down from loading Z (seek,
back-off, latch, by a program). Writes every measurement to FATC_RESULTS;
scripts/bench_probe.py prints them.

The simulated sensor is put at a height off the 0.2 mm grid of the stepping
method, as a real sensor would be."""
import json
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.environ["FATC_ROOT"], "tests", "integration", "harness"))
import driver  # noqa: E402  (bring-up and waits shared with the integration runs)
from driver import command, hal, linuxcnc, stat, wait_for  # noqa: E402

SENSOR_Z = -70.0731
REPEATS = int(os.environ.get("FATC_BENCH_REPEATS") or "10")
TOOL = 2
PROBE = 3  # a touch probe: scripts/bench_probe.sh declares it so in config.json
SENSOR_INPUT = "01"  # motion.digital-in-01: the stepping method reads the sensor there


def config():
    return json.load(open(os.path.join(os.path.dirname(sys.argv[2]), "config.json")))


def press(pin):
    # A pulse the component's 20 ms poll cannot miss, as in the integration driver.
    hal.set_p(pin, "1")
    time.sleep(0.1)
    hal.set_p(pin, "0")
    time.sleep(0.1)


def mdi(line, timeout=120):
    command.mode(linuxcnc.MODE_MDI)
    command.wait_complete()
    command.mdi(line)
    command.wait_complete(timeout)
    wait_for(lambda: stat.interp_state == linuxcnc.INTERP_IDLE, timeout, line)


def two_stage(tool=TOOL):
    """Load/Probe of the tool in the spindle; timed from the start of the first
    probing move to the tool-table write, read on the pins at 2 ms."""
    hal.set_p("fixed_atc_probe.tool-number", str(tool))
    press("fixed_atc_probe.load")
    wait_for(lambda: hal.get_value("fixed_atc_probe.waiting-for-operator"), 120, "the jog prompt")
    press("fixed_atc_probe.continue")
    start = None
    deadline = time.monotonic() + 300
    while time.monotonic() < deadline:
        if start is None and hal.get_value("fixed_atc_probe.awaiting") == 2:
            start = time.monotonic()
        if (start is not None and hal.get_value("fixed_atc_probe.step-kind") == 4 and
                hal.get_value("fixed_atc_probe.step-ready")):
            seconds = time.monotonic() - start
            length = hal.get_value("fixed_atc_probe.step-value")
            break
        time.sleep(0.002)
    else:
        raise TimeoutError("the two-stage probe never wrote a length")
    # The tool goes home to its pocket; fetch it again for the next measurement.
    wait_for(lambda: hal.get_value("fixed_atc_probe.state") == 1 and
             stat.interp_state == linuxcnc.INTERP_IDLE, 180, "the load flow to end")
    mdi("T%d M6" % tool, 180)
    return {"seconds": seconds, "length": length}


def stepping(c, program):
    """The prototype's method from loading Z: one 0.2 mm move, one read of the sensor."""
    mdi("G53 G0 Z%.4f" % c["loading"]["z"])
    mdi("G53 G0 X%.4f Y%.4f" % (c["probe_limit"]["x"], c["probe_limit"]["y"]))
    command.mode(linuxcnc.MODE_AUTO)
    command.wait_complete()
    command.program_open(program)
    command.wait_complete()
    start = time.monotonic()
    command.auto(linuxcnc.AUTO_RUN, 0)
    wait_for(lambda: stat.interp_state != linuxcnc.INTERP_IDLE, 30, "the stepping program to start")
    wait_for(lambda: stat.interp_state == linuxcnc.INTERP_IDLE, 600, "the stepping program to end")
    seconds = time.monotonic() - start
    stat.poll()
    z = stat.actual_position[2]
    return {"seconds": seconds, "length": z - c["probe_length_compensation_offset"]}


def all_the_way_program(c, work):
    """The probe as it was measured before issue 42: seek, back-off and latch,
    all at the probe's feed (probe_latch_feed), from loading Z."""
    path = os.path.join(work, "probe_all_the_way.ngc")
    with open(path, "w") as f:
        f.write("""(A touch probe measured at its own feed all the way down, as before issue 42)
(G49: machine Z, the sim having no work offsets)
G49 G90
G38.3 Z%(limit).4f F%(feed).4f
G91 G1 Z%(backoff).4f F%(feed).4f
G90 G38.3 Z%(limit).4f F%(feed).4f
M2
""" % {"limit": c["probe_limit"]["z"], "feed": c.get("probe_latch_feed", 25.0),
       "backoff": c.get("probe_backoff", 2.0)})
    return path


def probe_input_from(signal):
    """motion.probe-input from `signal`: with the probe in the spindle the
    spindle guard gives motion the probe's input (fatc-probe-input), and the
    program of the probe measured as before must touch the sensor (fatc-sensor)."""
    subprocess.run(["halcmd", "unlinkp", "motion.probe-input"], check=True)
    subprocess.run(["halcmd", "linkps", "motion.probe-input", signal], check=True)


def all_the_way(c, program):
    probe_input_from("fatc-sensor")
    try:
        result = stepping(c, program)
    finally:
        probe_input_from("fatc-probe-input")
    stat.poll()
    result["length"] = stat.probed_position[2] - c["probe_length_compensation_offset"]
    return result


def stepping_program(c, feed, work):
    path = os.path.join(work, "stepping_probe.ngc")
    with open(path, "w") as f:
        f.write("""(The prototype's probe: down 0.2 mm per move, the sensor read between moves)
(G49: #5422 is then the machine Z, the sim having no work offsets)
G49 G91
o100 while [#5422 GT %(limit).4f]
  G1 Z-0.2 F%(feed).1f
  M66 P%(input)s L0
  o101 if [#5399 EQ 1]
    o100 break
  o101 endif
o100 endwhile
G90
M2
""" % {"limit": c["probe_limit"]["z"], "feed": feed, "input": int(SENSOR_INPUT)})
    return path


def main():
    own = hal.component("fatc-bench")  # hal.get_value needs a component of our own
    own.ready()
    results = {"sensor_z": SENSOR_Z, "repeats": REPEATS, "two_stage": [], "stepping": [],
               "probe_approach": [], "probe_all_the_way": [], "error": None}
    try:
        c = config()
        results["config"] = {k: c.get(k) for k in ("probe_seek_feed", "probe_latch_feed", "probe_backoff",
                                                  "probe_length_compensation_offset", "tools")}
        results["truth"] = SENSOR_Z - c["probe_length_compensation_offset"]
        driver.bring_up()
        hal.set_p("fatc-sensor.z-trip", str(SENSOR_Z))
        subprocess.run(["halcmd", "net", "fatc-sensor", "motion.digital-in-" + SENSOR_INPUT], check=True)
        mdi("T%d M6" % TOOL, 180)
        feed = c.get("probe_seek_feed", 300.0)
        program = stepping_program(c, feed, os.path.dirname(sys.argv[2]))
        for _ in range(REPEATS):
            results["two_stage"].append(two_stage())
            results["stepping"].append(stepping(c, program))
        mdi("T%d M6" % PROBE, 180)
        program = all_the_way_program(c, os.path.dirname(sys.argv[2]))
        for _ in range(REPEATS):
            results["probe_approach"].append(two_stage(PROBE))
            results["probe_all_the_way"].append(all_the_way(c, program))
    except Exception as e:  # reported by the printer; LinuxCNC must still shut down
        results["error"] = "%s: %s (last messages: %s)" % (type(e).__name__, e, driver.messages[-4:])
    json.dump(results, open(os.environ["FATC_RESULTS"], "w"), indent=1)


if __name__ == "__main__":
    main()
