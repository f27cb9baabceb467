#!/bin/bash
# --lint on every G-code program LinuxCNC installs as samples (linuxcnc-uspace:
# /usr/share/linuxcnc/ncfiles): no crash, exit 0 or 1 only, each within 30 s
# (the lint stops LinuxCNC's interpreter after 15 s),
# and a table of programs, tool changes found and problems. Skips (exit 77)
# when the folder is not there.
# usage: lint_ncfiles.sh BINARY CONFIG [NCFILES]
set -u
binary=$1
config=$2
ncfiles=${3:-/usr/share/linuxcnc/ncfiles}
if [ ! -d "$ncfiles" ]; then
  echo "SKIP: $ncfiles not found (linuxcnc-uspace installs LinuxCNC's sample programs there)"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Subroutines of the samples live in folders of their own, as in LinuxCNC's sample INIs.
subs=$(find "$ncfiles" -type d | paste -sd:)

failed=0
programs=0
changes_total=0
problems_total=0
unknown_total=0
clean=0
start=$(date +%s%N)
printf '%-58s %5s %8s %8s %9s\n' program exit changes problems "not known"
while IFS= read -r -d '' program; do
  programs=$((programs + 1))
  timeout 30 "$binary" --lint "$program" --config "$config" --state "$work/none.state" \
    --subroutine-path "$subs" >"$work/out" 2>"$work/err"
  code=$?
  summary=$(tail -n 1 "$work/out")
  # "NAME: N tool changes (M6), K M61, P problems, U not known"
  changes=$(sed -n 's/.*: \([0-9]*\) tool changes\{0,1\} (M6).*/\1/p' <<<"$summary")
  problems=$(sed -n 's/.*, \([0-9]*\) problems\{0,1\}, .*/\1/p' <<<"$summary")
  unknown=$(sed -n 's/.*, \([0-9]*\) not known$/\1/p' <<<"$summary")
  printf '%-58s %5s %8s %8s %9s\n' "${program#"$ncfiles"/}" "$code" "${changes:-?}" \
    "${problems:-?}" "${unknown:-?}"
  if [ "$code" -ne 0 ] && [ "$code" -ne 1 ]; then
    echo "  FAILED: exit $code (only 0 or 1 may come back): $(head -c 300 "$work/err")"
    failed=$((failed + 1))
  elif [ -z "$changes" ] || [ -z "$problems" ] || [ -z "$unknown" ]; then
    echo "  FAILED: no summary line: $(tail -c 300 "$work/out")"
    failed=$((failed + 1))
  else
    changes_total=$((changes_total + changes))
    problems_total=$((problems_total + problems))
    unknown_total=$((unknown_total + unknown))
    [ "$code" -eq 0 ] && clean=$((clean + 1))
  fi
done < <(find "$ncfiles" -name '*.ngc' -type f -print0 | sort -z)
milliseconds=$((($(date +%s%N) - start) / 1000000))
echo
echo "$programs programs, $clean clean, $changes_total tool changes (M6) found," \
  "$problems_total problems, $unknown_total not known, in $milliseconds ms"
[ "$programs" -gt 0 ] && [ "$failed" -eq 0 ]
