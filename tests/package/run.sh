#!/usr/bin/env bash
# The Debian package, as a user meets it: builds it (the `deb` target), installs
# it with apt, checks its files are where Debian and LinuxCNC users look,
# runs the simulated demo from the installed files only (the binary in
# /usr/bin; NGC, HAL, panel and sample configs in /usr/share/fixed_atc_probe;
# the chuck guard in LinuxCNC's modules), removes it with --purge and checks
# nothing of it is left. Then puts back the realtime modules the build tree's
# tests load (scripts/setup.sh's, kept aside before the install). As root.
#   tests/package/run.sh BUILD_DIR
set -euo pipefail
[ "$(id -u)" = 0 ] || { echo "tests/package/run.sh: needs root (apt-get install)"; exit 77; }
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "$1" && pwd)
export DEBIAN_FRONTEND=noninteractive

cmake --build "$build" --target deb >/dev/null
deb=$(ls -t "$build"/fixed-atc-probe_*.deb | head -1)
echo "package: $(basename "$deb") ($(du -k "$deb" | cut -f1) KiB)"
dpkg-deb --field "$deb" Package Version Depends Recommends
# Only onto the LinuxCNC series it was built for (cmake/linuxcnc_depends.cmake).
dpkg-deb --field "$deb" Depends | grep -q 'linuxcnc-uspace (<< ' ||
  { echo "FAIL: the package's Depends does not pin the LinuxCNC series it was built against"; exit 1; }

