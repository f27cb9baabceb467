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
# The realtime guards the HAL snippet loads (src/rt: the chuck guard, the
# rack guard) must be in LinuxCNC's modules folder. The package installs them
# there; without the package this checkout's are compiled and installed by
# halcompile, said on one line, and an installed package later replaces those
# files with its own.
if dpkg-query -W -f='${Status}' fixed-atc-probe 2>/dev/null | grep -q "install ok installed"; then
  echo "setup: the realtime guards are the installed fixed-atc-probe package's"
else
  guard=$(mktemp -d)
  cp src/rt/*.comp "$guard/"
  for comp in "$guard"/*.comp; do (cd "$guard" && halcompile --install "$comp" >/dev/null); done
  rm -rf "$guard"
  echo "setup: installed this checkout's realtime guards ($(cd src/rt && echo *.comp)) into LinuxCNC's modules folder (halcompile --install; no package owns them)"
fi
