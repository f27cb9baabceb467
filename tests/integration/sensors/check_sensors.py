#!/usr/bin/env python3
"""Checks one scenario of the sensors run (scenarios_sensors.json: every
sensor wired, the rack simulated by rack_sim.py) against what LinuxCNC, the
component's files and the simulated rack report.
   check_sensors.py RESULTS.json CONFIG.json SCENARIO
Prints what it checked; exits 1 on the first failed expectation."""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
from check import Rack, distinct, fail, in_pockets, load_results, near, ok, rising_samples, said, scenario  # noqa: E402

GRIP_FAULT = "tool 2 not in the spindle after the chuck closed at pocket 2 (tool-present off, retried once)"
AIR_FAULT = "air pressure low (air-pressure-ok off) before the chuck opened to flush it; it stayed closed"
DISAGREEMENT = ("the sensors disagree with the saved tool state; pocket 1 reads empty "
                "(pocket-occupied-1 off), but tool 1 is recorded in it")


COVER_FAULT = ("the rack cover did not open within rack_cover.timeout_seconds (2.0 s, "
               "rack-cover-opened off): nothing moved into the rack")


def rack_log(results_path):
    """What the simulated rack did, in order: gripped, released, grip failed, ..."""
    path = os.path.join(os.path.dirname(os.path.abspath(results_path)), "rack_sim.log")
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]


def rises(samples, pin):
    """The times `pin` went high."""
    return [s["t"] for s in rising_samples(samples, pin)]


def intervals(samples, pin):
    """(from, to) of each time `pin` was high."""
    spans, since = [], None
    for s in samples:
        if s[pin] and since is None:
            since = s["t"]
        elif not s[pin] and since is not None:
            spans.append((since, s["t"]))
            since = None
    if since is not None:
        spans.append((since, samples[-1]["t"]))
    return spans


def check_cover_and_blast(r):
    """The rack cover opened before the first move and closed after the last;
    the chuck acted at a pocket only with the cover reading open; the air blast
    blew only while the chuck was open."""
    samples = r["samples"]
    opened = rises(samples, "fixed_atc_probe.rack-cover-opened")
    first = samples[0]["pos"]
    moved = next((s["t"] for s in samples if not near(s["pos"], first)), None)
    if not opened or moved is None or moved < opened[0]:
        fail("the machine moved at %s s, the rack cover read open at %s" % (moved, opened))
    ok("rack-cover-opened at %.2f s, the first move at %.2f s" % (opened[0], moved))
    bad = [s["t"] for s in samples if s["fixed_atc_probe.chuck"] and s["fixed_atc_probe.pocket-served"]
           and not s["fixed_atc_probe.rack-cover-opened"]]
    if bad:
        fail("the chuck acted at a pocket with the rack cover not reading open, at %s" % bad[:5])
    # The changer closes the cover after the last change and does not wait for
    # it (ComparingSensors does, up to rack_cover.timeout_seconds, faulting
    # after): LinuxCNC 2.10 can end the program first, so the scenario's
    # settle_pin waits for rack-cover-closed before the last sample.
    last = at_end(r)
    if last["fixed_atc_probe.rack-cover-open"] or not last["fixed_atc_probe.rack-cover-closed"]:
        fail("the rack cover is not closed at the end: %s" % last)
    ok("the chuck acted at a pocket only with the cover open (%d rises of rack-cover-opened); "
       "closed at the end" % len(opened))
    chuck = intervals(samples, "fixed_atc_probe.chuck")
    blasts = intervals(samples, "fixed_atc_probe.air-blast")
    if len(blasts) < 2:
        fail("the air blast blew %d times, expected at every return and fetch" % len(blasts))
    slack = 0.05  # the sampler reads one pin after the other
    for on, off in blasts:
        if not any(c_on - slack <= on and off <= c_off + slack for c_on, c_off in chuck):
            fail("the air blast blew from %.3f to %.3f s outside an opening of the chuck %s"
                 % (on, off, chuck))
    ok("the air blast blew %d times, each within an opening of the chuck" % len(blasts))


def settled(r):
    """When the program's scenario had settled: the 'faulted' snapshot, before
    the operator's confirmation, or the end."""
    return r.get("snapshots", {}).get("faulted", {}).get("t", float("inf"))


def at_end(r):
    """The last sample of the program, before any operator's confirmation."""
    return [s for s in r["samples"] if s["t"] <= settled(r)][-1]


