#!/usr/bin/env bash
# The package's Depends on linuxcnc-uspace (cmake/linuxcnc_depends.cmake),
# judged by dpkg's own version comparison: a package built against one
# LinuxCNC release series installs onto that series from the version built
# against on, Debian's (no epoch) and LinuxCNC's own (epoch 1) alike, and
# never onto another series (2.9 and 2.10 differ in task's tool handling and
# its NML status).
#   linuxcnc_depends_test.sh CMAKE_MODULE
set -euo pipefail
module=$1
failures=0

depends_of() { cmake -DVERSION="$1" -P "$module" 2>&1; }

# satisfies DEPENDS VERSION: 0 when linuxcnc-uspace VERSION meets DEPENDS.
satisfies() {
  local clause alt op ver ok
  local IFS=','
  for clause in $1; do
    ok=1
    IFS='|'
    for alt in $clause; do
      op=$(sed -n 's/.*(\([<>=]*\) .*/\1/p' <<< "$alt")
      ver=$(sed -n 's/.*([<>=]* \([^)]*\)).*/\1/p' <<< "$alt")
      if [ -z "$op" ] || dpkg --compare-versions "$2" "$op" "$ver"; then ok=0; break; fi
    done
    IFS=','
    [ "$ok" = 0 ] || return 1
  done
}

# expect BUILT_AGAINST INSTALLED yes|no
expect() {
  local depends got
  depends=$(depends_of "$1")
  if satisfies "$depends" "$2"; then got=yes; else got=no; fi
  if [ "$got" = "$3" ]; then
    echo "ok: built against $1, onto $2: $got"
  else
    echo "FAIL: built against $1, onto $2: $got, expected $3 (Depends: $depends)"
    failures=$((failures + 1))
  fi
}

debian=2.9.0~pre1+git20230208.f1270d6ed7-1+deb12u2
expect "$debian" "$debian" yes
expect "$debian" 2.9.0~pre1+git20230208.f1270d6ed7-1+deb12u5 yes
expect "$debian" 1:2.9.10 yes             # LinuxCNC's own 2.9 release
expect "$debian" 1:2.9.4 yes
expect "$debian" 2.8.4-1 no               # the series before
expect "$debian" 1:2.8.4 no
expect "$debian" 2.10.0~pre1 no           # master, the next series
expect "$debian" 1:2.10.0~pre1 no
expect "$debian" 1:2.10.0 no
expect 1:2.9.10 1:2.9.10 yes
expect 1:2.9.10 1:2.9.11 yes
expect 1:2.9.10 1:2.9.9 no                # older than built against
expect 1:2.9.10 "$debian" no
expect 1:2.9.10 1:2.10.0~pre1 no
expect 1:2.10.0~pre1 1:2.10.0~pre1 yes
expect 1:2.10.0~pre1 1:2.10.0 yes
expect 1:2.10.0~pre1 1:2.10.3 yes
expect 1:2.10.0~pre1 1:2.9.10 no
expect 1:2.10.0~pre1 "$debian" no
expect 1:2.10.0~pre1 1:2.11.0~pre1 no
expect 2.10.0~pre1 2.10.0~pre1 yes        # a Debian 2.10 some day
expect 2.10.0~pre1 1:2.10.0 yes
expect 2.10.0~pre1 "$debian" no
expect 2.10.0~pre1 1:2.9.10 no

# The strings themselves, for the record in a failing run.
echo "Debian bookworm's: $(depends_of "$debian")"
echo "LinuxCNC 1:2.9.10's: $(depends_of 1:2.9.10)"
# A version it cannot read: the package name alone (and a warning).
bare=$(depends_of "" | tail -1)
[ "$bare" = linuxcnc-uspace ] || { echo "FAIL: no version gave '$bare'"; failures=$((failures + 1)); }
[ "$failures" = 0 ] || exit 1
echo "ok: the Depends installs only onto the LinuxCNC series built against"
