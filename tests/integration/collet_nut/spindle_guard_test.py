#!/usr/bin/python3
"""fatc-spindle-guard (src/rt/fatc_spindle_guard.comp) under halrun, loaded
alone by spindle_guard_test.sh: each row sets the changer's and LinuxCNC's
inputs, keeps the heartbeat toggling or stops it, and reads the outputs back
once they had time to follow. LinuxCNC asks for the spindle throughout
(spindle-on-in, a speed). Prints each row; writes pass or fail into the file
it is given."""
import sys
import threading
import time

import hal

G = "fatc-spindle-guard."
SPEED = 100.0  # what motion gives the drive
BEATING = threading.Event()


def beat():
    """The component's heartbeat: a toggle every 5 ms while BEATING."""
    level = False
    while True:
        if BEATING.is_set():
            level = not level
            hal.set_p(G + "heartbeat", "1" if level else "0")
        time.sleep(0.005)


def settle(until, timeout=2.0):
    """Waits until `until()` or the time-out; the outputs then are the row's."""
    end = time.monotonic() + timeout
    while not until() and time.monotonic() < end:
        time.sleep(0.01)
    time.sleep(0.02)  # a 1 ms thread: twenty more periods


failures = []


# name; inputs: changer-busy, changer-spindle, probe-in-spindle, the heartbeat
# toggling; wanted: the spindle runs, held-for-change, held (and so refused, inhibit).
ROWS = [
    ("idle: the operator's spindle", False, False, False, True, True, False, False),
    ("busy, the changer not asking: held", True, False, False, True, False, True, False),
    ("busy, the changer asking and alive: runs", True, True, False, True, True, False, False),
    ("busy, asking, heartbeat stopped: held", True, True, False, False, False, True, False),
    ("not busy, asking, heartbeat stopped: held", False, True, False, False, False, True, False),
    ("busy, asking, heartbeat back: runs", True, True, False, True, True, False, False),
    ("a probe in the spindle, the changer asking: probe hold first", True, True, True, True, False, False, True),
    ("a probe in the spindle, idle: held and refused", False, False, True, True, False, False, True),
    ("the probe out, idle: runs", False, False, False, True, True, False, False),
]


def row(name, busy, asked, probe, alive, expect):
    for pin, value in (("changer-busy", busy), ("changer-spindle", asked), ("probe-in-spindle", probe)):
        hal.set_p(G + pin, "1" if value else "0")
    if alive:
        BEATING.set()
    else:
        BEATING.clear()
    # A stopped heartbeat is seen after the guard's timeout (0.5 s).
    settle(lambda: hal.get_value(G + "alive") == alive)
    got = {pin: hal.get_value(G + pin) for pin in expect}
    good = got == expect and hal.get_value(G + "alive") == alive
    print("%s: %s: %s" % ("ok" if good else "FAIL", name,
                          ", ".join("%s=%s (want %s)" % (p, got[p], expect[p]) for p in expect)))
    if not good:
        failures.append(name)


def outputs(runs, held_for_change, held):
    return {"spindle-on": runs, "speed-out": SPEED if runs else 0.0, "held-for-change": held_for_change,
            "held": held, "refused": held, "inhibit": held}


def main():
    component = hal.component("fatc-guard-test")
    component.ready()
    threading.Thread(target=beat, daemon=True).start()
    hal.set_p(G + "spindle-on-in", "1")
    hal.set_p(G + "speed-in", repr(SPEED))
    hal.set_p(G + "speed-command", "20")
    for name, busy, asked, probe, alive, runs, held_for_change, held in ROWS:
        row(name, busy, asked, probe, alive, outputs(runs, held_for_change, held))
    with open(sys.argv[1], "w") as verdict:
        verdict.write("fail" if failures else "pass")
    print("%d rows failed" % len(failures) if failures else "every row held")


if __name__ == "__main__":
    main()
