#!/usr/bin/env bash
# Installs, builds and runs every test: unit (label unit) and real-LinuxCNC
# integration (label integration).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
ctest --test-dir build --output-on-failure "$@"
