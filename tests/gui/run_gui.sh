#!/usr/bin/env bash
# The GUI test: the real AXIS (or gmoccapy, qtdragon, qtdragon_hd) with
# fixed_atc_probe's panel, on a virtual X server, operated by gui_driver.py
# through the panel's buttons.
#   run_gui.sh WORKDIR BINARY [axis|gmoccapy|qtdragon|qtdragon_hd]
# Leaves results.json and the screenshots (artifacts) in WORKDIR, then checks them.
# The others than AXIS: the sim's INI with its [DISPLAY] made the GUI's
# (embed_ini.py), the panel embedded through EMBED_TAB_COMMAND.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
work=$1
gui=${3:-axis}
# qtdragon_hd's window is 1920x1080; the others fit in 1400x1000.
screen=1400x1000
case "$gui" in
  axis) filter= ;;
  gmoccapy|qtdragon) filter="$here/embed_ini.py $gui" ;;
  qtdragon_hd) filter="$here/embed_ini.py $gui"; screen=1920x1080 ;;
  *) echo "run_gui.sh: unknown GUI $gui"; exit 2 ;;
esac
user=${FATC_SIM_USER:-fatc}
id "$user" >/dev/null 2>&1 || useradd -m -s /bin/bash "$user"
# A failed run's artifacts stay beside the next run's, for whoever looks into it.
if [ -e "$work/FAILED" ]; then rm -rf "$work.failed"; mv "$work" "$work.failed"; fi
rm -rf "$work"
mkdir -p "$work"
chown "$user" "$work"

# A free display, with a cookie: AXIS's remote control (axis-remote, which the
# driver quits AXIS with) refuses an X server open to everyone.
n=90
while [ -e "/tmp/.X$n-lock" ] || [ -e "/tmp/.X11-unix/X$n" ]; do n=$((n + 1)); done
export DISPLAY=":$n" XAUTHORITY="$work/Xauthority"
xauth -f "$XAUTHORITY" add "$DISPLAY" . "$(mcookie)"
chown "$user" "$XAUTHORITY"
Xvfb "$DISPLAY" -auth "$XAUTHORITY" -nolisten tcp -screen 0 ${screen}x24 >"$work/xvfb.log" 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null || true' EXIT
for _ in $(seq 1 300); do [ -e "/tmp/.X11-unix/X$n" ] && break; sleep 0.1; done
[ -e "/tmp/.X11-unix/X$n" ] || { echo "FAIL: Xvfb did not start"; cat "$work/xvfb.log"; exit 1; }

# The GUI, the panel and the driver share one D-Bus session: the driver finds the
# panel's buttons through AT-SPI there (and qtdragon's, Qt's bridge turned on).
export QT_LINUX_ACCESSIBILITY_ALWAYS_ON=1
run() {
  FATC_APP="$here/gui_driver.py" FATC_WRAP="dbus-run-session --" FATC_INI_FILTER="$filter" \
    FATC_RESULTS="$work/results.json" FATC_ARTIFACTS="$work" FATC_BINARY="$2" \
    "$root/tests/integration/harness/run_sim.sh" "$work/sim" "$gui" > "$work/linuxcnc.log" 2>&1 &
  sim=$!
  # qtvcp may crash (LinuxCNC's own, docs/qtdragon.md): as it closes with a
  # GladeVCP panel embedded, and as it starts where python3-dbus.mainloop.pyqt5
  # is installed. LinuxCNC has then shut down and only waits for someone to
  # close its error window: nobody here will, so this does (the log keeps
  # what it said), and a crash as it starts fails the test instead of hanging it.
  while kill -0 $sim 2>/dev/null; do
    pkill -u "$user" -f show_errors.tcl 2>/dev/null || true
    sleep 1
  done
  wait $sim || true
}
run "$@"
[ -s "$work/results.json" ] || {
  touch "$work/FAILED"; echo "FAIL: no results; LinuxCNC said:"; tail -40 "$work/linuxcnc.log"; exit 1; }
echo "ok: $gui ran with the panel; results and screenshots in $work"
if grep -q "Segmentation fault.*EMCDISPLAY" "$work/linuxcnc.log"; then
  echo "note: $gui crashed as it closed (qtvcp with an embedded GladeVCP panel, docs/qtdragon.md)"
fi
python3 "$here/check_gui.py" "$work/results.json" || { touch "$work/FAILED"; exit 1; }