# The realtime modules the build tree's tests load (scripts/setup.sh's), kept
# aside: the package replaces them and --purge removes them.
modules=/usr/lib/linuxcnc/modules
kept=$(mktemp -d)
for comp in "$root"/src/rt/*.comp; do
  module=$modules/$(basename "${comp%.comp}").so
  if [ -e "$module" ]; then cp -p "$module" "$kept/"; fi
done
put_back_guard() {
  local tmp comp
  # A failed run leaves nothing installed either.
  dpkg -s fixed-atc-probe >/dev/null 2>&1 && apt-get remove --purge -y -qq fixed-atc-probe >/dev/null
  # Those kept, as they were; halcompile only for one there was none of.
  tmp=$(mktemp -d)
  for comp in "$root"/src/rt/*.comp; do
    if [ -e "$kept/$(basename "${comp%.comp}").so" ]; then
      cp -p "$kept/$(basename "${comp%.comp}").so" "$modules/"
    else
      cp "$comp" "$tmp/" && (cd "$tmp" && halcompile --install "$(basename "$comp")" >/dev/null)
    fi
  done
  rm -rf "$tmp" "$kept"
}
trap put_back_guard EXIT

# --reinstall: a package of the same version left by an earlier run is replaced.
apt-get install -y -qq --reinstall "$deb" >/dev/null
files=$(dpkg -L fixed-atc-probe)
for want in /usr/bin/fixed_atc_probe /usr/lib/linuxcnc/modules/fatc_chuck_guard.so \
            /usr/lib/linuxcnc/modules/fatc_rack_guard.so \
            /usr/lib/linuxcnc/modules/fatc_spindle_guard.so \
            /usr/share/fixed_atc_probe/nc_files/fixed_atc_probe_m6.ngc \
            /usr/share/fixed_atc_probe/nc_files/fixed_atc_probe_execute.ngc \
            /usr/share/fixed_atc_probe/nc_files/fixed_atc_probe_chuck_release.ngc \
            /usr/share/fixed_atc_probe/nc_files/fixed_atc_probe_chuck_clamp.ngc \
            /usr/share/fixed_atc_probe/nc_files/fixed_atc_probe_chuck_eject.ngc \
            /usr/share/fixed_atc_probe/nc_files/fixed_atc_probe_save_modes.ngc \
            /usr/share/fixed_atc_probe/nc_files/fixed_atc_probe_on_abort.ngc \
            /usr/share/fixed_atc_probe/hal/fixed_atc_probe.hal \
            /usr/share/fixed_atc_probe/hal/fixed_atc_probe_panel.ui \
            /usr/share/fixed_atc_probe/hal/wiring/mesa_7i76e.hal \
            /usr/share/fixed_atc_probe/hal/wiring/vfd_huanyang.hal \
            /usr/share/fixed_atc_probe/config/config.json \
            /usr/share/fixed_atc_probe/config/sim/fixed_atc_sim.ini \
            /usr/share/doc/fixed-atc-probe/README.md \
            /usr/share/doc/fixed-atc-probe/docs/setup.md \
            /usr/share/doc/fixed-atc-probe/docs/reference.md \
            /usr/share/doc/fixed-atc-probe/docs/panel.png \
            /usr/share/doc/fixed-atc-probe/docs/gmoccapy.md; do
  grep -qx "$want" <<< "$files" || { echo "FAIL: the package has no $want"; exit 1; }
done
man -w fixed_atc_probe >/dev/null || { echo "FAIL: man fixed_atc_probe finds no page"; exit 1; }
# The installed program says the package's version (both from CMakeLists.txt's project()).
said=$(/usr/bin/fixed_atc_probe --version)
version=$(dpkg-deb --field "$deb" Version)
[[ "$said" == "fixed_atc_probe $version"* ]] ||
  { echo "FAIL: --version says \"$said\", the package is $version"; exit 1; }
echo "ok: $said"
if grep -q "__pycache__\|\.state$" <<< "$files"; then echo "FAIL: build leftovers packaged"; exit 1; fi
echo "ok: installed $(grep -c . <<< "$files") paths, each where expected; man fixed_atc_probe works"
/usr/bin/fixed_atc_probe --check --config /usr/share/fixed_atc_probe/config/config.json \
  --ini /usr/share/fixed_atc_probe/config/sim/fixed_atc_sim.ini | tail -1

# The demo from the installed files: run_sim.sh with FATC_INSTALLED copies the
# installed sample machine into a work folder, as a user copies a sample config;
# FATC_INI_SED and FATC_CONFIG_SET (the integration runs' faster axes and slow
# moves) only shorten it.
work=$(mktemp -d /tmp/fixed_atc_package.XXXXXX)
chmod 755 "$work"
printf '[{"name": "demo", "program": "nc_files/demo.ngc", "timeout": 600}]\n' > "$work/scenarios.json"
chmod 644 "$work/scenarios.json"
FATC_INSTALLED=/usr/share/fixed_atc_probe FATC_BINARY=/usr/bin/fixed_atc_probe \
  FATC_INI_SED="${FATC_INI_SED:-}" FATC_CONFIG_SET="${FATC_CONFIG_SET:-}" \
  FATC_SCENARIOS="$work/scenarios.json" FATC_RESULTS="$work/run/results.json" \
  "$root/tests/integration/harness/run_sim.sh" "$work/run" "$root/tests/integration/harness/driver.py" > "$work/linuxcnc.log" 2>&1 || {
  echo "FAIL: LinuxCNC failed; its output is in $work/linuxcnc.log"; exit 1; }
python3 - "$work/run/results.json" <<'PY'
import json, sys
results = json.load(open(sys.argv[1]))
if results["error"]:
    sys.exit("FAIL: the demo from the installed files: %s" % results["error"])
run = results["scenarios"][0]
tools = [run["samples"][0]["tool_in_spindle"]]
for s in run["samples"]:
    if s["tool_in_spindle"] != tools[-1]:
        tools.append(s["tool_in_spindle"])
if tools != [0, 1, 3, 0, 5]:
    sys.exit("FAIL: the demo's tools went %s, expected [0, 1, 3, 0, 5]" % tools)
print("ok: the demo ran from the installed files: tools %s in %.1f s" % (tools, run["duration"]))
PY
grep -q "^CONFIG = $work/run/config.json" "$work/run/sim.ini" || {
  echo "FAIL: the demo's INI does not read the copied config"; exit 1; }
grep -q "SUBROUTINE_PATH = /usr/share/fixed_atc_probe/nc_files" "$work/run/sim.ini" || {
  echo "FAIL: the demo's INI does not take its NGC from the package"; exit 1; }

apt-get remove --purge -y -qq fixed-atc-probe >/dev/null
left=$(while read -r path; do [ -f "$path" ] && echo "$path"; done <<< "$files" || true)
if [ -n "$left" ]; then echo "FAIL: left after removal: $left"; exit 1; fi
if [ -e /usr/share/fixed_atc_probe ]; then echo "FAIL: /usr/share/fixed_atc_probe left"; exit 1; fi
echo "ok: removed with --purge, nothing of it left"
