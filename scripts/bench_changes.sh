#!/usr/bin/env bash
# The tool-change benchmark (issue 11): tests/bench/changes.ngc on the
# simulated mill at its own speeds, the rack of tests/integration/rack_config.json
# with default feeds and 0.4 s dwells, once on the prototype's path and once on
# the direct path, each its own LinuxCNC run. Prints each change's time, the
# model time and the bound, and the ratios; before them, the component's CPU
# and memory while the machine stands idle for a minute. Never asserts.
#   scripts/bench_changes.sh          (ctest: ctest --test-dir build -L bench -V)
set -euo pipefail
cd "$(dirname "$0")/.."
binary=${FATC_BINARY:-$PWD/build/fixed_atc_probe}
work=$(mktemp -d /tmp/fixed_atc_bench.XXXXXX)
chmod 755 "$work"
printf '[{"name": "changes", "program": "tests/bench/changes.ngc", "timeout": 900}]\n' > "$work/scenarios.json"
chmod 644 "$work/scenarios.json"
# The component alone for a minute first: its CPU and memory doing nothing.
FATC_BINARY="$binary" FATC_RESULTS="$work/idle/results.json" \
  tests/integration/run_sim.sh "$work/idle" "$PWD/tests/bench/idle_bench.py" > "$work/idle.log" 2>&1 || {
  echo "LinuxCNC failed; its output is in $work/idle.log"; exit 1; }
for path in prototype direct; do
  FATC_BINARY="$binary" FATC_SCENARIOS="$work/scenarios.json" FATC_RESULTS="$work/$path/results.json" \
    FATC_CONFIG="$PWD/tests/integration/rack_config.json" FATC_TOOL_TABLE="$PWD/tests/integration/rack.tbl" \
    FATC_CONFIG_SET="{\"path\": \"$path\", \"pocket_feed\": 500, \"chuck_seconds\": 0.4}" \
    tests/integration/run_sim.sh "$work/$path" "$PWD/tests/integration/driver.py" > "$work/$path.log" 2>&1 || {
    echo "LinuxCNC failed; its output is in $work/$path.log"; exit 1; }
done
python3 scripts/bench_changes.py "$work" "$binary"
