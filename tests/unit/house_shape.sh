#!/usr/bin/env bash
# The house keeps its shape (issue 43): no include loop between the folders of
# src/ or inside one (scripts/include_loops.py), no source file over 500 lines.
set -euo pipefail
root="$1"
status=0
"$root/scripts/include_loops.py" "$root/src" || status=1
while read -r lines file; do
  if [ "$file" != total ] && [ "$lines" -gt 500 ]; then
    echo "$file: $lines lines, over 500: split it by concern"
    status=1
  fi
done < <(find "$root/src" -name '*.cpp' -o -name '*.hpp' -o -name '*.cc' -o -name '*.comp' | xargs wc -l)
exit "$status"
