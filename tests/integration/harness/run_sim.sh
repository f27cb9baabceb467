#!/usr/bin/env bash
# Starts the simulated machine (config/sim) headless with a display program
# of our choice, as an ordinary user (rtapi_app refuses root).
#   run_sim.sh WORKDIR DISPLAY_COMMAND   (env passes through to the display)
set -euo pipefail
# FATC_INSTALLED: the machine from an installed package's files (its
# share/fixed_atc_probe) instead of this checkout's.
root=${FATC_INSTALLED:-$(cd "$(dirname "$0")/../../.." && pwd)}
work=$1
display=$2
user=${FATC_SIM_USER:-fatc}
as_user=(runuser -u "$user" --)
if [ "$(id -u)" -ne 0 ]; then
  # Not root (a user rehearsing their machine): LinuxCNC runs as that user.
  user=$(id -un)
  as_user=()
fi
id "$user" >/dev/null 2>&1 || useradd -m -s /bin/bash "$user"

# One LinuxCNC per machine: a run from another checkout or test waits its turn
# (two at once share LinuxCNC's IPC keys and both fail).
lock=/tmp/fixed_atc_probe-linuxcnc.lock
# Read only where another user made it (a lock needs no write).
{ exec 9>>"$lock"; } 2>/dev/null || exec 9<"$lock"
flock -w 3600 9 || { echo "run_sim.sh: another LinuxCNC run held the machine for an hour" >&2; exit 1; }
# Under the lock: what LinuxCNC's IPC is there now was left by one that died.
"$(dirname "$0")/stale_ipc.sh" "$user"
mkdir -p "$work"
rm -f "$work/results.json"
if [ -z "${FATC_KEEP_STATE:-}" ] || [ ! -e "$work/sim.tbl" ]; then
  # Each run starts as a fresh machine: LinuxCNC starts with an empty spindle.
  # (FATC_KEEP_STATE: a restart of the same machine keeps its files.)
  rm -f "$work/fixed_atc_state.json"
  # FATC_TOOL_TABLE: another tool table for the same machine (the rack run's tools).
  cp "${FATC_TOOL_TABLE:-$root/config/sim/sim.tbl}" "$work/sim.tbl"
fi
cp "${FATC_CONFIG:-$root/config/config.json}" "$work/config.json"
if [ -n "${FATC_CONFIG_SET:-}" ]; then
  # Keys to set in the copied config, as a JSON object: one machine, another setting.
  python3 -c 'import json, sys; c = json.load(open(sys.argv[1])); c.update(json.loads(sys.argv[2]));
json.dump(c, open(sys.argv[1], "w"), indent=2)' "$work/config.json" "$FATC_CONFIG_SET"
fi
# FATC_SIM_INI: another machine's INI in place of config/sim's, its paths
# as config/sim's (a user's machine rehearsed, scripts/rehearse.py).
sed -e "s|^DISPLAY = .*|DISPLAY = $display|" \
    -e "s|\.\./\.\./nc_files|$root/nc_files|g" \
    -e "s|\.\./\.\./hal/|$root/hal/|g" \
    -e "s|^CONFIG = .*|CONFIG = $work/config.json|" \
    -e "s|^HALFILE = touchoff_sensor.hal|HALFILE = $root/config/sim/touchoff_sensor.hal|" \
    -e "s|^HALFILE = spindle_sim.hal|HALFILE = $root/config/sim/spindle_sim.hal|" \
    -e "s|^HALFILE = sim_rack.hal|HALFILE = $root/config/sim/sim_rack.hal|" \
    "${FATC_SIM_INI:-$root/config/sim/fixed_atc_sim.ini}" > "$work/sim.ini"
if python3 -c 'import json, sys; sys.exit(json.load(open(sys.argv[1])).get("chuck", {}).get("kind") != "collet_nut")' \
    "$work/config.json" 2>/dev/null; then
  # A collet-nut config: the simulated mill has the simulated magazine too,
  # after the spindle it reads (config/sim/sim_nut.hal).
  sed -i "s|^HALFILE = $root/config/sim/spindle_sim.hal$|&\nHALFILE = $root/config/sim/sim_nut.hal|" "$work/sim.ini"
fi
if [ -n "${FATC_INI_EXTRA:-}" ]; then
  sed -i "s|^RETURN_TO_XY = .*|$FATC_INI_EXTRA|" "$work/sim.ini"
fi
if [ -n "${FATC_INI_SED:-}" ]; then
  # A sed script for the copied INI: the same machine, e.g. with faster axes.
  sed -i -e "$FATC_INI_SED" "$work/sim.ini"
fi
if [ -n "${FATC_INI_FILTER:-}" ]; then
  # A program (and its arguments) that rewrites the copied INI in place:
  # another machine setup.
  $FATC_INI_FILTER "$work/sim.ini"
fi
if [ -n "${FATC_APP:-}" ]; then
  # A program LinuxCNC starts beside its GUI (the GUI test's driver).
  printf '\n[APPLICATIONS]\nAPP = %s\n' "$FATC_APP" >> "$work/sim.ini"
fi
chown -R "$user" "$work"
# Our binary must be on the PATH of the user LinuxCNC runs as.
bin_dir=$(dirname "$(readlink -f "${FATC_BINARY:-$root/build/fixed_atc_probe}")")
for d in "$bin_dir" "$root"; do
  while [ "$d" != "/" ]; do chmod o+rx "$d" 2>/dev/null || true; d=$(dirname "$d"); done
done
cd "$work"
# FATC_WRAP: a command LinuxCNC runs under (the GUI test's D-Bus session).
exec "${as_user[@]}" ${FATC_WRAP:-} env PATH="$bin_dir:$PATH" HOME="$(getent passwd "$user" | cut -d: -f6)" \
  FATC_ROOT="$root" FATC_SCENARIOS="${FATC_SCENARIOS:-}" FATC_RESULTS="${FATC_RESULTS:-}" \
  FATC_ARTIFACTS="${FATC_ARTIFACTS:-}" FATC_MATRIX_MODE="${FATC_MATRIX_MODE:-}" FATC_MATRIX_KINDS="${FATC_MATRIX_KINDS:-}" FATC_MATRIX_STEPS="${FATC_MATRIX_STEPS:-}" FATC_MATRIX_PENDING="${FATC_MATRIX_PENDING:-}" FATC_MATRIX_SPINDLE="${FATC_MATRIX_SPINDLE:-}" FATC_MATRIX_HOLD_STEPS="${FATC_MATRIX_HOLD_STEPS:-}" FATC_BENCH_REPEATS="${FATC_BENCH_REPEATS:-}" FATC_NO_CHANGER="${FATC_NO_CHANGER:-}" DISPLAY="${DISPLAY:-}" XAUTHORITY="${XAUTHORITY:-}" \
  RUNTESTS=1 linuxcnc "$work/sim.ini"
