#!/usr/bin/env bash
# Installs, builds and runs every test: unit (label unit) and real-LinuxCNC
# integration (label integration).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
status=0
# The benchmarks (label bench) print figures and take minutes, the soak (label
# soak) most of an hour: run them alone.
# Two at a time: the unit tests, fuzz, lint and checks overlap; every test that
# starts LinuxCNC or halrun is RUN_SERIAL (ctest runs it with nothing beside it:
# no CPU load to make LinuxCNC's motion commands time out).
ctest --test-dir build --output-on-failure -LE "bench|soak" -j2 "$@" || status=$?
# The fault matrices, as tables (ctest shows a passing test's output only with -V).
for results in build/tests/integration/fault_matrix/results.json \
               build/tests/integration/fault_matrix_restarts.json; do
  if [ -f "$results" ]; then python3 tests/integration/faults/fault_matrix_check.py "$results" --table || true; fi
done
exit "$status"
