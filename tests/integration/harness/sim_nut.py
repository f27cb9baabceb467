"""The simulated collet-nut magazine (src/rt/fatc_sim_nut.comp,
config/sim/sim_nut.hal) as a machinist sees it and handles it: which pocket
holds a nut, whether the spindle holds one and from which pocket it came,
seated or not; and their hands, which screw a nut on or off the spindle and
put one into a pocket or take it out. Pocket numbers as config.json's (1 is
the component's index 0). The tools of the runs that use it live in the
pocket of their own number, so a nut from pocket N is tool N."""
import time

import hal

NUT = "fatc-sim-nut."


def _pin(name):
    return hal.get_value(NUT + name)


def truth(pockets):
    """{"spindle": the pocket number of the nut on the spindle (0 none),
    "seated": it is screwed home, "pockets": {N: holds a nut}}."""
    return {"spindle": _pin("nut-on-spindle-from"), "seated": bool(_pin("seated")),
            "pockets": {p: bool(_pin("nut-in-pocket-%d" % (p - 1))) for p in pockets}}


def _taken():
    """Long enough for the component, in the 1 ms servo thread, to have read
    an init pin just set: its outputs may already show what that asks, so
    there is nothing of its own to wait on."""
    time.sleep(0.02)


def _until(condition, what, timeout=5.0):
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            raise TimeoutError("the simulated magazine: " + what)
        time.sleep(0.005)


def put_in_pocket(pocket, holds):
    """A nut put into the pocket (True) or taken out of it (False). The
    component takes its init pins on a change only: a value it already has
    is changed away first."""
    init = NUT + "nut-in-pocket-init-%d" % (pocket - 1)
    out = "nut-in-pocket-%d" % (pocket - 1)
    if bool(hal.get_value(init)) == holds:
        hal.set_p(init, "0" if holds else "1")
        _taken()
    hal.set_p(init, "1" if holds else "0")
    _until(lambda: bool(_pin(out)) == holds, "pocket %d %s" % (pocket, "full" if holds else "empty"))


def screw_on_by_hand(pocket):
    """The spindle's nut taken off (0) or a seated nut from `pocket` screwed
    on by hand (nut-on-spindle-init; any value of 0 or less is none)."""
    init = NUT + "nut-on-spindle-init"
    empty = -1 if hal.get_value(init) != -1 else -2
    hal.set_p(init, str(empty))
    _taken()
    _until(lambda: not _pin("nut-on-spindle"), "the spindle's nut off")
    if pocket:
        hal.set_p(init, str(pocket))
        _until(lambda: _pin("nut-on-spindle-from") == pocket and _pin("seated"),
               "a seated nut from pocket %d on the spindle" % pocket)


def spindle_still():
    """The spindle stands and nothing asks it to turn: LinuxCNC's spindle off,
    the drive's run and speed from fatc-spindle-guard off and 0, and the
    simulated spindle's real speed (limit_speed's ramp) exactly 0."""
    return (not hal.get_value("spindle.0.on") and not hal.get_value("fatc-spindle-guard.spindle-on")
            and hal.get_value("fatc-spindle-guard.speed-out") == 0
            and hal.get_value("limit_speed.out") == 0)


def spindle_now():
    """What says the spindle turns or stands, for the record."""
    return {"on": bool(hal.get_value("spindle.0.on")),
            "drive_on": bool(hal.get_value("fatc-spindle-guard.spindle-on")),
            "drive_speed": hal.get_value("fatc-spindle-guard.speed-out"),
            "speed": hal.get_value("limit_speed.out"),
            "held_for_change": bool(hal.get_value("fatc-spindle-guard.held-for-change"))}
