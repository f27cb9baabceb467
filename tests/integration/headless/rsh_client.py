#!/usr/bin/python3
"""The operator of docs/setup.md#a-program-without-a-gui: types the session the
page shows into linuxcncrsh, line for line, and writes what it answered.

  rsh_client.py PORT SETUP_MD PROGRAM JOINTS RESULTS

Only the program's path is its own (`set open`). Where the page says to ask
again until the machine is homed or the program has ended, it asks again
(every 0.2 s, up to the time-outs below). Ends with the page's `shutdown`,
which stops LinuxCNC."""
import json
import re
import socket
import sys
import time

HOMING_TIMEOUT, PROGRAM_TIMEOUT = 120.0, 600.0


def session(setup_md):
    """The lines of the page's ```linuxcncrsh block."""
    text = open(setup_md).read()
    block = re.search(r"^```linuxcncrsh\n(.*?)^```", text, re.S | re.M)
    if not block:
        sys.exit("rsh_client.py: no ```linuxcncrsh block in " + setup_md)
    return [line for line in block.group(1).splitlines() if line.strip()]


class Connection:
    def __init__(self, port):
        deadline = time.monotonic() + 120
        while True:  # linuxcncrsh listens once LinuxCNC has started
            try:
                self.socket = socket.create_connection(("127.0.0.1", port), timeout=5)
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.5)
        self.socket.settimeout(30)
        self.pending = b""

    def line(self):
        while b"\n" not in self.pending:
            data = self.socket.recv(4096)
            if not data:
                raise EOFError("linuxcncrsh closed the connection")
            self.pending += data
        line, self.pending = self.pending.split(b"\n", 1)
        return line.decode(errors="replace").strip()

    def ask(self, command):
        """Sends one line; the answer is the first line that is not its echo."""
        self.socket.sendall(command.encode() + b"\r\n")
        while True:
            answer = self.line()
            if answer and answer != command:
                return answer


def homed(answer, joints):
    """`JOINT_HOMED YES YES YES NO NO NO`: the machine's first `joints` say YES."""
    words = answer.upper().split()[1:]
    return len(words) >= joints and all(w == "YES" for w in words[:joints])


def main():
    port, setup_md, program = int(sys.argv[1]), sys.argv[2], sys.argv[3]
    joints, results_path = int(sys.argv[4]), sys.argv[5]
    results = {"exchanges": [], "error": None}
    try:
        lines = session(setup_md)
        results["session"] = lines
        link = Connection(port)
        for command in lines:
            if command.startswith("set open "):
                command = "set open " + program
            if command == "shutdown":
                link.socket.sendall(b"shutdown\r\n")
                results["exchanges"].append([command, None])
                break
            answer = link.ask(command)
            results["exchanges"].append([command, answer])
            if command == "get joint_homed":
                deadline = time.monotonic() + HOMING_TIMEOUT
                while not homed(answer, joints) and time.monotonic() < deadline:
                    time.sleep(0.2)
                    answer = link.ask(command)
                results["exchanges"].append([command, answer])
            elif command == "get program_status":
                # Until it has run and ended: RUNNING first, or IDLE for a second.
                began, ran = time.monotonic(), False
                while time.monotonic() - began < PROGRAM_TIMEOUT:
                    ran = ran or "IDLE" not in answer.upper()
                    if "IDLE" in answer.upper() and (ran or time.monotonic() - began > 1.0):
                        break
                    time.sleep(0.2)
                    answer = link.ask(command)
                results["exchanges"].append([command, answer])
                results["program_ran"] = ran
    except Exception as e:  # the checker reports it; LinuxCNC must still shut down
        results["error"] = "%s: %s" % (type(e).__name__, e)
        shut_down(port)
    json.dump(results, open(results_path, "w"), indent=1)


def shut_down(port):
    """After a session that went wrong: LinuxCNC stopped all the same, from a
    connection of its own, or run_sim.sh would wait on it for ever."""
    try:
        link = Connection(port)
        for command in ("hello EMC me 1.0", "set verbose on", "set enable EMCTOO"):
            link.ask(command)
        link.socket.sendall(b"shutdown\r\n")
    except Exception:
        pass  # nothing listens: LinuxCNC is gone already


if __name__ == "__main__":
    main()
