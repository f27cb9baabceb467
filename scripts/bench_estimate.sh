#!/usr/bin/env bash
# The change-time estimate against the real LinuxCNC (issue 22): what
# `fixed_atc_probe --lint` estimates for each change of tests/bench/changes.ngc
# (the rack of tests/integration/rack/rack_config.json, pocket_feed 500, 0.4 s
# dwells) beside what the change took, chip to chip, on
#  - the simulated mill at its own speeds (axes 200 mm/s, 2000 mm/s^2), on the
#    direct path and the prototype's;
#  - a slow machine: the same mill with the limits of LinuxCNC's gantry sample
#    (sim/axis/gantry/gantry_mm.ini: axes 30 mm/s and 200 mm/s^2, [TRAJ] 100
#    mm/s and 800 mm/s^2), on the direct path;
#  - the mill on the direct path with iocontrol's [EMCIO]CYCLE_TIME 0.1 s,
#    LinuxCNC's usual, instead of the sim's 0.01 s.
# Each run is its own LinuxCNC start, some eight minutes in all. Prints the
# figures and the costs the estimate adds (kStepSeconds, kIocontrolCycles,
# kChangeSeconds in src/core/dry_run/timing.hpp) as measured; never asserts.
#   scripts/bench_estimate.sh [WORKDIR]   (ctest: ctest --test-dir build -R bench_estimate -V)
set -euo pipefail
cd "$(dirname "$0")/.."
binary=${FATC_BINARY:-$PWD/build/fixed_atc_probe}
work=${1:-$(mktemp -d /tmp/fixed_atc_estimate.XXXXXX)}
mkdir -p "$work"
chmod 755 "$work"
# The gantry sample's limits on the sim's axes and joints.
slow_sed='s/^MAX_VELOCITY = 200$/MAX_VELOCITY = 30/;s/^MAX_ACCELERATION = 2000$/MAX_ACCELERATION = 200/;s/^MAX_LINEAR_VELOCITY = 200$/MAX_LINEAR_VELOCITY = 100/;s/^MAX_LINEAR_ACCELERATION = 2000$/MAX_LINEAR_ACCELERATION = 800/'
# iocontrol at LinuxCNC's usual cycle, ten times the sim's.
usual_io_sed='/^\[EMCIO\]/,/^\[/s/^CYCLE_TIME = .*/CYCLE_TIME = 0.100/'

# run NAME PATH [ENV...]: one LinuxCNC start, tests/bench/changes.ngc run once.
run() {
  local name=$1 path=$2
  shift 2
  printf '[{"name": "changes", "program": "tests/bench/changes.ngc", "timeout": 900}]\n' > "$work/$name.json"
  chmod 644 "$work/$name.json"
  env "$@" FATC_BINARY="$binary" FATC_SCENARIOS="$work/$name.json" FATC_RESULTS="$work/$name/results.json" \
    FATC_CONFIG="$PWD/tests/integration/rack/rack_config.json" FATC_TOOL_TABLE="$PWD/tests/integration/rack/rack.tbl" \
    FATC_CONFIG_SET="{\"path\": \"$path\", \"pocket_feed\": 500, \"chuck_seconds\": 0.4}" \
    tests/integration/harness/run_sim.sh "$work/$name" "$PWD/tests/integration/harness/driver.py" > "$work/$name.log" 2>&1 || {
    echo "LinuxCNC failed; its output is in $work/$name.log"; exit 1; }
}

if [ -z "${FATC_ESTIMATE_REPORT_ONLY:-}" ]; then
  run mill_direct direct
  run mill_prototype prototype
  run slow_direct direct FATC_INI_SED="$slow_sed"
  run usual_io_direct direct FATC_INI_SED="$usual_io_sed"
fi
python3 scripts/bench_estimate.py "$work" "$binary"
