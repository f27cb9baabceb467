#!/usr/bin/env bash
# The tool-change benchmark (issue 11), on the simulated mill at its own
# speeds with default feeds (pocket_feed 500) and 0.4 s dwells, each run its
# own LinuxCNC start:
#  - tests/bench/changes.ngc on the rack of tests/integration/rack/rack_config.json
#    (side pockets and a top pocket), on the prototype's path and the direct one;
#  - tests/bench/peer_changes.ngc on tests/bench/rack_y.json (six top pockets
#    along Y), on both paths and with LinuxCNC's own rack-toolchange remap
#    example instead of the changer (tests/bench/peer_ini.py), the peer;
#  - both programs again on the direct path with blend_tolerance 10 and 15, the
#    corners at safe Z rounded, and peer_changes.ngc once more with pocket_feed
#    at the mill's rapid (12000), as the example goes into and out of a pocket;
#  - the demo program, nc_files/demo.ngc, as the demo runs it, on both paths;
#  - tests/bench/spindown.ngc on config/config.json, direct path: one change
#    between two side pockets with the simulated spindle taking 3 s to stop
#    from S12000 (zero-speed wired), moving while it runs down and standing
#    until it stops (move_while_spindle_stops true and false).
# Prints each change's time, the bound and the ratios; the component's CPU and
# memory idle for a minute and during the changes. Never asserts.
#   scripts/bench_changes.sh          (ctest: ctest --test-dir build -L bench -V)
set -euo pipefail
cd "$(dirname "$0")/.."
binary=${FATC_BINARY:-$PWD/build/fixed_atc_probe}
work=$(mktemp -d /tmp/fixed_atc_bench.XXXXXX)
chmod 755 "$work"

# run NAME PROGRAM CONFIG TOOL_TABLE [ENV...]: one LinuxCNC start, the program run once.
run() {
  local name=$1 program=$2 config=$3 table=$4
  shift 4
  printf '[{"name": "changes", "program": "%s", "timeout": 900}]\n' "$program" > "$work/$name.json"
  chmod 644 "$work/$name.json"
  env "$@" FATC_BINARY="$binary" FATC_SCENARIOS="$work/$name.json" FATC_RESULTS="$work/$name/results.json" \
    FATC_CONFIG="$PWD/$config" FATC_TOOL_TABLE="$PWD/$table" \
    tests/integration/harness/run_sim.sh "$work/$name" "$PWD/tests/integration/harness/driver.py" > "$work/$name.log" 2>&1 || {
    echo "LinuxCNC failed; its output is in $work/$name.log"; exit 1; }
}

# The component alone for a minute first: its CPU and memory doing nothing.
FATC_BINARY="$binary" FATC_RESULTS="$work/idle/results.json" \
  tests/integration/harness/run_sim.sh "$work/idle" "$PWD/tests/bench/idle_bench.py" > "$work/idle.log" 2>&1 || {
  echo "LinuxCNC failed; its output is in $work/idle.log"; exit 1; }
for path in prototype direct; do
  run "$path" tests/bench/changes.ngc tests/integration/rack/rack_config.json tests/integration/rack/rack.tbl \
    FATC_CONFIG_SET="{\"path\": \"$path\", \"pocket_feed\": 500, \"chuck_seconds\": 0.4}"
  run "row_$path" tests/bench/peer_changes.ngc tests/bench/rack_y.json tests/bench/rack_y.tbl \
    FATC_CONFIG_SET="{\"path\": \"$path\"}"
done
# Blended runs: blend_tolerance as much as each rack allows (Config::blend_room):
# 10 on rack_config.json (pocket 5's side to pocket 4's column), 15 on rack_y.json.
run blended tests/bench/changes.ngc tests/integration/rack/rack_config.json tests/integration/rack/rack.tbl \
  FATC_CONFIG_SET='{"path": "direct", "pocket_feed": 500, "chuck_seconds": 0.4, "blend_tolerance": 10}'
run row_blended tests/bench/peer_changes.ngc tests/bench/rack_y.json tests/bench/rack_y.tbl \
  FATC_CONFIG_SET='{"path": "direct", "blend_tolerance": 15}'
# On the example's terms: into and out of a pocket at the mill's rapid.
run row_rapid_entry tests/bench/peer_changes.ngc tests/bench/rack_y.json tests/bench/rack_y.tbl \
  FATC_CONFIG_SET='{"path": "direct", "blend_tolerance": 15, "pocket_feed": 12000}'
for path in prototype direct; do
  run "demo_$path" nc_files/demo.ngc config/config.json config/sim/sim.tbl \
    FATC_CONFIG_SET="{\"path\": \"$path\"}"
done
for overlap in true false; do
  run "spindown_$overlap" tests/bench/spindown.ngc config/config.json config/sim/sim.tbl \
    FATC_INI_SED="s/^SIM_SPINDLE_RAMP = .*/SIM_SPINDLE_RAMP = 4000/" \
    FATC_CONFIG_SET="{\"path\": \"direct\", \"sensors\": {\"zero_speed\": true}, \"move_while_spindle_stops\": $overlap}"
done
run row_peer tests/bench/peer_changes.ngc tests/bench/rack_y.json tests/bench/rack_y.tbl \
  FATC_NO_CHANGER=1 FATC_INI_FILTER="$PWD/tests/bench/peer_ini.py"
python3 scripts/bench_changes.py "$work" "$binary"
