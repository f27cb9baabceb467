#!/usr/bin/env bash
# Locks the HAL interface: `loadusr -W fixed_atc_probe; show pin` under halrun
# must match tests/integration/pins/pins.golden. Also: a bad config makes loadusr -W
# fail at once with one line naming the problem, not hang.
#   pins_golden.sh BINARY
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
# The lock, the test user and $work: harness/halrun_work.sh.
. "$root/tests/integration/harness/halrun_work.sh" "$1"

cat > "$work/pins.hal" <<HAL
loadusr -W $binary --config $root/config/config.json --state $work/state.json
show pin fixed_atc_probe
HAL
runuser -u "$user" -- halrun -f "$work/pins.hal" > "$work/out.txt" 2>&1 || { cat "$work/out.txt"; exit 1; }
# The owner id differs from run to run, and the heartbeat toggles; the rest is the interface.
grep 'fixed_atc_probe\.' "$work/out.txt" |
  awk '{value = $5 ~ /\.heartbeat$/ ? "*" : $4; print $2, $3, value, $5}' > "$work/pins.txt"
if ! diff -u "$here/pins.golden" "$work/pins.txt"; then
  echo "FAIL: the pins HAL shows are not those src/linuxcnc/live/pin_list.hpp declares (pins.golden, generated: cmake --build build --target references)"
  exit 1
fi
echo "ok: $(wc -l < "$work/pins.txt") pins as in pins.golden"

printf '{"safe": 1}\n' > "$work/bad.json"
chmod 644 "$work/bad.json"
cat > "$work/bad.hal" <<HAL
loadusr -W $binary --config $work/bad.json --state $work/state.json
HAL
start=$(date +%s)
if runuser -u "$user" -- timeout 60 halrun -f "$work/bad.hal" > "$work/bad.txt" 2>&1; then
  echo "FAIL: halrun accepted a bad config"; cat "$work/bad.txt"; exit 1
fi
if ! grep -q "fixed_atc_probe: $work/bad.json: safe: expected an object, got 1" "$work/bad.txt"; then
  echo "FAIL: no clear line about the bad config:"; cat "$work/bad.txt"; exit 1
fi
echo "ok: a bad config fails loadusr -W in $(( $(date +%s) - start )) s with: $(grep -m1 'safe:' "$work/bad.txt")"

# rack_keepout_all_motion false: the component says the keep-out is off, on
# its pin and in one line.
sed 's/^{/{"rack_keepout_all_motion": false, /' "$root/config/config.json" > "$work/off.json"
chmod 644 "$work/off.json"
cat > "$work/off.hal" <<HAL
loadusr -W $binary --config $work/off.json --state $work/state.json
loadusr -w sleep 0.5
show pin fixed_atc_probe.rack-keepout
HAL
runuser -u "$user" -- timeout 60 halrun -f "$work/off.hal" > "$work/off.txt" 2>&1 || { cat "$work/off.txt"; exit 1; }
if ! grep -q "s32 *OUT *0 *fixed_atc_probe.rack-keepout$" "$work/off.txt" ||
   ! grep -q "rack keep-out OFF: rack_keepout_all_motion is false" "$work/off.txt"; then
  echo "FAIL: with rack_keepout_all_motion false the component does not say the keep-out is off:"
  cat "$work/off.txt"; exit 1
fi
echo "ok: rack_keepout_all_motion false: rack-keepout 0 and: $(grep -m1 'keep-out OFF' "$work/off.txt")"
