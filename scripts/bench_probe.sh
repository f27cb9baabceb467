#!/usr/bin/env bash
# The probe benchmark: fixed_atc_probe's two-stage probe against the
# prototype's 0.2 mm stepping, on the simulated mill, side by side in one
# LinuxCNC run. Prints lengths, errors, repeatability and times.
#   scripts/bench_probe.sh [REPEATS]   (default 10)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh >/dev/null
work=$(mktemp -d /tmp/fixed_atc_bench.XXXXXX)
chmod 755 "$work"
FATC_BENCH_REPEATS=${1:-10} FATC_RESULTS="$work/run/results.json" \
  tests/integration/harness/run_sim.sh "$work/run" "$PWD/tests/bench/probe_bench.py" > "$work/linuxcnc.log" 2>&1 || {
  echo "LinuxCNC failed; its output is in $work/linuxcnc.log"; exit 1; }
python3 scripts/bench_probe.py "$work/run/results.json"
