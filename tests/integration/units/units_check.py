#!/usr/bin/env python3
"""Judges the units run (run_units.sh): on the inch mill with no feed in
config.json, every slow move and probe runs at the physical speed of the mm
defaults (docs/config.md: each inch default the mm one over 25), and the touch
probe T2, new, is measured in less than a third of the time its own feed would
take all the way down from loading.
   units_check.py RESULTS.json CONFIG.json
Prints what it checked and the figures; exits 1 on the first failed expectation."""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
from check import fail, load_results, no_fault, ok, scenario, tool_table_length  # noqa: E402

MM = 25.4
FEED, PROBE = 2, 3  # step-kind codes (src/core/motion/step.hpp)
# The mm defaults in mm/min (unit_default in src/core/config/settings.hpp).
MM_DEFAULTS = {"pocket_feed": 500.0, "probe_seek_feed": 300.0, "probe_latch_feed": 25.0}
SENSOR_Z_MM = -70.0  # [FIXED_ATC_PROBE]SIM_SENSOR_Z of config/sim, before to_inch.py


def steps(samples):
    """Each feed or probe step the executor ran: its kind, its feed in in/min
    (the step-feed pin), the fastest the machine moved during it in in/min, and
    when it ran."""
    found = []
    for s in samples:
        kind, number = s["fixed_atc_probe.step-kind"], s["fixed_atc_probe.step-number"]
        if kind not in (FEED, PROBE):
            continue
        if not found or found[-1]["number"] != number:
            found.append({"number": number, "kind": kind, "feed": s["fixed_atc_probe.step-feed"],
                          "fastest": 0.0, "from": s["t"], "to": s["t"]})
        found[-1]["fastest"] = max(found[-1]["fastest"], abs(s["vel"]) * 60.0)
        found[-1]["to"] = s["t"]
    return found


def main():
    results_path, config_path = sys.argv[1], sys.argv[2]
    r = scenario(load_results(results_path, "units"), "units")
    config = json.load(open(config_path))
    no_fault(r)
    if config["units"] != "inch" or any(k in config for k in MM_DEFAULTS):
        fail("the run's config is not inch with the feeds left out: %s" % config_path)
    run = steps(r["samples"])
    feeds = {}
    for step in run:
        if step["fastest"] > step["feed"] * 1.02:
            fail("step %d (kind %d) moved at %.3f in/min, over its feed %.3f" % (
                step["number"], step["kind"], step["fastest"], step["feed"]))
        feeds.setdefault((step["kind"], round(step["feed"], 6)), []).append(step)
    # The inch defaults, each the same physical speed as its mm one within 1.6 %.
    wanted = {"pocket_feed": (FEED, 20.0), "probe_seek_feed": (PROBE, 12.0),
              "probe_latch_feed": (PROBE, 1.0)}
    for key, (kind, feed) in wanted.items():
        taken = feeds.get((kind, feed))
        if not taken:
            fail("no %s step at %s in/min: the steps ran at %s" % (
                "probe" if kind == PROBE else "feed", feed, sorted(feeds)))
        physical = max(s["fastest"] for s in taken) * MM
        ratio = physical / MM_DEFAULTS[key]
        if not 0.99 <= ratio <= 1.03:
            fail("%s: the machine moved at %.1f mm/min, the mm default is %.0f mm/min (x%.3f)" % (
                key, physical, MM_DEFAULTS[key], ratio))
        ok("%s: %d step(s) at %g in/min, the machine at %.1f mm/min against the mm default %.0f "
           "(x%.3f)" % (key, len(taken), feed, physical, MM_DEFAULTS[key], ratio))
    # The probe: fast to the window above its touch, then at its own feed.
    probes = [s for s in run if s["kind"] == PROBE]
    if len(probes) != 3 or probes[0]["feed"] != 12.0 or probes[1]["feed"] != 1.0:
        fail("the probe of T2 was not an approach at 12 in/min, a seek and a latch at 1 in/min: %s"
             % [(s["kind"], s["feed"]) for s in probes])
    took = probes[-1]["to"] - probes[0]["from"]
    start_z, touch_z = config["loading"]["z"], SENSOR_Z_MM / MM
    backoff = 0.08  # probe_backoff's inch default
    slow_all_the_way = ((start_z - touch_z) + 2 * backoff) / 1.0 * 60.0
    if took >= slow_all_the_way / 3.0:
        fail("the probe of T2 took %.1f s, not under a third of %.1f s at its own feed all the way"
             % (took, slow_all_the_way))
    ok("T2 (a new probe) measured in %.1f s; at its own feed all the way down from loading it "
       "takes %.1f s (x%.2f)" % (took, slow_all_the_way, took / slow_all_the_way))
    length = tool_table_length(r, 2)
    truth = (SENSOR_Z_MM / MM) - config["probe_length_compensation_offset"]
    if abs(length - truth) > 0.0002:
        fail("T2 measured %.5f inch in the tool table, the simulated sensor says %.5f" % (length, truth))
    ok("T2 is %.5f inch in LinuxCNC's tool table (the simulated sensor's %.5f)" % (length, truth))
    if r["samples"][-1]["tool_in_spindle"] != 0:
        fail("the spindle holds T%d at the end, expected empty" % r["samples"][-1]["tool_in_spindle"])
    ok("T2 put back: the spindle empty")


if __name__ == "__main__":
    main()
