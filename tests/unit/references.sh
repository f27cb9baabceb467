#!/usr/bin/env bash
# The references generated from the code (fatc_docs) against the committed ones.
#   references.sh check|write FATC_DOCS PROJECT_ROOT
# check: exit 1 naming each stale file; write: bring them up to date.
set -euo pipefail
mode=$1
docs=$2
root=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
generate() {  # FILE COMMAND...
  local file=$1
  shift
  mkdir -p "$work/$(dirname "$file")"
  "$docs" "$@" > "$work/$file"
}
generate docs/pins.md pins-md
generate docs/config.md config-md
generate docs/command-line.md cli-md
generate docs/fixed_atc_probe.1 man "$root/docs/fixed_atc_probe.1.in"
generate tests/integration/pins/pins.golden pins-golden "$root/config/config.json"
stale=0
for file in docs/pins.md docs/config.md docs/command-line.md docs/fixed_atc_probe.1 tests/integration/pins/pins.golden; do
  if [ "$mode" = write ]; then
    cp "$work/$file" "$root/$file"
  elif ! cmp -s "$work/$file" "$root/$file"; then
    echo "$file is stale: run \`cmake --build build --target references\`"
    diff -u "$root/$file" "$work/$file" | head -20 || true
    stale=1
  fi
done
exit "$stale"
