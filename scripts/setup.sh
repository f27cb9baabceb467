#!/usr/bin/env bash
# Installs what fixed_atc_probe needs on Debian bookworm (as root), then
# configures and builds it with warnings as errors into ./build.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake pkg-config libboost-dev nlohmann-json3-dev libgtest-dev libcli11-dev
          linuxcnc-uspace linuxcnc-uspace-dev graphviz python3
          # the GladeVCP panel, and the GUI test: AXIS on a virtual X server
          python3-gi gir1.2-gtk-3.0 gir1.2-gtksource-3.0 xvfb xauth dbus-daemon at-spi2-core
          python3-xlib man-db
          # qtdragon (qtvcp) for its GUI test; not python3-dbus.mainloop.pyqt5: without
          # a notification service qtvcp crashes at start with it (docs/qtdragon.md)
          python3-pyqt5 python3-pyqt5.qsci python3-pyqt5.qtsvg python3-pyqt5.qtopengl
          python3-pyqt5.qtwebkit python3-poppler-qt5 pyqt5-dev-tools
          # the fuzz test (tests/fuzz/run.sh): clang with libFuzzer and the sanitizers
          clang libclang-rt-14-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
# Arguments: the targets to build (the demo builds only what it runs); none: all.
targets=()
for target in "$@"; do targets+=(--target "$target"); done
cmake --build build -j"$(nproc)" "${targets[@]}"
# The realtime modules the HAL files load (src/rt: the chuck guard, the
# rack guard, the spindle guard, the simulated sensor, rack and nut magazine) must be in LinuxCNC's modules folder. The package installs them
# there; without the package this checkout's are compiled and installed by
# halcompile, said on one line, and an installed package later replaces those
# files with its own. Building only the package (`setup.sh deb`, as the
# README installs) installs none: the package brings its own.
modules=/usr/lib/linuxcnc/modules
if [ "$*" = deb ]; then
  echo "setup: built the package: apt-get install ./build/fixed-atc-probe_*_amd64.deb installs the realtime modules with it (none installed outside it)"
  for guard in $(cd src/rt && for c in *.comp; do echo "$modules/${c%.comp}.so"; done); do
    if [ -e "$guard" ] && ! dpkg -S "$guard" >/dev/null 2>&1; then
      echo "setup: $guard is a checkout's (an earlier setup.sh, no package owns it): the package replaces it with its own, and removing the package removes it"
    fi
  done
elif dpkg-query -W -f='${Status}' fixed-atc-probe 2>/dev/null | grep -q "install ok installed"; then
  echo "setup: the realtime modules are the installed fixed-atc-probe package's"
else
  guard=$(mktemp -d)
  cp src/rt/*.comp "$guard/"
  for comp in "$guard"/*.comp; do (cd "$guard" && halcompile --install "$comp" >/dev/null); done
  rm -rf "$guard"
  echo "setup: installed this checkout's realtime modules ($(cd src/rt && echo *.comp)) into LinuxCNC's modules folder (halcompile --install; no package owns them)"
fi
