#!/usr/bin/env bash
# Installs what is missing, builds, then runs nc_files/demo.ngc on the
# simulated mill (config/sim) headless on the real LinuxCNC and reports each
# tool change, on config.json's direct path, then once more on the
# prototype path for its change times. --gui opens the same machine in AXIS
# instead (needs a display).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh fixed_atc_probe >/dev/null
build/fixed_atc_probe --check --config config/config.json --ini config/sim/fixed_atc_sim.ini | tail -1
work=$(mktemp -d /tmp/fixed_atc_demo.XXXXXX)
chmod 755 "$work"
if [ "${1:-}" = "--gui" ]; then
  exec tests/integration/harness/run_sim.sh "$work" axis
fi
printf '[{"name": "demo", "program": "nc_files/demo.ngc", "timeout": 600}]\n' > "$work/scenarios.json"
chmod 644 "$work/scenarios.json"
FATC_SCENARIOS="$work/scenarios.json" FATC_RESULTS="$work/run/results.json" \
  tests/integration/harness/run_sim.sh "$work/run" "$PWD/tests/integration/harness/driver.py" > "$work/linuxcnc.log" 2>&1 || {
  echo "LinuxCNC failed; its output is in $work/linuxcnc.log"; exit 1; }
# The same program on the prototype path, for its change times beside the direct path's.
FATC_SCENARIOS="$work/scenarios.json" FATC_RESULTS="$work/prototype/results.json" \
  FATC_CONFIG_SET='{"path": "prototype"}' \
  tests/integration/harness/run_sim.sh "$work/prototype" "$PWD/tests/integration/harness/driver.py" > "$work/prototype.log" 2>&1 || {
  echo "LinuxCNC failed; its output is in $work/prototype.log"; exit 1; }
python3 scripts/demo_report.py "$work/run/results.json" "$work/prototype/results.json"
# One change drawn over time: position and chuck (docs/timeline.svg is one such).
python3 scripts/timeline_svg.py "$work/run/results.json" "$work/timeline.svg"
