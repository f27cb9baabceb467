#!/usr/bin/python3
"""The simulated collet-nut magazine (src/rt/fatc_sim_nut.comp), loaded under
halrun by sim_nut_test.sh with config/sim/sim_nut.hal's values: the test
moves the nose, turns the spindle (speed-in, signed rpm) and reads back
where the nuts are, what the recognition beam sees and the speed the
spindle's at-speed compares (a near, as basic_sim.tcl's near_speed).
Prints each case; writes pass or fail into the file it is given."""
import sys
import time

import hal

N = "fatc-sim-nut."
AT_SPEED = "fatc-test-at-speed."
failures = []


def value(pin):
    return hal.get_value(N + pin)


def setp(pin, v):
    hal.set_p(pin, repr(v) if isinstance(v, float) else str(int(v)))


def nose(x, y, z):
    for axis, v in zip("xyz", (x, y, z)):
        setp(N + axis, float(v))


def spin(rpm):
    """The spindle at `rpm` at once (the test has no ramp), and the command
    at-speed compares with."""
    setp(N + "speed-in", float(rpm))
    setp(AT_SPEED + "in1", float(rpm))


def wait_for(what, timeout=3.0):
    """Seconds until `what()`, or None after the time-out."""
    began = time.monotonic()
    while time.monotonic() - began < timeout:
        if what():
            return time.monotonic() - began
        time.sleep(0.001)
    return None


def settle():
    time.sleep(0.02)  # a 1 ms thread: twenty periods


def check(name, good, detail=""):
    print("%s: %s%s" % ("ok" if good else "FAIL", name, ": " + detail if detail else ""))
    if not good:
        failures.append(name)


def state():
    return "on the spindle %s (from %d, seated %s), in pocket 1..3 %s, turns %.2f, seat turns %.2f" % (
        value("nut-on-spindle"), value("nut-on-spindle-from"), value("seated"),
        [value("nut-in-pocket-%d" % k) for k in range(3)], value("turns"), value("seat-turns"))


def nothing_turns(name, pocket, rpm, z, seconds, expect_on, expect_in_pocket):
    """The nose held `seconds` at `z` over pocket index `pocket` at `rpm`:
    no turn counts and the nut stays where it was."""
    nose(PX[pocket], PY[pocket], z)
    spin(rpm)
    time.sleep(seconds)
    good = (value("turns") == 0 and value("nut-on-spindle") == expect_on
            and value("nut-in-pocket-%d" % pocket) == expect_in_pocket)
    spin(0)
    check(name, good, state())


def timed(name, what, turns, rpm):
    """`what()` within the time `turns` take at `rpm` (a little jitter allowed)."""
    expected = turns * 60.0 / abs(rpm)
    took = wait_for(what)
    good = took is not None and expected * 0.9 - 0.003 <= took <= expected + 0.1
    check(name, good, "%s s, %.3f s expected; %s" % (
        "never" if took is None else "%.3f" % took, expected, state()))


def beam(name, pocket_xy, z, cut):
    nose(pocket_xy[0], pocket_xy[1], z)
    settle()
    check(name, value("beam-cut") == cut, "nose at z %.1f: beam-cut %s" % (z, value("beam-cut")))


