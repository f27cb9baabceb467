#!/usr/bin/env bash
# Installs, builds and shows the changer on the sample config: the rack check
# and the plan of a tool change.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build/fixed_atc_probe --check --config config/config.json
echo
build/fixed_atc_probe --plan --config config/config.json --from 2 --to 5
