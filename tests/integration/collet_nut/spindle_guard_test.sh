#!/usr/bin/env bash
# fatc-spindle-guard's holds under halrun (no LinuxCNC, no component):
# fatc_spindle_guard alone in a thread of its own, its inputs set and its
# heartbeat toggled by spindle_guard_test.py, which judges every row.
#   spindle_guard_test.sh
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
# The lock, the test user and $work: harness/halrun_work.sh (no binary of ours runs).
. "$root/tests/integration/harness/halrun_work.sh" "$here/spindle_guard_test.py"

cat > "$work/guard.hal" <<HAL
loadrt fatc_spindle_guard names=fatc-spindle-guard
loadrt threads name1=fatc-guard-thread period1=1000000
addf fatc-spindle-guard fatc-guard-thread
start
loadusr -w /usr/bin/python3 $here/spindle_guard_test.py $work/verdict
HAL
halrun_verdict "$work/guard.hal"