def main():
    global PX, PY
    component = hal.component("fatc-nut-test")
    component.ready()
    PX = [value("pocket-x-%d" % k) for k in range(3)]
    PY = [value("pocket-y-%d" % k) for k in range(3)]
    engage, window = value("engage-z"), value("window")
    rpm = (value("rpm-min") + value("rpm-max")) / 2.0
    inside, above = engage + window / 2.0, engage + window + 1.0
    turns_off, turns_on, turns_seat = value("turns-off"), value("turns-on"), value("turns-seat")
    zone_1, zone_2 = -60.0, -54.0  # config/sim/collet_nut.json's recognition
    hold = 5 * max(turns_off, turns_on + turns_seat) * 60.0 / rpm  # long enough for any screwing, five times

    nose(0, 0, 0)
    setp(N + "nut-in-pocket-init-0", 1)
    setp(N + "nut-in-pocket-init-1", 1)
    settle()
    check("the starting magazine: nuts in pockets 1 and 2, the spindle empty",
          value("nut-in-pocket-0") and value("nut-in-pocket-1") and not value("nut-in-pocket-2")
          and not value("nut-on-spindle"), state())

    # Screwing on, and what keeps a nut from going on.
    setp(N + "reverse", 1)
    nothing_turns("forward in the window, the drive miswired (reverse): nothing screws on", 0, rpm,
                  inside, hold, False, True)
    setp(N + "reverse", 0)
    nothing_turns("reversing (M4) in the window over a nut, the spindle empty: nothing screws on", 0, -rpm,
                  inside, hold, False, True)
    nothing_turns("forward above the window: nothing screws on", 0, rpm, above, hold, False, True)
    nothing_turns("forward too fast (%.0f rpm, out of the band): nothing screws on" % (value("rpm-max") + 200),
                  0, value("rpm-max") + 200, inside, hold, False, True)
    setp(N + "missing-0", 1)
    settle()
    check("missing-0: pocket 1 reads empty", not value("nut-in-pocket-0"), state())
    nothing_turns("missing-0, forward in the window: nothing to screw on", 0, rpm, inside, hold, False, False)
    setp(N + "missing-0", 0)
    settle()
    check("missing-0 cleared: pocket 1's nut back", value("nut-in-pocket-0"), state())

    nose(PX[0], PY[0], inside)
    spin(rpm)
    timed("forward in the window over pocket 1: on the spindle after turns-on",
          lambda: value("nut-on-spindle"), turns_on, rpm)
    check("just on: from pocket 1, pocket 1 empty", value("nut-on-spindle-from") == 1
          and not value("nut-in-pocket-0"), state())
    timed("still turning in the window: seated after turns-seat more", lambda: value("seated"), turns_seat, rpm)
    spin(0)
    beam("seated, zone 1: the beam cut", (PX[0], PY[0]), zone_1, True)
    beam("seated, zone 2: the beam clear", (PX[0], PY[0]), zone_2, False)
    beam("seated, zone 1 but off the magazine: the beam clear", (PX[0] - 20, PY[0]), zone_1, False)

    # Screwing off.
    nothing_turns("forward in the window with the nut on: it stays on", 0, rpm, inside, hold, True, False)
    setp(N + "reverse", 1)
    nothing_turns("reversing, the drive miswired (reverse): the nut stays on", 0, -rpm, inside, hold, True, False)
    setp(N + "reverse", 0)
    nothing_turns("reversing above the window: the nut stays on", 0, -rpm, above, hold, True, False)
    nose(PX[0], PY[0], inside)
    spin(-rpm)
    timed("reversing in the window over pocket 1: in the pocket after turns-off",
          lambda: value("nut-in-pocket-0") and not value("nut-on-spindle"), turns_off, rpm)
    spin(0)
    beam("unloaded, zone 1: the beam clear", (PX[0], PY[0]), zone_1, False)

    # A cross-threaded nut: on, never seated; then seated by a later plunge.
    setp(N + "cross-thread", 1)
    nose(PX[1], PY[1], inside)
    spin(rpm)
    timed("cross-thread: forward over pocket 2, on after turns-on", lambda: value("nut-on-spindle"), turns_on, rpm)
    time.sleep(hold)
    check("cross-thread: never seated", value("nut-on-spindle-from") == 2 and not value("seated")
          and value("seat-turns") == 0, state())
    spin(0)
    beam("unseated, zone 1: the beam cut", (PX[1], PY[1]), zone_1, True)
    beam("unseated, zone 2: the beam cut (it hangs low)", (PX[1], PY[1]), zone_2, True)
    setp(N + "cross-thread", 0)
    nose(PX[1], PY[1], inside)
    spin(rpm)
    timed("the next plunge, not cross-threaded: seated after turns-seat", lambda: value("seated"), turns_seat, rpm)
    spin(0)

    # A stall: the spindle stops under load, the speed reads 0 and at-speed drops.
    nose(PX[1], PY[1], above)
    spin(-rpm)
    settle()
    check("reversing above the window: speed-out the spindle's, at speed",
          value("speed-out") == -rpm and hal.get_value(AT_SPEED + "out"), "speed-out %.0f" % value("speed-out"))
    setp(N + "stall", 1)
    nose(PX[1], PY[1], inside)
    time.sleep(hold)
    check("stall in the window, the nut on: speed-out 0, at-speed off, the nut stays on",
          value("speed-out") == 0 and value("stalled") and not hal.get_value(AT_SPEED + "out")
          and value("nut-on-spindle") and value("turns") == 0,
          "speed-out %.0f, at-speed %s; %s" % (value("speed-out"), hal.get_value(AT_SPEED + "out"), state()))
    nose(PX[1], PY[1], above)
    settle()
    check("stall, out of the window: the speed back", value("speed-out") == -rpm and not value("stalled"),
          "speed-out %.0f" % value("speed-out"))
    setp(N + "stall", 0)
    nose(PX[1], PY[1], inside)
    timed("no stall: reversing over pocket 2 screws it off", lambda: value("nut-in-pocket-1"), turns_off, rpm)
    setp(N + "stall", 1)
    nose(PX[2], PY[2], inside)
    settle()
    check("stall, the spindle empty in pocket 3's empty window (no load): the speed stays",
          value("speed-out") == -rpm and not value("stalled"), "speed-out %.0f" % value("speed-out"))
    setp(N + "stall", 0)
    spin(0)

    setp(N + "nut-on-spindle-init", 3)
    settle()
    check("nut-on-spindle-init 3: a seated nut from pocket 3 on the spindle",
          value("nut-on-spindle") and value("nut-on-spindle-from") == 3 and value("seated"), state())
    setp(N + "nut-on-spindle-init", 0)
    settle()
    check("nut-on-spindle-init 0: the spindle empty", not value("nut-on-spindle"), state())

    with open(sys.argv[1], "w") as verdict:
        verdict.write("fail" if failures else "pass")
    print("%d cases failed" % len(failures) if failures else "every case held")


if __name__ == "__main__":
    main()
