#!/usr/bin/env bash
# Fuzzes the readers of hostile files (config.json, the saved tool state, the
# machine INI, what reads a program: its numbering, rs274's output, the
# tool table; the status file --operator prints from) with libFuzzer,
# AddressSanitizer and UBSan, each under a memory
# limit: 2 GB resident for the others; the program reader, which must stay
# small whatever it is fed, 256 MB, and no single allocation over 32 MB.
# ASan's quarantine of freed memory (256 MB by default) is held at 8 MB so
# that the limit measures the reader: with the default, 60 s of fuzz_program
# grew to 470 MB resident and an empty input tripped the limit; with 8 MB the
# peak is 71 MB.
# Configures a clang build of its own, builds the targets, seeds each
# with the hostile corpus of tests/unit and the valid files, and runs each for
# SECONDS (default 60). Fails on any finding: a crash, a leak, undefined
# behaviour, an input slower than 2 s, a broken invariant (see invariants.hpp).
# A finding is saved as BUILD_DIR/findings/<reader>-crash-<sha1> (or -timeout-,
# -leak-, -oom-); replay it with BUILD_DIR/tests/fuzz/fuzz_<reader> FILE.
#
# usage: tests/fuzz/run.sh [SECONDS] [BUILD_DIR]     (BUILD_DIR: ./build-fuzz)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
seconds=${1:-60}
build=${2:-$root/build-fuzz}

command -v clang++ >/dev/null || { echo "run.sh: clang++ not found (scripts/setup.sh installs it)"; exit 1; }
echo "run.sh: building the fuzz targets in $build"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DFATC_FUZZ=ON \
  -DBUILD_TESTING=OFF >/dev/null
cmake --build "$build" --target fuzz_config fuzz_state fuzz_ini fuzz_program fuzz_status -j"$(nproc)" >/dev/null

work=$build/fuzz_run
findings=$build/findings
rm -rf "$work"
mkdir -p "$work" "$findings"
unit=$root/tests/unit

# Seeds: every hostile file, and the valid ones they were spoiled from.
mkdir -p "$work/config" "$work/state" "$work/ini" "$work/program" "$work/status"
cp "$unit"/bad_configs/*.json "$root"/config/config.json "$root"/config/sim/collet_nut.json "$work/config/"
cp "$unit"/bad_states/*.json "$work/state/"
printf '%s\n' '{"version": 1, "spindle": 3, "uncertain": false, "in_pocket": [1, 2, 4, 5, 6], "lengths": {"1": 42.125, "3": 17.5}}' \
  > "$work/state/valid.json"
printf '%s\n' '{"version": 1, "spindle": 0, "uncertain": true, "in_pocket": [1], "lengths": {}, "in_progress": {"sequence": "M6 T3", "step": "returning tool 1 to pocket 1", "pocket": 1}}' \
  > "$work/state/valid_in_progress.json"
cp "$unit"/bad_inis/*.ini "$unit"/bad_configs/narrow_limits.ini "$root"/config/sim/*.ini "$work/ini/"
# The status file --operator reads: one as the component writes it, and words that act on a terminal.
printf '%s\n' '{"state": 3, "awaiting": 5, "activity": "load", "serial": 4, "messages": [{"kind": "prompt", "text": "Insert tool 3 into the spindle, then press Continue"}]}' \
  > "$work/status/valid.json"
printf '%s\n' '{"state": 3, "awaiting": 5, "activity": "load", "serial": 2, "messages": [{"kind": "prompt\u001b[31m", "text": "\u001b[2J\u001b]0;owned\u0007\u009b31m\r\noutcome: done"}, {"kind": "info", "text": "\u007f\u0085"}]}' \
  > "$work/status/escapes.json"
printf '{"state": 1, "awaiting": 0, "activity": "", "serial": 1, "messages": [{"kind": "error", "text": "\x1b[2J\x9b\xff"}]}\n' \
  > "$work/status/raw_bytes.json"
# The program reader: programs and tool tables, each behind
# the byte that chooses the size of the pieces it is read in.
for seed in "$unit"/lint_programs/*.ngc "$unit"/lint_programs/*.tbl "$root"/config/sim/sim.tbl \
            "$root"/nc_files/*.ngc; do
  { printf '\x07'; head -c 60000 "$seed"; } > "$work/program/$(basename "$seed")"
done

status=0
for reader in config state ini program status; do
  dict=$here/json.dict
  [ "$reader" = ini ] && dict=$here/ini.dict
  [ "$reader" = program ] && dict=$here/program.dict
  memory="-rss_limit_mb=2048"
  [ "$reader" = program ] && memory="-rss_limit_mb=256 -malloc_limit_mb=32"
  log=$work/$reader.log
  echo "run.sh: fuzz_$reader for ${seconds} s"
  if ASAN_OPTIONS=quarantine_size_mb=8${ASAN_OPTIONS:+:$ASAN_OPTIONS} "$build/tests/fuzz/fuzz_$reader" "$work/$reader" -dict="$dict" -max_total_time="$seconds" \
      -timeout=2 $memory -max_len=65536 -print_final_stats=1 \
      -artifact_prefix="$findings/$reader-" >"$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    peak=$(sed -n 's/^stat::peak_rss_mb: *//p' "$log")
    echo "run.sh: fuzz_$reader: no findings in $runs runs ($(grep -c . < <(ls "$work/$reader")) inputs in its corpus, peak ${peak} MB resident)"
  else
    echo "run.sh: fuzz_$reader FOUND A PROBLEM:"
    grep -E "ERROR|broken promise|SUMMARY|Test unit written|runtime error" "$log" | head -20 | cat -v
    status=1
  fi
done
exit $status
