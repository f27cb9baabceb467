#!/usr/bin/python3
"""FATC_INI_FILTER of the status_lost run: the machine's INI given an NML file
of its own, LinuxCNC's (linuxcnc.nmlfile) with the xemc processes' lock and
read time-out cut from 10 s to 2 s. The component and the driver are xemc:
a status channel whose lock a dead reader holds is found out in seconds
instead of half a minute; nothing else changes.
    short_nml.py INI"""
import linuxcnc
import os
import re
import sys

ini = sys.argv[1]
nml = os.path.join(os.path.dirname(os.path.abspath(ini)), "short_timeouts.nml")
# "P xemc  emcStatus  LOCAL  localhost  R  0  10.0  0  10": the 7th field is the time-out.
xemc = re.compile(r"^(P\s+xemc\s+\S+\s+\S+\s+\S+\s+\S+\s+\S+\s+)10\.0(\s)", re.M)
text, cut = xemc.subn(r"\g<1>2.0\2", open(linuxcnc.nmlfile).read())
if not cut:
    sys.exit("short_nml.py: no xemc time-out of 10.0 in %s" % linuxcnc.nmlfile)
open(nml, "w").write(text)
lines = open(ini).read().splitlines()
at = lines.index("[EMC]") + 1
lines.insert(at, "NML_FILE = %s" % nml)
open(ini, "w").write("\n".join(lines) + "\n")
