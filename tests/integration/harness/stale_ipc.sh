#!/usr/bin/env bash
# Stale LinuxCNC IPC: the shared memory and semaphores a LinuxCNC that died
# left behind (its NML buffers' keys, HAL's, RTAPI's, the simulator's UUID);
# the next start as another user stops at "Starting LinuxCNC IO program".
# Run only while holding run_sim.sh's lock: then no LinuxCNC of ours runs, and
# whatever is there is stale. The test user's own are removed; another user's
# are named with the command that removes them, and nothing starts (exit 1).
#   stale_ipc.sh USER [NML_FILE]
set -euo pipefail
user=$1
nml=${2:-/usr/share/linuxcnc/linuxcnc.nml}
keys=$( { [ -r "$nml" ] && awk '$1 == "B" && $3 == "SHMEM" {printf "0x%08x\n", $10}' "$nml"
          printf '%s\n' 0x48414c32 0x90280a48 0x48484c34; } | sort -u)
status=0
# ipcs: key id owner perms, then for shared memory bytes and attached processes.
while read -r kind key id owner attached; do
  grep -qx "$key" <<<"$keys" || continue
  what=$([ "$kind" = m ] && echo "shared memory" || echo "semaphore")
  if [ "$kind" = m ] && [ "${attached:-0}" -gt 0 ]; then
    echo "run_sim.sh: LinuxCNC's $what $key (id $id, $owner) is attached by $attached process(es): a LinuxCNC runs outside run_sim.sh; stop it first" >&2
    status=1
  elif [ "$owner" = "$user" ]; then
    ipcrm "-$kind" "$id"
    echo "run_sim.sh: removed stale LinuxCNC $what $key (id $id) of $user, left by a run that died" >&2
  else
    echo "run_sim.sh: stale LinuxCNC $what $key (id $id) of user $owner, left by a LinuxCNC that died: remove it with 'ipcrm -$kind $id' (as $owner or root)" >&2
    status=1
  fi
done < <(ipcs -m | awk 'NR > 3 && NF >= 6 {print "m", $1, $2, $3, $6}'
         ipcs -s | awk 'NR > 3 && NF >= 5 {print "s", $1, $2, $3}')
exit $status
