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
# T3 a touch probe, its rough length in the tool table as the simulated
# sensor has it (the sensor knows no lengths: every tool measures about 25 mm).
sed 's/^T3 P3 Z40.0 /T3 P3 Z25.0 /' config/sim/sim.tbl > "$work/bench.tbl"
FATC_TOOL_TABLE="$work/bench.tbl" FATC_CONFIG_SET='{"tools": {"3": {"kind": "probe"}}}' \
FATC_BENCH_REPEATS=${1:-10} FATC_RESULTS="$work/run/results.json" \
  tests/integration/harness/run_sim.sh "$work/run" "$PWD/tests/bench/probe_bench.py" > "$work/linuxcnc.log" 2>&1 || {
  echo "LinuxCNC failed; its output is in $work/linuxcnc.log"; exit 1; }
python3 scripts/bench_probe.py "$work/run/results.json"
