#!/usr/bin/env bash
# LinuxCNC with linuxcncrsh as its display, as docs/setup.md#a-program-without-a-gui
# sets it up, and rsh_client.py - started by LinuxCNC as an [APPLICATIONS]APP,
# so that it lives exactly as long as LinuxCNC - typing the page's session
# into it: a program run headless with no display of our own. It writes
# WORKDIR/client.json; headless_check.py judges.
#   run_headless.sh WORKDIR   (FATC_BINARY as run_sim.sh takes it)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
work=$1
mkdir -p "$work"
rm -f "$work/client.json"
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
joints=$(sed -n 's/^JOINTS = //p' "$root/config/sim/fixed_atc_sim.ini")
display="$("$here/rsh_client.py" display "$root/docs/setup.md") -p $port"
export FATC_APP="$here/rsh_client.py $port $root/docs/setup.md $here/headless.ngc $joints $work/client.json"
exec "$root/tests/integration/harness/run_sim.sh" "$work" "$display"