def faulted_with(r, words):
    last = at_end(r)
    if not last["fixed_atc_probe.fault"]:
        fail("the changer is not in fault at the end")
    said(r, words)
    activity = r["status_file"].get("activity", "")
    if activity != "fault: " + words:
        fail("the status file's activity is %r, expected the fault's words" % activity)
    texts = [m["text"] for m in r["status_file"].get("messages", [])]
    if not any(words in t for t in texts):
        fail("the status file's messages do not carry the fault: %s" % texts)
    ok("faulted, and the panel's status file says: %s" % activity)


def still_after(r, t):
    """Nothing moved after `t` (seconds into the scenario), until the operator confirmed."""
    after = [s for s in r["samples"] if t <= s["t"] <= settled(r)]
    first = after[0]["pos"]
    for s in after:
        if not near(s["pos"], first):
            fail("the machine moved after the fault: %s -> %s at %.2f s" % (first, s["pos"], s["t"]))
    ok("nothing moved after %.2f s (%d samples at %s)" % (t, len(after), [round(v, 3) for v in first]))


def fault_time(r):
    for s in r["samples"]:
        if s["fixed_atc_probe.fault"]:
            return s["t"]
    fail("no sample shows the fault")


def check_sensors_changes(r, rack, log):
    if any(s["fixed_atc_probe.fault"] for s in r["samples"]):
        fail("a fault during the changes: %s" % r["messages"])
    tools = distinct(r["samples"], "tool_in_spindle")
    if tools[-3:] != [1, 3, 0]:
        fail("tool in spindle went %s, expected ... 1, 3, 0" % tools)
    ok("tool in spindle went %s with every sensor wired and checked" % tools)
    moved = [(e["what"], e.get("tool"), e.get("pocket")) for e in log
             if e["what"] in ("gripped", "released", "dropped", "grip failed")]
    expected = [("gripped", 1, 1), ("released", 1, 1), ("gripped", 3, 3), ("released", 3, 3)]
    if moved[:4] != expected:
        fail("the simulated rack saw %s, expected %s" % (moved[:4], expected))
    ok("the simulated rack: %s" % moved[:4])
    if in_pockets(r["state_file"]) != sorted(rack.pockets):
        fail("the state file says %s in their pockets" % in_pockets(r["state_file"]))
    ok("every tool home again, as the state file says")
    check_cover_and_blast(r)


def check_sensors_grip_fails(r, rack, log):
    faulted_with(r, GRIP_FAULT)
    said(r, "tool 2 not in the spindle after the chuck closed at pocket 2 (tool-present off); "
            "gripping it once more")
    opened = rises(r["samples"], "fatc-chuck-guard.chuck")
    if len(opened) != 3:
        fail("the chuck opened %d times, expected 3 (flush, above pocket 2, once more in it)" % len(opened))
    at_retry = [s for s in r["samples"] if s["t"] >= opened[2]][0]["pos"]
    if not near(at_retry, rack.pocket(2)):
        fail("the chuck opened again at %s, not at pocket 2 %s" % (at_retry, rack.pocket(2)))
    ok("the chuck opened 3 times: the flush, above pocket 2, and once more at pocket 2 %s" % at_retry)
    still_after(r, fault_time(r))
    last = at_end(r)
    if last["interp"] != 1 or last["tool_in_spindle"] != 0:
        fail("the program should have stopped with LinuxCNC's spindle empty: %s" % last)
    if last["fatc-chuck-guard.chuck"]:
        fail("the chuck is open after the fault")
    ok("the program stopped, the chuck closed, LinuxCNC says the spindle is empty")
    if not r["state_file"].get("uncertain"):
        fail("the state file does not mark the spindle uncertain: %s" % r["state_file"])
    ok("the state file marks the spindle uncertain: %s" % r["state_file"]["in_progress"])
    failed = [e for e in log if e["what"] == "grip failed" and e["tool"] == 2]
    if len(failed) != 2:
        fail("the simulated rack saw %d failed grips of tool 2, expected 2" % len(failed))
    ok("the simulated rack saw both grips of tool 2 fail; tool 2 stayed in pocket 2")
    confirmed = r["snapshots"]["confirmed"]
    if confirmed["pins"]["fixed_atc_probe.state"] != 1 or confirmed["state_file"].get("uncertain"):
        fail("not idle and certain after the confirmation: %s" % confirmed)
    ok("idle after the operator confirmed: spindle empty, pocket 2 holds tool 2")


