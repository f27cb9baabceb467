# linuxcnc_depends(VERSION OUT): the package's Depends on linuxcnc-uspace for
# a build against LinuxCNC VERSION (a Debian version, e.g. the installed
# linuxcnc-uspace-dev's): that version or later within its release series
# (major.minor), never the next series, whose NML status layout may differ.
#
#   2.9.0~pre1+git20230208.f1270d6ed7-1+deb12u2 (Debian bookworm) ->
#     linuxcnc-uspace (>= 2.9.0~pre1+git20230208.f1270d6ed7-1+deb12u2),
#     linuxcnc-uspace (<< 2.10~) | linuxcnc-uspace (>= 1:2.9~),
#     linuxcnc-uspace (<< 1:2.10~)
#   1:2.9.10 (LinuxCNC's own packages carry the epoch 1) ->
#     linuxcnc-uspace (>= 1:2.9.10), linuxcnc-uspace (<< 1:2.10~)
#
# Debian's own packages have no epoch, LinuxCNC's have 1, and every 1:x sorts
# after every x: a build against Debian's 2.9 also takes LinuxCNC's 2.9
# releases (1:2.9.x, the same series), which needs the second range, written
# as the conjunction Debian's Depends allows:
#   v >= built AND (v << 2.10~ OR v >= 1:2.9~) AND v << 1:2.10~.
# An empty or unreadable VERSION: the package name alone, with a warning.
# tests/unit/linuxcnc_depends_test.sh checks these against dpkg's comparison.
function(linuxcnc_depends version out)
  set(pkg linuxcnc-uspace)
  if(NOT version MATCHES "^(([0-9]+):)?([0-9]+)\\.([0-9]+)")
    message(WARNING "LinuxCNC version '${version}' not understood: the package depends on any ${pkg}")
    set(${out} ${pkg} PARENT_SCOPE)
    return()
  endif()
  set(epoch "${CMAKE_MATCH_2}")
  set(major "${CMAKE_MATCH_3}")
  set(minor "${CMAKE_MATCH_4}")
  math(EXPR next "${minor} + 1")
  if(epoch STREQUAL "" OR epoch STREQUAL "0")
    set(${out}
        "${pkg} (>= ${version}), ${pkg} (<< ${major}.${next}~) | ${pkg} (>= 1:${major}.${minor}~), ${pkg} (<< 1:${major}.${next}~)"
        PARENT_SCOPE)
  else()
    set(${out} "${pkg} (>= ${version}), ${pkg} (<< ${epoch}:${major}.${next}~)" PARENT_SCOPE)
  endif()
endfunction()

# cmake -DVERSION=... -P cmake/linuxcnc_depends.cmake prints the Depends.
if(CMAKE_SCRIPT_MODE_FILE STREQUAL CMAKE_CURRENT_LIST_FILE)
  linuxcnc_depends("${VERSION}" depends)
  message("${depends}")
endif()
