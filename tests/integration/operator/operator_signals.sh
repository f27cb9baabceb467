#!/usr/bin/env bash
# --operator ended by each signal a terminal session sends while it waits for
# the component (SIGHUP of a dropped SSH session, SIGINT, SIGTERM, SIGQUIT,
# SIGPIPE): it leaves HAL (no fatc-operator-PID left in `halcmd show comp`)
# and ends by that signal; writing into a pipe whose reader is gone, it
# presses nothing. Also: its output lost (> /dev/full) is exit 2 and one line
# on stderr. Under halrun, with the component loaded and stopped
# (SIGSTOP), so that it answers nothing and --operator waits.
#   operator_signals.sh BINARY
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
# The lock, the test user and $work: harness/halrun_work.sh.
. "$root/tests/integration/harness/halrun_work.sh" "$1"

# Inside the HAL session, as the test user.
cat > "$work/inside.sh" <<INSIDE
set -u
ulimit -c 0
# Each signal at its default, as in a terminal: halcmd leaves SIGPIPE ignored, a background job SIGINT.
# (env execs it: the pid of the job is the operator's)
operator="env --default-signal=HUP,INT,TERM,QUIT,PIPE $binary --operator"
state=$work/state.json
for i in \$(seq 100); do [ -s "\$state.status" ] && break; sleep 0.1; done
component=\$(halcmd show comp | awk '\$3 == "fixed_atc_probe" { print \$4 }')
kill -STOP "\$component"
for signal in HUP INT TERM QUIT PIPE; do
  \$operator load:3 --state "\$state" > $work/out.\$signal 2> $work/err.\$signal &
  pid=\$!
  for i in \$(seq 100); do
    halcmd show comp | grep -q "fatc-operator-\$pid" && break; sleep 0.05
  done
  sleep 0.3  # pressing the button: the signal comes while it waits
  kill -\$signal \$pid
  wait \$pid
  echo "\$signal \$? \$(halcmd show comp | grep -c fatc-operator)" >> $work/results
done
# A pipe whose reader is gone before it writes: its first line raises SIGPIPE.
mkfifo $work/pipe
exec 5<> $work/pipe 6> $work/pipe 5<&-
\$operator load:3 --state "\$state" >&6 2> $work/err.closed
echo "closed \$? \$(halcmd show comp | grep -c fatc-operator)" >> $work/results
exec 6>&-
\$operator continue --state "\$state" > /dev/full 2> $work/err.full
echo "full \$? \$(halcmd show comp | grep -c fatc-operator)" >> $work/results
kill -CONT "\$component"
INSIDE
cat > "$work/signals.hal" <<HAL
loadusr -W $binary --config $root/config/config.json --state $work/state.json
loadusr -w bash $work/inside.sh
HAL
runuser -u "$user" -- halrun -f "$work/signals.hal" > "$work/halrun.txt" 2>&1 ||
  { cat "$work/halrun.txt"; exit 1; }

failed=0
declare -A number=([HUP]=1 [INT]=2 [QUIT]=3 [PIPE]=13 [TERM]=15)
for signal in HUP INT TERM QUIT PIPE; do
  if ! read -r _ code left < <(grep "^$signal " "$work/results"); then
    echo "FAIL: SIG$signal: no result"; failed=1; continue
  fi
  said=$(cat "$work/err.$signal")
  expected="fixed_atc_probe: stopped waiting (SIG$signal), out of HAL; the request goes on in the component"
  if [ "$code" -ne $((128 + ${number[$signal]})) ] || [ "$left" -ne 0 ] || [ "$said" != "$expected" ]; then
    echo "FAIL: SIG$signal: exit $code (expected $((128 + ${number[$signal]}))), $left" \
         "fatc-operator components left, stderr: $said"
    failed=1
  else
    echo "ok: SIG$signal while it waits: out of HAL, ended by SIG$signal (exit $code), stderr: $said"
  fi
done
read -r _ code left < <(grep "^closed " "$work/results")
expected="fixed_atc_probe: stopped before asking (SIGPIPE), out of HAL; nothing was asked
fixed_atc_probe: cannot write to standard output (Broken pipe): what it printed is lost"
if [ "$code" -ne 141 ] || [ "$left" -ne 0 ] || [ "$(cat "$work/err.closed")" != "$expected" ]; then
  echo "FAIL: a closed pipe: exit $code (expected 141), $left left, stderr: $(cat "$work/err.closed")"
  failed=1
else
  echo "ok: a closed pipe: out of HAL before pressing, ended by SIGPIPE (exit 141), stderr:" \
       "$(tr '\n' '|' < "$work/err.closed")"
fi
read -r _ code left < <(grep "^full " "$work/results")
said=$(cat "$work/err.full")
lost="fixed_atc_probe: cannot write to standard output (No space left on device): what it printed is lost"
if [ "$code" -ne 2 ] || [ "$left" -ne 0 ] || [ "$(tail -1 "$work/err.full")" != "$lost" ]; then
  echo "FAIL: > /dev/full: exit $code, $left left, stderr: $said"
  failed=1
else
  echo "ok: > /dev/full: exit 2, stderr: $(tail -1 "$work/err.full")"
fi
exit $failed