def check_sensors_air_refused(r, rack, log):
    said(r, "M6 T4 refused: air pressure is low (air-pressure-ok off): the chuck cannot open")
    first = r["samples"][0]["pos"]
    if any(not near(s["pos"], first) for s in r["samples"]):
        fail("the machine moved although the M6 was refused")
    if any(s["fatc-chuck-guard.chuck"] for s in r["samples"]) or r["samples"][-1]["fixed_atc_probe.fault"]:
        fail("the chuck opened or the changer faulted")
    ok("M6 T4 refused without air: nothing moved, the chuck stayed closed, no fault")


def check_sensors_air_lost(r, rack, log):
    faulted_with(r, AIR_FAULT)
    if rises(r["samples"], "fatc-chuck-guard.chuck"):
        fail("the chuck opened without air")
    ok("the chuck never opened")
    still_after(r, fault_time(r))
    if r["state_file"].get("uncertain"):
        fail("the spindle is marked uncertain though the chuck never moved")
    ok("the tool state stays certain: the chuck never moved")
    if not any(e["what"] == "air cut" for e in log):
        fail("the simulated rack never cut the air")


def check_sensors_cover_stuck(r, rack, log):
    faulted_with(r, COVER_FAULT)
    still_after(r, 0.0)
    if rises(r["samples"], "fixed_atc_probe.chuck"):
        fail("the chuck opened although the cover never did")
    if r["state_file"].get("uncertain"):
        fail("the spindle is marked uncertain though nothing moved")
    last = at_end(r)
    if not last["fixed_atc_probe.rack-cover-open"] or last["fixed_atc_probe.air-blast"]:
        fail("at the fault the cover output should stay open and the blast be off: %s" % last)
    ok("nothing moved, the state stays certain, the cover stays as it was and the blast is off")


def check_sensors_kill(r, rack, log):
    if r["samples"][-1]["fatc-chuck-guard.alive"]:
        fail("the chuck guard still sees the killed component")
    ok("component killed (pid %s)" % r.get("killed_pid"))


def check_sensors_start_disagree(r, rack, log):
    faulted = r["snapshots"]["faulted"]
    if not faulted["pins"]["fixed_atc_probe.fault"]:
        fail("the restarted component is not in fault")
    said(r, DISAGREEMENT)
    if faulted["status_file"].get("activity") != "fault: " + DISAGREEMENT:
        fail("the status file says %r" % faulted["status_file"].get("activity"))
    ok("restarted with tool 1 gone from its pocket: %s" % faulted["status_file"]["activity"])
    if in_pockets(faulted["state_file"]).count(1) != 1:
        fail("the state file changed before the operator confirmed: %s" % faulted["state_file"])
    said(r, "M6 T3 refused: the changer is in fault")
    ok("M6 refused until the operator confirms")
    said(r, "pocket 1 recorded empty, as pocket-occupied-1 reads (off)")
    confirmed = r["snapshots"]["confirmed"]["state_file"]
    if 1 in in_pockets(confirmed) or confirmed.get("uncertain"):
        fail("after the confirmation the state file says %s" % confirmed)
    ok("after the confirmation the state file has pocket 1 empty: %s" % in_pockets(confirmed))
    if r["samples"][-1]["tool_in_spindle"] != 3 or r["samples"][-1]["fixed_atc_probe.fault"]:
        fail("M6 T3 after the confirmation did not complete: %s" % r["samples"][-1])
    ok("M6 T3 after the confirmation: tool 3 in the spindle")
    if not any(e["what"] == "taken out by hand" and e["tool"] == 1 for e in log):
        fail("the simulated rack never had tool 1 taken out")


ATOM_FAULT = ("after the clamp from G-code tool-present reads the spindle empty (off), but tool 3 "
              "is recorded in it")


def check_sensors_atoms(r, rack, log):
    held = [s for s in r["samples"] if s["fixed_atc_probe.chuck-held"]]
    if not held or any(s["fixed_atc_probe.fault"] for s in held):
        fail("no fault was to come while the release held the chuck open (%d samples)" % len(held))
    ok("released at loading with tool 3, held open %d samples without a fault (tool-present off "
       "once the tool dropped)" % len(held))
    said(r, "chuck released at loading (G-code); tool 3 stays recorded in the spindle")
    if not any(e["what"] == "dropped" and e["tool"] == 3 for e in log):
        fail("the simulated spindle never let go of tool 3")
    faulted_with(r, ATOM_FAULT)
    last = at_end(r)
    if not near(last["pos"], [20.0, 150.0, -10.0]) or last["fixed_atc_probe.chuck"]:
        fail("the program went on past the clamp, or the chuck is open: %s" % last)
    ok("the program stopped at loading with the chuck closed")
    confirmed = r["snapshots"]["confirmed"]
    if confirmed["pins"]["fixed_atc_probe.fault"] or confirmed["state_file"]["spindle"] != 0:
        fail("the operator's answer (spindle empty) did not clear the fault: %s" % confirmed["state_file"])
    ok("confirmed empty: the changer is out of fault, the spindle recorded empty")


