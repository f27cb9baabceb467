#!/usr/bin/env bash
# The preflight of a long job (issue 32): `fixed_atc_probe --lint` of a
# program of 10,000 tool changes on a rack of 200 pockets, made by
# tests/bench/long_program.py, with the INI it writes (the M6 remap, the
# project's nc_files) and without an INI (every change a random tool, no
# moves). Prints the wall clock and the CPU time of each run (with rs274's),
# the median of RUNS; never fails on them.
#   scripts/bench_lint.sh [RUNS] [WORKDIR]   (ctest: ctest --test-dir build -R bench_lint -V)
set -euo pipefail
cd "$(dirname "$0")/.."
binary=${FATC_BINARY:-$PWD/build/fixed_atc_probe}
runs=${1:-3}
work=${2:-$(mktemp -d /tmp/fixed_atc_bench_lint.XXXXXX)}
python3 tests/bench/long_program.py "$work" 10000 200
# The unit test's rack and program (lint_test.cpp, TenThousandChanges...): the
# sample config's side pockets, 200 in ten rows; 10,000 changes to a random tool.
python3 - "$work/random.ngc" "$work/rack200.json" config/config.json <<'PY'
import json, sys
rack = json.load(open(sys.argv[3]))
rack["pockets"] = {str(i + 1): {"x": 10.0 + (i % 20) * 45.0, "y": 20.0 + (i // 20) * 100.0}
                   for i in range(200)}
rack.update(safe={"x": 450.0, "y": 1050.0, "z": -5.0}, rack_keepout_all_motion=False,
            loading={"x": 20.0, "y": 1100.0, "z": -10.0},
            probe_limit={"x": 20.0, "y": 1100.0, "z": -90.0})
json.dump(rack, open(sys.argv[2], "w"))
seed, text = 1, ""
for _ in range(10000):
    seed = (seed * 1103515245 + 12345) % 2**32
    text += f"T{seed // 65536 % 200 + 1} M6\n"
open(sys.argv[1], "w").write(text + "M2\n")
PY
# measure NAME ARGS...: RUNS runs, the median wall and CPU seconds.
measure() {
  local name=$1
  shift
  local walls=() cpus=()
  for _ in $(seq "$runs"); do
    /usr/bin/time -f "%e %U %S" -o "$work/time" "$binary" "$@" > "$work/out" 2> "$work/err" || true
    read -r wall user system < <(tail -1 "$work/time")
    walls+=("$wall")
    cpus+=("$(python3 -c "print($user + $system)")")
  done
  local wall cpu
  wall=$(printf '%s\n' "${walls[@]}" | sort -n | sed -n "$(( (runs + 1) / 2 ))p")
  cpu=$(printf '%s\n' "${cpus[@]}" | sort -n | sed -n "$(( (runs + 1) / 2 ))p")
  printf '%-48s %6.2f s wall %6.2f s CPU   (%s)\n' "$name" "$wall" "$cpu" "$(tail -1 "$work/out")"
}
echo "fixed_atc_probe --lint, median of $runs runs ($(nproc) cores, load $(cut -d' ' -f1 /proc/loadavg)):"
measure "10,000 changes with moves, 200 pockets, INI" \
  --lint "$work/program.ngc" --config "$work/config.json" --ini "$work/machine.ini" \
  --state "$work/none.state"
measure "10,000 random changes, 200 top pockets, no INI" \
  --lint "$work/random.ngc" --config "$work/config.json" --state "$work/none.state"
measure "the same on 200 side pockets (the unit test's)" \
  --lint "$work/random.ngc" --config "$work/rack200.json" --state "$work/none.state"
