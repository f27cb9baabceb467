#!/usr/bin/python3
"""[DISPLAY]DISPLAY of the idle measurement in scripts/bench_changes.sh: brings
the simulated mill up (machine on, homed, the changer idle), leaves it alone
for FATC_IDLE_SECONDS (default 60), and writes the component's CPU over that
time (share of one core, from /proc/PID/stat) and its resident memory (VmRSS,
VmHWM) to FATC_RESULTS."""
import json
import os
import sys
import time

sys.path.insert(0, os.path.join(os.environ["FATC_ROOT"], "tests", "integration", "harness"))
import driver  # noqa: E402  (bring-up shared with the integration runs)
from driver import hal  # noqa: E402


def main():
    idle = hal.component("fatc-idle-bench")  # hal.get_value needs a component of our own
    idle.ready()
    result = {"error": None}
    try:
        driver.bring_up()
        seconds = float(os.environ.get("FATC_IDLE_SECONDS") or "60")
        start, before = time.monotonic(), driver.component_usage()
        time.sleep(seconds)  # the measurement is of doing nothing
        wall, after = time.monotonic() - start, driver.component_usage()
        result.update(seconds=wall, cpu_share=(after["cpu_seconds"] - before["cpu_seconds"]) / wall,
                      rss_kib=after["rss_kib"], peak_kib=after["peak_kib"])
    except Exception as e:  # printed by bench_changes.py; LinuxCNC must still shut down
        result["error"] = "%s: %s" % (type(e).__name__, e)
    json.dump(result, open(os.environ["FATC_RESULTS"], "w"))


if __name__ == "__main__":
    main()
