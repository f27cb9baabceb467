#!/usr/bin/env bash
# Every snippet of hal/wiring loaded into HAL as a user would load it, after
# hal/fixed_atc_probe.hal, with the hardware replaced by stand-ins of the same
# pin names (stand_ins.json, stand_in.py): LinuxCNC's motion module real
# (motmod), the changer's component and guards real, every sensor named in
# its config.json. halcmd stops at a pin no one has ("Pin '…' does not
# exist", with the snippet's file and line); wiring_check.py judges the rest.
# Each snippet's lines go to OUT/<snippet>.txt, its verdict to
# OUT/<snippet>.result (pass or fail), which ctest's integration_wiring_<snippet>
# reads; the script fails only when it could not judge them all.
#   wiring_check.sh BINARY OUT
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
# The lock, the test user and $work: harness/halrun_work.sh.
. "$root/tests/integration/harness/halrun_work.sh" "$1"
out=$2
mkdir -p "$out"

# config/config.json with every sensor, the rack cover and the air blast wired.
/usr/bin/python3 - "$root/config/config.json" "$work/config.json" <<'PY'
import json, sys
config = json.load(open(sys.argv[1]))
config["sensors"] = {key: True for key in config["sensors"]}
config["rack_cover"] = {"opened_sensor": True, "closed_sensor": True}
config["air_blast"] = True
json.dump(config, open(sys.argv[2], "w"), indent=2)
PY
# The sim's INI: the changer's section, motion's period, the axes' accelerations.
awk '/^\[/ {keep = ($0 ~ /^\[(FIXED_ATC_PROBE|EMCMOT|AXIS_[XYZ])\]$/)} keep' "$root/config/sim/fixed_atc_sim.ini" |
  sed "s|^CONFIG = .*|CONFIG = $work/config.json|;s|^STATE = .*|STATE = $work/state.json|;s|^MACHINE_ON_SIGNAL = .*|MACHINE_ON_SIGNAL = machine-is-enabled|" \
  > "$work/wiring.ini"
chmod -R a+r "$work"

for snippet in "$root"/hal/wiring/*.hal; do
  name=$(basename "$snippet")
  copy="$work/$name"
  drive="$work/drive-${name%.hal}.json"
  stand_ins=$(/usr/bin/python3 "$here/stand_in.py" --snippet "$here/stand_ins.json" "$snippet" "$copy" "$drive")
  cat > "$work/run.hal" <<HAL
# what the machine's own HAL gives the changer: motion, the card, iocontrol
loadrt trivkins coordinates=xyz
loadrt tpmod
loadrt homemod
loadrt [EMCMOT]EMCMOT servo_period_nsec=[EMCMOT]SERVO_PERIOD num_joints=3 num_dio=4 num_aio=4
addf motion-command-handler servo-thread
addf motion-controller servo-thread
source $copy.before
source $root/hal/fixed_atc_probe.hal
source $copy
start
loadusr -w /usr/bin/python3 $here/wiring_check.py $snippet $stand_ins $drive $here/expect.json $work/result-$name
HAL
  chmod a+r "$work"/*
  if ! runuser -u "$user" -- env PATH="$(dirname "$binary"):$PATH" timeout 120 halrun -i "$work/wiring.ini" -f "$work/run.hal" > "$work/out.txt" 2>&1 ||
     [ "$(cat "$work/result-$name" 2>/dev/null)" != pass ]; then
    # halcmd's own lines start with the file and line it stopped at (the
    # copy's line is the snippet's).
    { grep -hE "FAIL:|\.hal:[0-9]+: " "$work/out.txt" | sed "s|$copy|hal/wiring/$name|g" ||
        cat "$work/out.txt"
      echo "FAIL: hal/wiring/$name, loaded with the stand-ins of tests/integration/wiring/stand_ins.json"
    } > "$out/$name.txt"
    echo fail > "$out/$name.result"
  else
    grep -h "^ok:" "$work/out.txt" > "$out/$name.txt"
    echo pass > "$out/$name.result"
  fi
  cat "$out/$name.txt"
done

# The stand-ins against the real drivers where they are installed and load
# without their hardware: hy_vfd opens any serial device, a pseudo-terminal
# here, makes its pins and waits for enable. Its pins as halcmd shows them
# must be stand_ins.json's, type, direction and name.
if command -v hy_vfd > /dev/null; then
  # The terminal is held open until the file done appears (2 minutes at most).
  runuser -u "$user" -- /usr/bin/python3 -c '
import os, pty, sys, time
master, slave = pty.openpty()
open(sys.argv[1] + "/pty", "w").write(os.ttyname(slave))
end = time.monotonic() + 120
while not os.path.exists(sys.argv[1] + "/done") and time.monotonic() < end:
    time.sleep(0.1)' "$work" &
  holder=$!
  for _ in $(seq 100); do [ -s "$work/pty" ] && break; sleep 0.1; done
  cat > "$work/real.hal" <<HAL
loadusr -Wn hy-real hy_vfd -n hy-real -d $(cat "$work/pty")
show pin hy-real
HAL
  if runuser -u "$user" -- timeout 60 halrun -f "$work/real.hal" > "$work/real.txt" 2>&1; then
    awk '$5 ~ /^hy-real\./ {sub(/^hy-real\./, "", $5); print $2, tolower($3), $5}' "$work/real.txt" | sort > "$work/real-pins.txt"
    /usr/bin/python3 - "$here" > "$work/stand-in-pins.txt" <<'PY'
import json, sys
sys.dont_write_bytecode = True
sys.path.insert(0, sys.argv[1])
import stand_in
entry = json.load(open(sys.argv[1] + "/stand_ins.json"))["hy_vfd"]
print("\n".join(sorted("%s %s %s" % (kind, direction, name) for name, kind, direction in stand_in.pins_of(entry))))
PY
    if diff -u "$work/stand-in-pins.txt" "$work/real-pins.txt" > "$work/diff.txt"; then
      echo "ok: the installed hy_vfd ($(dpkg-query -W -f '${Version}' linuxcnc-uspace 2>/dev/null)) has the $(wc -l < "$work/real-pins.txt") pins stand_ins.json lists" > "$out/stand_ins.txt"
      echo pass > "$out/stand_ins.result"
    else
      { cat "$work/diff.txt"; echo "FAIL: the installed hy_vfd's pins (+) are not stand_ins.json's (-)"; } > "$out/stand_ins.txt"
      echo fail > "$out/stand_ins.result"
    fi
  else
    { cat "$work/real.txt"; echo "FAIL: the installed hy_vfd did not load on a pseudo-terminal"; } > "$out/stand_ins.txt"
    echo fail > "$out/stand_ins.result"
  fi
  touch "$work/done"
  wait "$holder"
else
  echo "ok: hy_vfd is not installed: its stand-in not compared" > "$out/stand_ins.txt"
  echo pass > "$out/stand_ins.result"
fi
cat "$out/stand_ins.txt"
