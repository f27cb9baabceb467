#!/usr/bin/env bash
# Every command-line mode under a memory limit (ulimit -v, from where the
# binary cannot even be loaded up to where it no longer matters): it ends on
# its own exit status, never on a signal (std::bad_alloc included, thrown
# before main or after), and when it fails it says so in one line.
#   memory_limit.sh BINARY CONFIG
set -uo pipefail
binary=$1
config=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
{ echo "T1 M6"; for i in $(seq 1 5000); do echo "G1 X$((i % 100)).000 Y2.000 F100"; done
  echo "T2 M6"; echo "M2"; } > "$work/program.ngc"
safe=$(python3 -c 'import json, sys; s = json.load(open(sys.argv[1]))["safe"]; print("%s,%s,%s" % (s["x"], s["y"], s["z"]))' "$config")
failures=0
loader=$(readelf -l "$binary" | sed -n 's/.*Requesting program interpreter: \(.*\)]/\1/p')
check() {  # check LIMIT_KB NAME ARGS...: one run under the limit
  local limit=$1 name=$2
  shift 2
  ( ulimit -v "$limit"; exec "$binary" "$@" ) > "$work/out" 2> "$work/err"
  local code=$?
  local lines
  lines=$(grep -c '' "$work/err")
  if grep -q "error while loading shared libraries" "$work/err"; then
    return  # the loader's, before any of our code runs
  fi
  # glibc's loader may also die silently at this edge (SIGSEGV in init_tls):
  # when it cannot even list the libraries under the same limit, that is its.
  if [ "$code" -ge 128 ] && ! ( ulimit -v "$limit"; exec "$loader" --list "$binary" ) \
       > /dev/null 2>&1; then
    return
  fi
  if [ "$code" -ge 128 ]; then
    echo "FAIL: $name under ulimit -v $limit: ended on signal $((code - 128)): $(head -c 300 "$work/err")"
    failures=$((failures + 1))
  elif [ "$code" -ne 0 ] && [ "$name" != lint ] && [ "$lines" -ne 1 ]; then
    echo "FAIL: $name under ulimit -v $limit: exit $code with $lines lines: $(head -c 300 "$work/err")"
    failures=$((failures + 1))
  elif [ "$name" = lint ] && [ "$lines" -gt 1 ]; then
    echo "FAIL: lint under ulimit -v $limit: $lines lines: $(head -c 300 "$work/err")"
    failures=$((failures + 1))
  fi
}
runs=0
for limit in $(seq 8000 2000 32000) 48000 64000 128000; do
  check "$limit" help --help
  check "$limit" version --version
  check "$limit" check --check --config "$config" --state "$work/none.state"
  check "$limit" plan --plan --config "$config" --from 1 --to 2
  check "$limit" dot --dot
  check "$limit" plot --plot "$work/rack.svg" --config "$config"
  check "$limit" lint --lint "$work/program.ngc" --config "$config" --state "$work/none.state"
  # The writers: a teach of the sample's own safe position, a confirm with nothing cut off.
  cp "$config" "$work/teach.json"
  check "$limit" teach --teach safe --config "$work/teach.json" --at "$safe"
  # A confirm that went through rewrote it: each starts with the same cut-off record.
  printf '{"version": 1, "spindle": 0, "uncertain": true, "in_pocket": [1, 2, 3, 4, 5, 6], "lengths": {}}\n' \
    > "$work/confirm.state"
  check "$limit" confirm --confirm --config "$config" --spindle 0 --state "$work/confirm.state"
  runs=$((runs + 9))
done
echo "memory_limit.sh: $runs runs from ulimit -v 8000 to 128000 KB, $failures failures"
[ "$failures" -eq 0 ]
