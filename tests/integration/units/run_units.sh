#!/usr/bin/env bash
# The units run (issue 42): the simulated mill in inches - config/sim's INI,
# config.json and tool table divided by 25.4 (to_inch.py) - with the keys whose
# default has a unit left out, so the changer runs on its inch defaults.
# T2 is a touch probe (measured when new) whose rough length the tool table
# gives as the simulated sensor has it. units_check.py judges the results.
#   run_units.sh WORKDIR   (FATC_RESULTS, FATC_BINARY as run_sim.sh takes them)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
work=$1
mkdir -p "$work"
python3 "$here/to_inch.py" config "$root/config/config.json" "$work/units_config.json"
sed 's/^T2 P2 Z35.0 /T2 P2 Z25.0 /' "$root/config/sim/sim.tbl" > "$work/units_mm.tbl"
python3 "$here/to_inch.py" table "$work/units_mm.tbl" "$work/units.tbl"
export FATC_CONFIG="$work/units_config.json" FATC_TOOL_TABLE="$work/units.tbl"
export FATC_INI_FILTER="python3 $here/to_inch.py ini"
export FATC_CONFIG_SET='{"tools": {"2": {"kind": "probe", "measure": "new"}}}'
export FATC_SCENARIOS="$here/scenarios_units.json"
exec "$root/tests/integration/harness/run_sim.sh" "$work" "$root/tests/integration/harness/driver.py"
