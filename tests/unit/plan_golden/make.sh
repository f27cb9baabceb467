#!/usr/bin/env bash
# Prints --plan for every change between tools 0-6 on each rack of the
# tests, on both paths and on the direct one with blend_tolerance 10: what plan_golden compares with the committed
# *.golden (and, with --write, rewrites them). BINARY SOURCE_DIR [--write]
set -euo pipefail
binary=$(realpath "$1") source=$(realpath "$2") write=${3:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
for rack in config/config.json tests/integration/rack/rack_config.json tests/bench/rack_y.json; do
  for path in prototype direct blended; do
    name=$(basename "$rack" .json)-$path
    python3 - "$source/$rack" "$path" "$work/$name.json" <<'PY'
import json, sys
config = json.load(open(sys.argv[1]))
config["path"] = "direct" if sys.argv[2] == "blended" else sys.argv[2]
if sys.argv[2] == "blended":
    config["blend_tolerance"] = 10
json.dump(config, open(sys.argv[3], "w"), indent=1)
PY
    out=$work/$name.golden
    for from in 0 1 2 3 4 5 6; do
      for to in 0 1 2 3 4 5 6; do
        echo "=== --from $from --to $to" >> "$out"
        code=0
        (cd "$work" && "$binary" --plan --config "$name.json" --from $from --to $to) >> "$out" 2>&1 || code=$?
        echo "=== exit $code" >> "$out"
      done
    done
    if [ "$write" = --write ]; then
      cp "$out" "$source/tests/unit/plan_golden/$name.golden"
    elif ! diff -u "$source/tests/unit/plan_golden/$name.golden" "$out"; then
      echo "plan_golden: --plan differs on $rack, path $path" >&2
      status=1
    fi
  done
done
exit $status
