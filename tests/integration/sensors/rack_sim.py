#!/usr/bin/python3
"""The simulated mill's rack and spindle sensors, for the sensors run
(tests/integration/sensors/rack_sim.hal): a userspace HAL component `fatc-rack-sim`
that knows where every tool is and feeds fixed_atc_probe's optional sensor
inputs from that, as a real rack's switches would.

The tool follows the drawbar: when it opens with a tool in the spindle, the
tool drops into the pocket the spindle nose is in (or out of the machine);
when it closes with the spindle empty in a pocket that holds a tool, the
spindle takes it. The drawbar follows the valve (`chuck`, the fatc-chuck
signal) after 50 ms, and opens only with air. Zero speed is the simulated
mill's own (config/sim/spindle_sim.hal).

Faults to inject, as a test would on a real machine:
  grip-fails        bit: a closing drawbar does not take the tool (not seated)
  air-off           bit: no air pressure while high
  air-cut           bit: a rising edge cuts the air for air-cut-seconds
  take-from-pocket  s32: on a change to N > 0, tool N is taken out of pocket N by hand
  drawbar-seconds   float: how long the drawbar takes to follow the valve (0.05 s)
The operator's hand at `loading` (the soak):
  hand              s32: on a change to N > 0, tool N is put into an empty spindle;
                    to -1, the tool in the spindle is taken out
Where every tool is, for the checks: spindle-tool, and pocket-tool-P (0: empty).

Every change of where a tool is goes to rack_sim.log (one JSON object a
line) in the folder LinuxCNC runs in, for the checks. Where a file
rack_sim.state is in that folder (the soak puts one there), the rack starts
as it says and it is kept up to date: the truth outlives a LinuxCNC start.
    rack_sim.py CONFIG.json"""
import json
import os
import signal
import sys
import time

import hal

PERIOD = 0.005
DRAWBAR_SECONDS = 0.05
COVER_SECONDS = 0.2  # the rack cover takes this long to open or close
AT = 0.01  # mm: the sim follows its commands exactly

running = True


def stop(*_):
    global running
    running = False


def pockets_of(config):
    default = config.get("pocket_default", {})
    pockets = {}
    for key, own in config["pockets"].items():
        p = {**default, **own}
        pockets[int(key)] = (p["x"], p["y"], p["z"])
    return pockets


