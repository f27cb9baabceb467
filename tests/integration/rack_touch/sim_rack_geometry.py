#!/usr/bin/python3
"""The simulated rack's geometry (src/rt/fatc_sim_rack.comp), loaded under
halrun by sim_rack_geometry.sh with config/sim/sim_rack.hal's plate: each
touch a probe makes on it, the nose a hair short of the true contact and a
hair past it, read back from the module's `touching` after its function ran.
Prints each case; writes pass or fail into the file it is given."""
import math
import sys
import time

import hal

R = "fatc-sim-rack."
HAIR = 1e-5  # mm: both sides of every contact


def touching(x, y, z, shift=(0.0, 0.0, 0.0), also=False):
    for axis, value in zip("xyz", shift):
        hal.set_p(R + "shift-" + axis, repr(value))
    hal.set_p(R + "also", "1" if also else "0")
    hal.set_p(R + "x", repr(x))
    hal.set_p(R + "y", repr(y))
    hal.set_p(R + "z", repr(z))
    time.sleep(0.01)  # a 1 ms thread: ten periods
    return hal.get_value(R + "touching"), hal.get_value(R + "out")


failures = []


def contact(name, at, before, past, shift=(0.0, 0.0, 0.0)):
    """`at(d)`: the nose at distance d past the true contact; short of it no touch, past it one."""
    short, _ = touching(*at(-HAIR), shift=shift)
    beyond, _ = touching(*at(HAIR), shift=shift)
    good = short == before and beyond == past
    print("%s: %s: %s short of the contact touching=%s, %s past it touching=%s"
          % ("ok" if good else "FAIL", name, HAIR, short, HAIR, beyond))
    if not good:
        failures.append(name)


def main():
    component = hal.component("fatc-geometry")
    component.ready()
    top, bottom, bore, length, ball = (hal.get_value(R + p) for p in (
        "top-z", "bottom-z", "bore-diameter", "probe-length", "stylus-radius"))
    x_min, x_max = hal.get_value(R + "x-min"), hal.get_value(R + "x-max")
    px, py = hal.get_value(R + "pocket-x-0"), hal.get_value(R + "pocket-y-0")
    between = (px + hal.get_value(R + "pocket-x-1")) / 2  # on the top face, between bores 1 and 2
    # The nose with the ball's lowest point 5 mm below the top face (its lowest point is `length` below).
    wall_z = top - 5.0 + length
    wall = bore / 2 - ball  # the ball's centre, and so the nose, from the bore's axis at a wall touch
    for name, (ux, uy) in (("+X wall", (1, 0)), ("-X wall", (-1, 0)), ("+Y wall", (0, 1)),
                           ("-Y wall", (0, -1)), ("wall at 30 degrees", (math.cos(math.pi / 6),
                                                                         math.sin(math.pi / 6)))):
        contact(name + " of pocket 1's bore",
                lambda d, ux=ux, uy=uy: (px + ux * (wall + d), py + uy * (wall + d), wall_z), False, True)
    contact("+X wall, the rack shifted 0.5 in X", lambda d: (px + 0.5 + wall + d, py, wall_z), False, True,
            shift=(0.5, 0.0, 0.0))
    contact("-X wall, the rack shifted 0.5 in X", lambda d: (px + 0.5 - wall - d, py, wall_z), False, True,
            shift=(0.5, 0.0, 0.0))
    contact("the top face from above, between bores 1 and 2", lambda d: (between, py, top + length - d),
            False, True)
    contact("the top face, the rack shifted 0.5 in Z", lambda d: (between, py, top + 0.5 + length - d),
            False, True, shift=(0.0, 0.0, 0.5))
    # The ball's centre 0.5 inside the bore's rim: it meets the rim's edge.
    rim = math.sqrt(ball ** 2 - 0.5 ** 2)
    contact("the rim of the bore from above", lambda d: (px + bore / 2 - 0.5, py, top + rim + length - ball - d),
            False, True)
    contact("the plate's outside face x-min from outside", lambda d: (x_min - ball + d, py, wall_z), False, True)
    contact("the bottom face from below", lambda d: (between, py, bottom - 2 * ball + length + d), False, True)
    contact("down the bore's axis: never", lambda d: (px, py, top - 10 + length - d), False, False)
    no_rack, out = touching(x_max + 100.0, py, wall_z, also=True)
    good = not no_rack and out
    print("%s: another probe's input (also) passes to out, the rack not touched" % ("ok" if good else "FAIL"))
    if not good:
        failures.append("also")
    verdict = "fail" if failures else "pass"
    if failures:
        print("FAIL: %d of the simulated rack's contacts are wrong: %s" % (len(failures), ", ".join(failures)))
    with open(sys.argv[1], "w") as f:
        f.write(verdict + "\n")


if __name__ == "__main__":
    main()
