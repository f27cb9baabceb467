#!/usr/bin/env bash
# LinuxCNC with linuxcncrsh as its display, as docs/setup.md#a-program-without-a-gui
# sets it up, and rsh_client.py typing the page's session into it: a program
# run headless with no display of our own. headless_check.py judges.
#   run_headless.sh WORKDIR RESULTS   (FATC_BINARY as run_sim.sh takes it)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
work=$1
results=$2
mkdir -p "$work"
rm -f "$results"
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
joints=$(sed -n 's/^JOINTS = //p' "$root/config/sim/fixed_atc_sim.ini")
python3 "$here/rsh_client.py" "$port" "$root/docs/setup.md" "$here/headless.ngc" "$joints" "$results" &
client=$!
status=0
"$root/tests/integration/harness/run_sim.sh" "$work" "linuxcncrsh -p $port" || status=$?
wait "$client" || status=$?
exit "$status"
