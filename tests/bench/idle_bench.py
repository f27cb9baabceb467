#!/usr/bin/python3
"""[DISPLAY]DISPLAY of the idle measurement in scripts/bench_changes.sh: brings
the simulated mill up (machine on, homed, the changer idle), leaves it alone
for FATC_IDLE_SECONDS (default 60), and writes the component's CPU over that
time (share of one core, from /proc/PID/stat) and its resident memory (VmRSS,
VmHWM) to FATC_RESULTS."""
import json
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.environ["FATC_ROOT"], "tests", "integration"))
import driver  # noqa: E402  (bring-up shared with the integration runs)
from driver import hal  # noqa: E402


def cpu_seconds(pid):
    fields = open("/proc/%d/stat" % pid).read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def main():
    idle = hal.component("fatc-idle-bench")  # hal.get_value needs a component of our own
    idle.ready()
    result = {"error": None}
    try:
        driver.bring_up()
        pid = int(subprocess.check_output(["pgrep", "-x", "fixed_atc_probe"]).split()[0])
        seconds = float(os.environ.get("FATC_IDLE_SECONDS") or "60")
        start, used = time.monotonic(), cpu_seconds(pid)
        time.sleep(seconds)  # the measurement is of doing nothing
        wall, used = time.monotonic() - start, cpu_seconds(pid) - used
        memory = {line.split(":")[0]: int(line.split()[1]) for line in open("/proc/%d/status" % pid)
                  if line.startswith(("VmRSS", "VmHWM"))}
        result.update(seconds=wall, cpu_share=used / wall, rss_kib=memory["VmRSS"],
                      peak_kib=memory["VmHWM"])
    except Exception as e:  # printed by bench_changes.py; LinuxCNC must still shut down
        result["error"] = "%s: %s" % (type(e).__name__, e)
    json.dump(result, open(os.environ["FATC_RESULTS"], "w"))


if __name__ == "__main__":
    main()
