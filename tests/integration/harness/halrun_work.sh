# Sourced by a test that runs halrun itself (pins/pins_golden.sh,
# operator/operator_signals.sh), with the checkout's root in $root and the
# binary as its argument: sets $binary (made absolute), takes the machine-wide
# lock (one LinuxCNC or halrun at a time: a run_sim.sh run ends first), makes
# the test user $user, and $work, a folder of that user's (the component
# writes its state and status files there) removed at exit, with the binary
# and the checkout readable to that user. halrun_verdict runs a HAL file whose
# program writes its verdict into $work/verdict.
binary=$(readlink -f "$1")
exec 9>>/tmp/fixed_atc_probe-linuxcnc.lock
flock -w 3600 9
user=${FATC_SIM_USER:-fatc}
id "$user" >/dev/null 2>&1 || useradd -m -s /bin/bash "$user"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
chmod 755 "$work"
chown "$user" "$work"
for d in "$(dirname "$binary")" "$root"; do
  while [ "$d" != "/" ]; do chmod o+rx "$d" 2>/dev/null || true; d=$(dirname "$d"); done
done

# halrun_verdict FILE: FILE under halrun as $user (120 s at most), what it
# printed shown; true when its program wrote "pass" into $work/verdict.
halrun_verdict() {
  chmod a+r "$1"
  runuser -u "$user" -- timeout 120 halrun -f "$1" > "$work/out.txt" 2>&1 || true
  cat "$work/out.txt"
  test "$(cat "$work/verdict" 2>/dev/null)" = pass
}
