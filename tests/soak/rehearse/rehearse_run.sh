#!/usr/bin/env bash
# The rehearsal (scripts/rehearse.py, issue 44) on a machine the project did
# not write: a copy of one of LinuxCNC's own sample configs with its tool
# table, setup step 4's [FIXED_ATC_PROBE] added and config.json placed to fit
# it; then rehearse_check.py holds the printed report against the soak's
# events file.
#   rehearse_run.sh SAMPLE_INI CONFIG_JSON WORKDIR CHANGES SEED
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
sample=$1
config=$2
work=$3
changes=$4
seed=$5
machine=$work/machine
rm -rf "$work"
mkdir -p "$machine"
table=$(/usr/bin/python3 -c 'import linuxcnc, sys; print(linuxcnc.ini(sys.argv[1]).find("EMCIO", "TOOL_TABLE"))' "$sample")
cp "$(dirname "$sample")/$table" "$machine/"
cp "$config" "$machine/fixed_atc_probe.json"
# As a user following setup step 4: LinuxCNC's own M6 moves out of [EMCIO]
# (--check refuses them), the changer's section in.
grep -v '^TOOL_CHANGE_\(POSITION\|QUILL_UP\|AT_G30\)' "$sample" > "$machine/machine.ini"
cat "$here/fixed_atc_probe_section.ini" >> "$machine/machine.ini"
status=0
"$here/../../../scripts/rehearse.py" --ini "$machine/machine.ini" --changes "$changes" --seed "$seed" \
  --workdir "$work/rehearsal" > "$work/rehearse.out" 2>&1 || status=$?
cat "$work/rehearse.out"
/usr/bin/python3 "$here/rehearse_check.py" "$machine/machine.ini" "$work/rehearsal" "$work/rehearse.out" "$changes"
exit "$status"
