#!/usr/bin/env bash
# docs/setup.md step 8: LinuxCNC started from a terminal shows the
# component's lines there, the first its start line with the version
# `--version` says; STATE.log keeps the same line. The linuxcnc script sends
# every program's stderr to a temporary file unless its stdin is a terminal:
# script(1) gives the run one, as a user's terminal would.
#   terminal_lines.sh BINARY WORKDIR
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
binary=$(readlink -f "$1")
work=$2
mkdir -p "$work"
rm -f "$work/terminal.txt"
printf '[]\n' > "$work/scenarios.json"  # LinuxCNC up and down again: only its start matters
version=$("$binary" --version)
expected="fixed_atc_probe: info: ${version#fixed_atc_probe } started with $work/run/config.json"
FATC_BINARY=$binary FATC_SCENARIOS=$work/scenarios.json FATC_RESULTS=$work/run/results.json \
  script --quiet --return --command \
  "$here/../harness/run_sim.sh $work/run $here/../harness/driver.py" "$work/terminal.txt" \
  < /dev/null > /dev/null || { echo "FAIL: LinuxCNC failed; its terminal is in $work/terminal.txt"; exit 1; }
if ! grep -qF "$expected" "$work/terminal.txt"; then
  echo "FAIL: the terminal LinuxCNC was started from has no \"$expected\" line; it shows:"
  grep -a 'fixed_atc_probe' "$work/terminal.txt" | head -20
  exit 1
fi
if ! grep -qF "$expected" "$work/run/fixed_atc_state.json.log"; then
  echo "FAIL: $work/run/fixed_atc_state.json.log has no \"$expected\" line"
  exit 1
fi
echo "ok: $(grep -aF "$expected" "$work/terminal.txt" | tr -d '\r')"
