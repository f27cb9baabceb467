#!/usr/bin/env bash
# The simulated rack's geometry under halrun (no LinuxCNC): fatc_sim_rack
# loaded with config/sim/sim_rack.hal's plate and probe in a thread of its
# own, each contact judged by sim_rack_geometry.py.
#   sim_rack_geometry.sh
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
# The lock, the test user and $work: harness/halrun_work.sh (no binary of ours runs).
. "$root/tests/integration/harness/halrun_work.sh" "$here/sim_rack_geometry.py"

{
  echo "loadrt fatc_sim_rack names=fatc-sim-rack"
  echo "loadrt threads name1=fatc-geometry-thread period1=1000000"
  echo "addf fatc-sim-rack fatc-geometry-thread"
  grep '^setp fatc-sim-rack\.' "$root/config/sim/sim_rack.hal"
  echo "start"
  echo "loadusr -w /usr/bin/python3 $here/sim_rack_geometry.py $work/verdict"
} > "$work/geometry.hal"
halrun_verdict "$work/geometry.hal"
