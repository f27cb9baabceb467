#!/usr/bin/env bash
# The collet-nut benchmark (issue 46): tests/bench/collet_changes.ngc on the
# simulated magazine (config/sim/collet_nut.json, config/sim/sim_nut.hal) at
# the simulated mill's own speeds (axes 200 mm/s, 2000 mm/s^2; the spindle
# ramping at [FIXED_ATC_PROBE]SIM_SPINDLE_RAMP, at-speed and zero-speed wired),
# one LinuxCNC start. Prints each change's time against its physical bound,
# the spindle's ramps included (scripts/bench_collet.py); never asserts.
#   scripts/bench_collet.sh [WORKDIR]   (ctest: ctest --test-dir build -R bench_collet -V)
set -euo pipefail
cd "$(dirname "$0")/.."
binary=${FATC_BINARY:-$PWD/build/fixed_atc_probe}
work=${1:-$(mktemp -d /tmp/fixed_atc_collet_bench.XXXXXX)}
mkdir -p "$work"
chmod 755 "$work"
# Every pocket's nut in it, as a fresh state file has it.
nuts=$(for i in 0 1 2 3 4 5; do printf '"fatc-sim-nut.nut-in-pocket-init-%d": "1", ' "$i"; done)
printf '[{"name": "changes", "program": "tests/bench/collet_changes.ngc", "timeout": 900, "set_pins": {%s}}]\n' \
  "${nuts%, }" > "$work/collet.json"
chmod 644 "$work/collet.json"
FATC_BINARY="$binary" FATC_SCENARIOS="$work/collet.json" FATC_RESULTS="$work/collet/results.json" \
  FATC_CONFIG="$PWD/config/sim/collet_nut.json" \
  tests/integration/harness/run_sim.sh "$work/collet" "$PWD/tests/integration/harness/driver.py" \
  > "$work/collet.log" 2>&1 || { echo "LinuxCNC failed; its output is in $work/collet.log"; exit 1; }
python3 scripts/bench_collet.py "$work/collet" "$binary"
