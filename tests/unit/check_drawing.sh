#!/usr/bin/env bash
# docs/rack.svg is what `--plot` draws of the sample config now (regenerate:
# cmake --build build --target rack_drawing), and valid SVG: well-formed XML
# with an <svg> root, every pocket of the config named in it.
set -euo pipefail
binary=$1
root=$2
drawn=$(mktemp --suffix=.svg)
trap 'rm -f "$drawn"' EXIT
# Drawn from the same relative path as the target, so the titles agree.
(cd "$root" && "$binary" --plot "$drawn" --config config/config.json --from 2 --to 5 >/dev/null)
python3 - "$drawn" "$root/config/config.json" <<'PY'
import json, sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
if root.tag != "{http://www.w3.org/2000/svg}svg":
    sys.exit("the drawing's root is %s, not svg" % root.tag)
texts = [t.text for t in root.iter("{http://www.w3.org/2000/svg}text")]
for n in json.load(open(sys.argv[2]))["pockets"]:
    if "pocket %s" % n not in texts:
        sys.exit("pocket %s is not named in the drawing" % n)
print("valid SVG, every pocket named")
PY
if ! cmp -s "$drawn" "$root/docs/rack.svg"; then
  echo "docs/rack.svg is out of date: run cmake --build build --target rack_drawing"
  exit 1
fi
