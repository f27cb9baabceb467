#!/usr/bin/env bash
# The simulated collet-nut magazine under halrun (no LinuxCNC, no
# component): fatc_sim_nut loaded with config/sim/sim_nut.hal's pockets,
# speeds and beam in a thread of its own, with a near (as the simulated
# spindle's at-speed) comparing the command with the nut's speed-out;
# sim_nut_test.py moves the nose, turns the spindle and judges each case.
#   sim_nut_test.sh
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
# The lock, the test user and $work: harness/halrun_work.sh (no binary of ours runs).
. "$root/tests/integration/harness/halrun_work.sh" "$here/sim_nut_test.py"

{
  echo "loadrt fatc_sim_nut names=fatc-sim-nut"
  echo "loadrt near names=fatc-test-at-speed"
  echo "loadrt threads name1=fatc-nut-thread period1=1000000"
  echo "addf fatc-sim-nut fatc-nut-thread"
  echo "addf fatc-test-at-speed fatc-nut-thread"
  echo "net fatc-test-speed fatc-sim-nut.speed-out => fatc-test-at-speed.in2"
  # basic_sim.tcl's near_speed
  echo "setp fatc-test-at-speed.scale 1.1"
  echo "setp fatc-test-at-speed.difference 10"
  grep '^setp fatc-sim-nut\.' "$root/config/sim/sim_nut.hal"
  echo "start"
  echo "loadusr -w /usr/bin/python3 $here/sim_nut_test.py $work/verdict"
} > "$work/nut.hal"
halrun_verdict "$work/nut.hal"