IO_TIMINGS = {"chuck-release": ("drawbar opened in ", 1.0), "chuck-clamp": ("drawbar closed in ", 1.0),
              "cover-open": ("rack cover opened in ", 2.0), "cover-close": ("rack cover closed in ", 2.0)}


def io_command(r, name, code):
    run = r["operator_commands"][name]
    if run["code"] != code:
        fail("--operator %s exited %s, not %s: %s %s" % (name, run["code"], code, run["out"], run["err"]))
    return run["out"]


def check_sensors_io_check(r, rack, log):
    """The I/O check drives each output of the simulated rack once and reads its
    sensor back with the time; with the spindle on a release is refused and the
    chuck never moves; the state file and the tool table are as they were."""
    shown = io_command(r, "sensors", 0)
    for line in ("drawbar-closed: on, expected on (the chuck is clamped)",
                 "drawbar-open: off, expected off (the chuck is clamped)",
                 "rack-cover-closed: on, expected on (the cover is commanded closed)",
                 "chuck-release: allowed"):
        if line not in shown:
            fail("--operator io does not show %r: %s" % (line, shown))
    ok("--operator io shows the sensors against the belief, and what may be driven")
    for name, (words, timeout) in IO_TIMINGS.items():
        out = io_command(r, name, 0)
        if words not in out:
            fail("--operator io:%s says no time: %s" % (name, out))
        seconds = float(out.split(words, 1)[1].split(" s;", 1)[0])
        wanted = "your timeout %g s" % timeout
        if not 0.0 < seconds < timeout or wanted not in out:
            fail("io:%s answered in %s s, not within %s: %s" % (name, seconds, wanted, out))
        ok("io:%s: %s" % (name, out.strip().splitlines()[-2]))
    if r["snapshots"]["released"]["pins"]["fixed_atc_probe.chuck"] is not True:
        fail("the chuck output was not on after io:chuck-release")
    ok("the chuck output on after the release, the simulated drawbar open (read from HAL)")
    if "air blast on for 1.0 s" not in io_command(r, "air-blast", 0):
        fail("io:air-blast did not say what it drove")
    if not any(s["fixed_atc_probe.air-blast"] for s in r["samples"]):
        fail("air-blast never seen on")
    ok("io:air-blast: air-blast on, then off again")
    refused = io_command(r, "refused", 1)
    if "refused: the spindle is on" not in refused:
        fail("io:chuck-release with the spindle on was not refused for it: %s" % refused)
    spun = [s for s in r["samples"] if s["spindle.0.on"]]
    if not spun or any(s["fixed_atc_probe.chuck"] or s["fatc-chuck-guard.chuck"] for s in spun):
        fail("the chuck moved while the spindle was on (%d samples)" % len(spun))
    ok("spindle on: io:chuck-release refused, the chuck closed in all %d samples" % len(spun))
    before, after = r["snapshots"]["before"], r["snapshots"]["after"]
    if before["state_file"] != after["state_file"]:
        fail("the state file changed: %s -> %s" % (before["state_file"], after["state_file"]))
    tables = r["tool_tables"]
    if any(tables["before"][k] != tables["after"][k] for k in ("file", "stat")):
        fail("the tool table changed: %s -> %s" % (tables["before"], tables["after"]))
    if after["pins"]["fixed_atc_probe.fault"] or any(s["fixed_atc_probe.fault"] for s in r["samples"]):
        fail("the changer faulted during the I/O check")
    ok("state file and tool table unchanged, no fault: %s" % in_pockets(after["state_file"]))


def main():
    results_path, config_path, name = sys.argv[1:4]
    results = load_results(results_path, name)
    if results.get("error"):
        fail("the run failed: %s" % results["error"])
    rack = Rack(json.load(open(config_path)))
    globals()["check_" + name](scenario(results, name), rack, rack_log(results_path))


if __name__ == "__main__":
    main()
