#!/usr/bin/env bash
# The soak (issue 36): thousands of tool changes on the simulated mill on the
# real LinuxCNC, with faults injected and the operator's recoveries, the
# changer's belief held against the simulated rack's truth after every change
# (tests/soak/soak.py); then the report and its picture (soak_report.py).
#
#   scripts/soak.sh [WORKDIR] [CHANGES] [SEED]     (default build/soak 1000 1)
#
# FATC_SOAK_CYCLE=1: one fault a program, each kind in turn (the short soak
# of the suite, which must meet every kind). FATC_SOAK_COLLET=1: the
# collet-nut magazine instead of the drawbar's rack (below). The machine: the simulated mill
# with axes ten times as fast (2000 mm/s, 20000 mm/s²), every sensor wired to
# the simulated rack, pocket_feed 12000, 0.1 s chuck dwells, 0.05 s flush
# pulses, sensor_timeout_seconds 0.5, each tool measured at its first change
# ("new"): a change takes about two seconds.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
work=${1:-$root/build/soak}
changes=${2:-1000}
seed=${3:-1}
here=$root/tests/soak
rack=$root/tests/integration/sensors
export FATC_BINARY=${FATC_BINARY:-$root/build/fixed_atc_probe}
export FATC_INI_SED="s/^\(MAX_\(LINEAR_\)\?VELOCITY\) = 200$/\1 = 2000/;s/^\(MAX_\(LINEAR_\)\?ACCELERATION\) = 2000$/\1 = 20000/
/^RETURN_TO_XY = /a RACK_SIM = $rack/rack_sim.py
/^HALFILE = .*touchoff_sensor.hal$/a HALFILE = $rack/rack_sim.hal\nHALFILE = $here/soak_rack.hal"
export FATC_CONFIG_SET='{"sensors": {"tool_present": true, "drawbar_open": true, "drawbar_closed": true, "air_pressure": true, "pocket_occupancy": true, "zero_speed": true}, "sensor_timeout_seconds": 0.5, "pocket_feed": 12000, "chuck_seconds": 0.1, "spindle_stop_timeout_seconds": 2.0, "flush": {"pulses": 1, "pulse_seconds": 0.05, "pause_seconds": 0.05}, "probe_after_change": "new"}'
if [ -n "${FATC_SOAK_COLLET:-}" ]; then
  # The collet-nut magazine (issue 46): config/sim/collet_nut.json and the
  # simulated magazine (config/sim/sim_nut.hal, tests/soak/soak_collet.py) on
  # the same fast axes, at-speed and zero-speed wired, each tool measured at
  # its first change; the operator's flows are the collet-nut scenarios'.
  export FATC_CONFIG=$root/config/sim/collet_nut.json
  export FATC_INI_SED="s/^\(MAX_\(LINEAR_\)\?VELOCITY\) = 200$/\1 = 2000/;s/^\(MAX_\(LINEAR_\)\?ACCELERATION\) = 2000$/\1 = 20000/"
  export FATC_CONFIG_SET='{"spindle_stop_timeout_seconds": 2.0, "probe_after_change": "new"}'
  export FATC_SOAK_OPERATOR_RATE=0
fi
python3 "$here/soak_run.py" "$work" "$changes" "$seed"
exec python3 "$here/soak_report.py" "$work" "$changes"
