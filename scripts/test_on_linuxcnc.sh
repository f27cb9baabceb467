#!/usr/bin/env bash
# The real-LinuxCNC tests against a LinuxCNC built from source, run-in-place
# (uspace), beside Debian's linuxcnc-uspace that CI tests on. As root on
# Debian bookworm:
#
#   scripts/test_on_linuxcnc.sh SRC [CTEST_ARGS...]
#
# SRC: a LinuxCNC source tree, e.g. a release exported from LinuxCNC's
# repository:  git archive v2.9.10 -- . ':!docs/po' | tar -x -C SRC
#  1. builds LinuxCNC in SRC unless it is built (SRC/bin/rtapi_app and
#     SRC/scripts/rip-environment there): its Build-Depends installed from
#     Debian by name (apt-get build-dep on what its debian/configure writes,
#     without the documentation), then autogen.sh, configure --with-realtime=uspace
#     --disable-build-documentation, make; its log in SRC/src/fatc-build.log;
#  2. builds fixed_atc_probe against it (-DLINUXCNC_ROOT=SRC: SRC's headers,
#     libraries and halcompile, which compiles the realtime guards of src/rt)
#     in a build folder of its own, build-lcnc-<SRC's folder name>
#     (FATC_LCNC_BUILD names another), and puts every src/rt module into
#     SRC/rtlib where that LinuxCNC loads realtime modules from;
#  3. runs the integration label (the real LinuxCNC headless, and the GUI
#     tests on a virtual X server) and the linuxcnc label (the adapters'
#     unit tests against SRC) with SRC's rip-environment, and ends with
#     ctest's summary line and its exit status. CTEST_ARGS go to ctest, e.g.
#     -R integration_run.
# Every LinuxCNC start takes the machine-wide lock (run_sim.sh, pins_golden.sh):
# one LinuxCNC on the machine at a time.
set -euo pipefail
[ $# -ge 1 ] || { sed -n '2,24p' "$0"; exit 2; }
[ "$(id -u)" = 0 ] || { echo "test_on_linuxcnc.sh: as root (apt-get, the test user)"; exit 2; }
root=$(cd "$(dirname "$0")/.." && pwd)
src=$(cd "$1" && pwd)
shift
[ -x "$src/src/autogen.sh" ] || [ -x "$src/bin/rtapi_app" ] ||
  { echo "test_on_linuxcnc.sh: $src is no LinuxCNC source tree (no src/autogen.sh)"; exit 2; }
# The system's folders only: pyenv's shims or another Python first on the
# PATH make LinuxCNC's configure find no Python, and the tests run LinuxCNC's
# Python module for the system's python3.
export PATH=/usr/sbin:/usr/bin:/sbin:/bin
export DEBIAN_FRONTEND=noninteractive
version=$(cat "$src/VERSION")
build=${FATC_LCNC_BUILD:-$root/build-lcnc-$(basename "$src")}
jobs=$(nproc)
say() { echo "test_on_linuxcnc.sh: $*"; }

# The project's own packages (as scripts/setup.sh, LinuxCNC left out): the
# build and the GUI tests.
packages=(build-essential cmake pkg-config libboost-dev nlohmann-json3-dev libgtest-dev libcli11-dev
          graphviz python3 python3-gi gir1.2-gtk-3.0 gir1.2-gtksource-3.0 xvfb xauth dbus-daemon
          at-spi2-core python3-xlib man-db)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  say "installing ${missing[*]}"
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# 1. LinuxCNC, run-in-place.
if [ -x "$src/bin/rtapi_app" ] && [ -f "$src/scripts/rip-environment" ] && [ -f "$src/lib/liblinuxcnc.a" ]; then
  say "LinuxCNC $version in $src is built"
else
  log=$src/src/fatc-build.log
  say "building LinuxCNC $version in $src (log: $log)"
  start=$(date +%s)
  # Its Build-Depends as its own debian/configure writes them (debian/control),
  # without the documentation's (build profile nodoc) and the package tests'.
  (cd "$src" && debian/configure no-docs) > "$log" 2>&1
  apt-get update -qq
  apt-get build-dep -y -qq --no-install-recommends --arch-only -P nodoc,nocheck "$src" >> "$log" 2>&1 ||
    { tail -20 "$log"; say "its build dependencies did not install"; exit 1; }
  # The man pages are built even without the documentation, and validated
  # against the DocBook DTD offline (2.9: a2x; master: asciidoctor, in its
  # Build-Depends); configure looks for libedit's readline headers.
  apt-get install -y -qq --no-install-recommends libedit-dev docbook-xml docbook-xsl xsltproc \
    asciidoc-base >> "$log" 2>&1
  (cd "$src/src" &&
   ./autogen.sh &&
   ./configure --with-realtime=uspace --disable-build-documentation --disable-check-runtime-deps &&
   nice -n 10 make -j"$jobs") >> "$log" 2>&1 ||
    { tail -30 "$log"; say "LinuxCNC $version did not build (log: $log)"; exit 1; }
  say "built LinuxCNC $version in $(( $(date +%s) - start )) s"
fi

# What its linuxcnc-uspace package would bring along (its Depends in the
# debian/control that debian/configure writes): a run-in-place tree is no
# package, and its GUIs need them (2.9.10's gladevcp imports GtkSource 4,
# Debian's 2.9.0~pre1 GtkSource 3). python3-opencv (qtvcp's camera view
# only, some 160 packages) left out; of alternatives the first. Left out too:
# python3-dbus.mainloop.pyqt5, with which qtvcp crashes as it starts where no
# notification service runs (docs/qtdragon.md) - and it stays installed: the
# project's own QtDragon tests on the same machine crashed at every start after
# a run of this script had installed it (6 December 2026).
[ -f "$src/debian/control" ] || (cd "$src" && debian/configure no-docs) > /dev/null
mapfile -t runtime < <(awk '/^Package: linuxcnc-uspace$/ {p = 1} p && /^Depends:/ {d = 1; next}
                            d && /^[^ \t]/ {exit} d' "$src/debian/control" |
  tr ',' '\n' | sed -e 's/|.*//' -e 's/(.*)//' -e 's/^[ \t]*//' -e 's/[ \t]*$//' |
  grep -v -e '^\$' -e '^$' -e '^python3-opencv$' -e '^python3-dbus.mainloop.pyqt5$')
# A name may be a virtual package (tclx, tclreadline: tclx8.4 and
# tcl-tclreadline provide them): one that an installed package provides is there.
provided=$(dpkg-query -W -f='${db:Status-Abbrev} ${Provides}\n' 2>/dev/null | awk '/^ii/ {$1 = ""; print}' |
  tr ',' '\n' | sed -e 's/(.*)//' -e 's/^[ \t]*//' -e 's/[ \t]*$//')
missing=()
for p in "${runtime[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
    grep -qxF -- "$p" <<< "$provided" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  say "installing LinuxCNC $version's run-time dependencies: ${missing[*]}"
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
# rtapi_app setuid root as Debian's package installs it (mode 4755; `make
# setuid`'s 4750 would keep the test user out): on a realtime kernel
# (PREEMPT_RT) that is what gives its threads realtime priority. On a stock
# kernel LinuxCNC runs "POSIX non-realtime" either way, 2.9 and 2.10 alike.
if [ ! -u "$src/bin/rtapi_app" ] || [ "$(stat -c %U "$src/bin/rtapi_app")" != root ]; then
  chown root "$src/bin/rtapi_app"
  chmod 4755 "$src/bin/rtapi_app"
  say "rtapi_app made setuid root, as Debian's package has it"
fi
# LinuxCNC runs as an ordinary user (rtapi_app refuses root), who must reach
# the tree: its programs, libraries, modules and Python.
d=$src
while [ "$d" != "/" ]; do chmod o+rx "$d"; d=$(dirname "$d"); done
# Its environment: SRC's programs, libraries and Python module first.
# rip-environment reads unset variables.
set +u
# shellcheck disable=SC1091
source "$src/scripts/rip-environment"
set -u
export LD_LIBRARY_PATH PYTHONPATH TCLLIBPATH

# 2. The changer against it.
say "building fixed_atc_probe against LinuxCNC $version in $build"
launcher=()
# ccache, where there is one: the core is the same code as the Debian build's.
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DLINUXCNC_ROOT="$src" "${launcher[@]}" \
  > "$build.cmake.log" 2>&1 ||
  { cat "$build.cmake.log"; exit 1; }
rm -f "$build.cmake.log"
nice -n 10 cmake --build "$build" -j"$jobs" --target fixed_atc_probe realtime_guards linuxcnc_tests
# Every realtime module of src/rt (the chuck guard, the rack guard), as
# SRC's halcompile compiled it, into SRC/rtlib.
for comp in "$root"/src/rt/*.comp; do
  module=$(basename "$comp" .comp).so
  [ -f "$build/rt/$module" ] ||
    { say "$build/rt/$module was not built: CMake's realtime_guards lacks $(basename "$comp")"; exit 1; }
  install -m 644 "$build/rt/$module" "$src/rtlib/$module"
  say "$module (compiled by $src/bin/halcompile) is in $src/rtlib"
done

# 3. The real-LinuxCNC tests, ending with ctest's summary.
say "running the integration tests on LinuxCNC $version ($(command -v linuxcnc))"
exec ctest --test-dir "$build" -L 'integration|linuxcnc' --output-on-failure "$@"
