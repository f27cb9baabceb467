#!/usr/bin/env python3
"""stale_ipc.sh, run_sim.sh's look at LinuxCNC IPC under its lock: a stale
semaphore and shared memory of the test user are removed; one of another user
is named with the command that removes it, and nothing may start; shared
memory a process still has attached means a LinuxCNC runs: refused. Keys of
an NML file of our own (never LinuxCNC's), made as each user with semget and
shmget, everything removed after. As root, else skipped (77).
   stale_ipc_test.py STALE_IPC_SH TEST_USER"""
import fcntl
import os
import re
import subprocess
import sys
import tempfile

SEM_KEY = 0x46415401  # "FAT\\1", "FAT\\2": no LinuxCNC buffer's
SHM_KEY = 0x46415402
MAKE = """import ctypes, sys, time
libc = ctypes.CDLL(None, use_errno=True)
kind, key = sys.argv[1], int(sys.argv[2])
if kind == "s":
    made = libc.semget(key, 1, 0o1000 | 0o600)
else:
    made = libc.shmget(key, 4096, 0o1000 | 0o600)
    libc.shmat.restype = ctypes.c_void_p
    if len(sys.argv) > 3 and libc.shmat(made, None, 0) in (None, ctypes.c_void_p(-1).value):
        sys.exit("shmat failed")
if made < 0:
    sys.exit("%sget failed: %d" % (kind, ctypes.get_errno()))
print(made, flush=True)
if len(sys.argv) > 3:
    time.sleep(60)
"""


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def make(user, kind, key, attach=False):
    """An IPC object of `user`: its id (and the process holding it attached)."""
    args = ["python3", "-c", MAKE, kind, str(key)] + (["attach"] if attach else [])
    # The process itself as the user (no runuser between): killing it detaches.
    holder = subprocess.Popen(args, stdout=subprocess.PIPE, text=True, user=user)
    ident = int(holder.stdout.readline())
    if not attach:
        holder.wait()
    return ident, holder


def listed(kind, ident):
    out = subprocess.run(["ipcs", "-" + kind], capture_output=True, text=True).stdout
    return any(line.split()[1:2] == [str(ident)] for line in out.splitlines() if line.startswith("0x"))


def remove(kind, ident):
    subprocess.run(["ipcrm", "-" + kind, str(ident)], stderr=subprocess.DEVNULL)


def check(script, nml, user, code, pattern):
    run = subprocess.run([script, user, nml], capture_output=True, text=True)
    lines = run.stderr.splitlines()
    if run.returncode != code or len(lines) != 1 or not re.fullmatch(pattern, lines[0]):
        fail("expected exit %d and one line matching %r, got %d: %r" % (code, pattern, run.returncode, run.stderr))
    print("ok: exit %d: %s" % (code, lines[0]))


def main():
    script, user = sys.argv[1], sys.argv[2]
    if os.geteuid() != 0:
        print("not root: cannot make IPC as other users; skipped")
        sys.exit(77)
    subprocess.run(["id", user], check=True, capture_output=True)
    # Under run_sim.sh's lock, as stale_ipc.sh must be: no LinuxCNC starts meanwhile.
    lock = open("/tmp/fixed_atc_probe-linuxcnc.lock", "a")
    fcntl.flock(lock, fcntl.LOCK_EX)
    with tempfile.TemporaryDirectory() as folder:
        nml = os.path.join(folder, "test.nml")
        with open(nml, "w") as f:
            f.write("B testSem SHMEM localhost 1024 0 0 1 16 %d TCP=5005 xdr\n" % SEM_KEY)
            f.write("B testShm SHMEM localhost 1024 0 0 2 16 %d TCP=5005 xdr\n" % SHM_KEY)
        made = []
        try:
            ident, _ = make(user, "s", SEM_KEY)
            made.append(("s", ident))
            check(script, nml, user, 0,
                  r"run_sim\.sh: removed stale LinuxCNC semaphore 0x46415401 \(id %d\) of %s, left by a run that died" % (ident, user))
            if listed("s", ident):
                fail("the test user's semaphore %d is still there" % ident)
            ident, _ = make("nobody", "s", SEM_KEY)
            made.append(("s", ident))
            check(script, nml, user, 1,
                  r"run_sim\.sh: stale LinuxCNC semaphore 0x46415401 \(id %d\) of user nobody, left by a LinuxCNC "
                  r"that died: remove it with 'ipcrm -s %d' \(as nobody or root\)" % (ident, ident))
            if not listed("s", ident):
                fail("another user's semaphore was removed")
            remove("s", ident)
            ident, holder = make(user, "m", SHM_KEY, attach=True)
            made.append(("m", ident))
            try:
                check(script, nml, user, 1,
                      r"run_sim\.sh: LinuxCNC's shared memory 0x46415402 \(id %d, %s\) is attached by 1 "
                      r"process\(es\): a LinuxCNC runs outside run_sim\.sh; stop it first" % (ident, user))
            finally:
                holder.kill()
                holder.wait()
            check(script, nml, user, 0,
                  r"run_sim\.sh: removed stale LinuxCNC shared memory 0x46415402 \(id %d\) of %s, left by a run that died" % (ident, user))
        finally:
            for kind, ident in made:
                remove(kind, ident)


if __name__ == "__main__":
    main()