def main():
    signal.signal(signal.SIGTERM, stop)
    signal.signal(signal.SIGINT, stop)
    pockets = pockets_of(json.load(open(sys.argv[1])))
    c = hal.component("fatc-rack-sim")
    for name in ("x", "y", "z"):
        c.newpin(name, hal.HAL_FLOAT, hal.HAL_IN)
    for name in ("chuck", "grip-fails", "air-off", "air-cut", "cover", "cover-jam"):
        c.newpin(name, hal.HAL_BIT, hal.HAL_IN)
    c.newpin("air-cut-seconds", hal.HAL_FLOAT, hal.HAL_IN)
    c.newpin("take-from-pocket", hal.HAL_S32, hal.HAL_IN)
    c.newpin("hand", hal.HAL_S32, hal.HAL_IN)
    c.newpin("drawbar-seconds", hal.HAL_FLOAT, hal.HAL_IN)
    for name in ("tool-present", "drawbar-open", "drawbar-closed", "air-pressure-ok", "cover-opened",
                 "cover-closed"):
        c.newpin(name, hal.HAL_BIT, hal.HAL_OUT)
    c.newpin("spindle-tool", hal.HAL_S32, hal.HAL_OUT)
    for tool in pockets:
        c.newpin("pocket-occupied-%d" % tool, hal.HAL_BIT, hal.HAL_OUT)
        c.newpin("pocket-tool-%d" % tool, hal.HAL_S32, hal.HAL_OUT)
    c["air-cut-seconds"] = 10.0
    c["drawbar-seconds"] = DRAWBAR_SECONDS
    c.ready()

    log = open("rack_sim.log", "w")  # one run's story

    def note(what, **details):
        log.write(json.dumps({"t": time.time(), "what": what, **details}) + "\n")
        log.flush()

    holder = {tool: tool for tool in pockets}  # pocket -> the tool in it, 0 empty
    spindle = 0
    kept = "rack_sim.state"
    if os.path.exists(kept):
        saved = json.load(open(kept))
        holder = {int(p): t for p, t in saved["holders"].items()}
        spindle = saved["spindle"]
    shown = None
    drawbar_open = False
    moving_since = None
    cover_open = False
    cover_moving_since = None
    air_off_until = 0.0
    last_cut = False
    last_take = 0
    last_hand = 0
    note("start", pockets=holder, spindle=spindle)

    def pocket_at():
        for tool, (x, y, z) in pockets.items():
            if abs(c["x"] - x) < AT and abs(c["y"] - y) < AT and abs(c["z"] - z) < AT:
                return tool
        return 0

    while running:
        now = time.monotonic()
        if c["air-cut"] and not last_cut:
            air_off_until = now + c["air-cut-seconds"]
            note("air cut", seconds=c["air-cut-seconds"])
        last_cut = c["air-cut"]
        air = not c["air-off"] and now >= air_off_until

        # The drawbar follows the valve, opening only with air.
        if c["chuck"] != drawbar_open and (air or not c["chuck"]):
            moving_since = now if moving_since is None else moving_since
            if now - moving_since >= c["drawbar-seconds"]:
                drawbar_open = c["chuck"]
                moving_since = None
                at = pocket_at()
                if drawbar_open and spindle:
                    if at and not holder[at]:
                        holder[at] = spindle
                        note("released", tool=spindle, pocket=at)
                    else:
                        note("dropped", tool=spindle, at=[c["x"], c["y"], c["z"]])
                    spindle = 0
                elif not drawbar_open and not spindle and at and holder[at]:
                    if c["grip-fails"]:
                        note("grip failed", tool=holder[at], pocket=at)
                    else:
                        spindle, holder[at] = holder[at], 0
                        note("gripped", tool=spindle, pocket=at)
        else:
            moving_since = None

        # The rack cover follows its valve after COVER_SECONDS; a jammed one does not open.
        if c["cover"] != cover_open and not (c["cover"] and c["cover-jam"]):
            cover_moving_since = now if cover_moving_since is None else cover_moving_since
            if now - cover_moving_since >= COVER_SECONDS:
                cover_open = c["cover"]
                cover_moving_since = None
                note("cover opened" if cover_open else "cover closed")
        else:
            cover_moving_since = None

        take = c["take-from-pocket"]
        if take != last_take and take > 0 and holder.get(take):
            note("taken out by hand", tool=holder[take], pocket=take)
            holder[take] = 0
        last_take = take

        hand = c["hand"]
        if hand != last_hand and hand > 0 and not spindle:
            spindle = hand
            note("handed in", tool=hand)
        elif hand != last_hand and hand < 0 and spindle:
            note("taken out", tool=spindle)
            spindle = 0
        last_hand = hand

        c["air-pressure-ok"] = air
        c["drawbar-open"] = drawbar_open
        c["drawbar-closed"] = not drawbar_open
        c["cover-opened"] = cover_open and cover_moving_since is None
        c["cover-closed"] = not cover_open and cover_moving_since is None
        c["tool-present"] = spindle != 0
        c["spindle-tool"] = spindle
        for tool in pockets:
            c["pocket-occupied-%d" % tool] = holder[tool] != 0
            c["pocket-tool-%d" % tool] = holder[tool]
        if os.path.exists(kept) and shown != (spindle, sorted(holder.items())):
            shown = (spindle, sorted(holder.items()))
            with open(kept + ".tmp", "w") as f:
                json.dump({"holders": holder, "spindle": spindle}, f)
            os.replace(kept + ".tmp", kept)
        time.sleep(PERIOD)
    note("stop", pockets=holder, spindle=spindle)


if __name__ == "__main__":
    main()
