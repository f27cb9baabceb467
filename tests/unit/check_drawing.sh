#!/usr/bin/env bash
# docs/rack.svg is what `--plot` draws of the sample config on the sim's INI now (regenerate:
# cmake --build build --target rack_drawing), and valid SVG: well-formed XML
# with an <svg> root, every pocket of the config named in it.
set -euo pipefail
binary=$1
root=$2
drawn=$(mktemp --suffix=.svg)
trap 'rm -f "$drawn"' EXIT
# Drawn from the same relative path as the target, so the titles agree.
(cd "$root" && "$binary" --plot "$drawn" --config config/config.json \
  --ini config/sim/fixed_atc_sim.ini --from 2 --to 5 >/dev/null)
mapfile -t pockets < <(python3 -c 'import json, sys
print("\n".join("pocket " + n for n in json.load(open(sys.argv[1]))["pockets"]))' "$root/config/config.json")
python3 "$root/scripts/check_svg.py" "$drawn" "${pockets[@]}"
if ! cmp -s "$drawn" "$root/docs/rack.svg"; then
  echo "docs/rack.svg is out of date: run cmake --build build --target rack_drawing"
  exit 1
fi
