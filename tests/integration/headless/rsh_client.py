#!/usr/bin/python3
"""The operator of docs/setup.md#a-program-without-a-gui: types the session the
page shows into linuxcncrsh, line for line, and writes what it answered.

  rsh_client.py display SETUP_MD
      prints the page's [DISPLAY]DISPLAY line's value (run_headless.sh puts it
      into the INI, with a port of its own)
  rsh_client.py PORT SETUP_MD PROGRAM JOINTS RESULTS
      the session; LinuxCNC starts it as an [APPLICATIONS]APP, so it lives
      as long as LinuxCNC does

Only the program's path is its own (`set open`). Where the page says to ask
again - until the machine's JOINTS joints are homed, until the program has
run and ended - it asks again every 0.2 s, up to the time-outs below. The
page's `shutdown` stops LinuxCNC; a session that goes wrong stops it too."""
import json
import re
import socket
import sys
import time

CONNECT_TIMEOUT, HOMING_TIMEOUT, PROGRAM_TIMEOUT = 120.0, 120.0, 600.0


def section(setup_md):
    text = open(setup_md).read()
    start = text.find("### A program without a GUI")
    if start < 0:
        raise ValueError("no section 'A program without a GUI' in " + setup_md)
    return text[start:]


def display(setup_md):
    found = re.search(r"^```ini\n\[DISPLAY\]\nDISPLAY = (linuxcncrsh[^\n]*)\n```", section(setup_md), re.M)
    if not found:
        raise ValueError("no [DISPLAY] DISPLAY = linuxcncrsh block in " + setup_md)
    return found.group(1)


def session(setup_md):
    """The lines of the section's ```linuxcncrsh block."""
    block = re.search(r"^```linuxcncrsh\n(.*?)^```", section(setup_md), re.S | re.M)
    if not block:
        raise ValueError("no ```linuxcncrsh block in " + setup_md)
    return [line for line in block.group(1).splitlines() if line.strip()]


class Connection:
    def __init__(self, port):
        deadline = time.monotonic() + CONNECT_TIMEOUT
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


def run(port, lines, program, joints, results):
    link = Connection(port)
    for command in lines:
        if command.startswith("set open "):
            command = "set open " + program
        if command == "shutdown":
            link.socket.sendall(b"shutdown\r\n")
            results["exchanges"].append([command, None])
            return True
        answer = link.ask(command)
        results["exchanges"].append([command, answer])
        if command == "get joint_homed":
            deadline = time.monotonic() + HOMING_TIMEOUT
            while not homed(answer, joints) and time.monotonic() < deadline:
                time.sleep(0.2)
                answer = link.ask(command)
            results["exchanges"].append([command, answer])
        elif command == "get program_status":
            # As the page says: until it has said RUNNING, then IDLE.
            began, ran = time.monotonic(), False
            while time.monotonic() - began < PROGRAM_TIMEOUT:
                ran = ran or "RUNNING" in answer.upper()
                if ran and "IDLE" in answer.upper():
                    break
                time.sleep(0.2)
                answer = link.ask(command)
            results["exchanges"].append([command, answer])
            results["program_ran"] = ran
    return False


def shut_down(port, lines):
    """LinuxCNC stopped all the same, from a connection of its own with the
    page's passwords, or run_sim.sh would wait on it for ever."""
    try:
        link = Connection(port)
        for command in lines:
            if command.startswith(("hello ", "set verbose", "set enable ")):
                link.ask(command)
        link.socket.sendall(b"shutdown\r\n")
    except Exception:
        pass  # nothing listens: LinuxCNC is gone already


def main():
    if sys.argv[1:2] == ["display"]:
        print(display(sys.argv[2]))
        return
    port, setup_md, program = int(sys.argv[1]), sys.argv[2], sys.argv[3]
    joints, results_path = int(sys.argv[4]), sys.argv[5]
    results = {"exchanges": [], "error": None}
    lines, shut = [], False
    try:
        lines = session(setup_md)
        results["session"] = lines
        shut = run(port, lines, program, joints, results)
        if not shut:
            results["error"] = "the page's session has no shutdown"
    except BaseException as e:  # the checker reports it; LinuxCNC must still shut down
        results["error"] = "%s: %s" % (type(e).__name__, e)
    finally:
        if not shut:
            shut_down(port, lines or ["hello EMC me 1.0", "set verbose on", "set enable EMCTOO"])
        json.dump(results, open(results_path, "w"), indent=1)


if __name__ == "__main__":
    main()
