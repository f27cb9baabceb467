#!/usr/bin/python3
"""Judges one hal/wiring snippet loaded into HAL (run by wiring_check.sh
inside halrun, with loadusr -w, after the snippet and `start`):

- every signal the snippet nets has a writer (a misspelt signal name makes a
  new signal that nothing drives, which halcmd accepts silently);
- every signal a stand-in drives reaches its readers: the test sets the
  stand-in's pin (through DRIVE, see stand_in.py) on and off, or to a speed
  and back to 0, and each pin on the signal must follow;
- the snippet's own chains (expect.json): e.g. zero speed from the drive's
  speed and its link, the probe input through the spindle guard.

One line per failure, naming the snippet's line; "ok:" lines otherwise. The
verdict goes to RESULT too (halcmd's loadusr -w does not pass an exit code on).
    wiring_check.py SNIPPET STAND_IN_NAMES DRIVE EXPECT RESULT"""
import json
import os
import subprocess
import sys
import time

TIMEOUT = 10.0  # s: generous, the machine is shared


def halcmd(*args):
    return subprocess.run(["halcmd", *args], capture_output=True, text=True, check=True).stdout


def signals():
    """{signal: (type, writer or None, [readers])} from `halcmd show sig`."""
    sigs, current = {}, None
    for line in halcmd("show", "sig").splitlines():
        words = line.split()
        if len(words) == 3 and words[0] in ("bit", "float", "s32", "u32", "port"):
            current = words[2]
            sigs[current] = (words[0], None, [])
        elif current and len(words) == 2 and words[0] in ("<==", "==>", "<=>"):
            kind, writer, readers = sigs[current]
            if words[0] == "<==":
                writer = words[1]
            else:
                readers.append(words[1])
            sigs[current] = (kind, writer, readers)
    return sigs


def value(pin):
    text = halcmd("-s", "getp", pin).strip()
    if text in ("TRUE", "FALSE"):
        return text == "TRUE"
    return float(text)


def same(a, b):
    return a == b if isinstance(b, bool) else abs(float(a) - float(b)) < 1e-6


def drive(path, values):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(values, f)
    os.replace(tmp, path)


def wait_for(pins):
    """pins {pin: expected}: the pins that never read so within TIMEOUT."""
    deadline = time.monotonic() + TIMEOUT
    while True:
        wrong = {p: value(p) for p, want in pins.items() if not same(value(p), want)}
        if not wrong or time.monotonic() > deadline:
            return wrong
        time.sleep(0.02)


def nets(snippet):
    """[(line number, signal)] of the snippet's net lines."""
    out = []
    for number, line in enumerate(open(snippet), 1):
        words = line.split("#")[0].split()
        if len(words) >= 2 and words[0] == "net":
            out.append((number, words[1]))
    return out


def main():
    snippet, stand_in_names, drive_file, expect_file, result = sys.argv[1:6]
    name = os.path.basename(snippet)
    stand_ins = tuple(n + "." for n in stand_in_names.split(","))
    failures, driven, values = [], 0, {}
    sigs = signals()
    lines = nets(snippet)
    for number, sig in lines:
        kind, writer, readers = sigs[sig]
        where = "%s:%d: signal %s" % (name, number, sig)
        if writer is None:
            failures.append("%s has no writer: nothing drives %s" % (where, " ".join(readers) or "it"))
            continue
        if not writer.startswith(stand_ins) or not readers:
            continue
        base, inverted = (writer[:-4], True) if writer.endswith("-not") else (writer, False)
        for level in ((True, False) if kind == "bit" else (1234.5, 0.0)):
            values[base] = level
            drive(drive_file, values)
            want = (not level) if inverted else level
            for pin, got in wait_for({r: want for r in readers}).items():
                failures.append("%s: %s set to %s, but %s reads %s" % (where, writer, want, pin, got))
        driven += 1
    steps = json.load(open(expect_file)).get(name, [])
    for step in steps:
        values.update(step["drive"])
        drive(drive_file, values)
        for pin, got in wait_for(step["expect"]).items():
            failures.append("%s: %s: %s reads %s, expected %s (%s)"
                            % (name, step["why"], pin, got, step["expect"][pin], json.dumps(step["drive"])))
    for line in failures:
        print("FAIL: " + line)
    if not failures:
        print("ok: %s: %d signals, each with a writer; %d driven from the stand-ins to every pin on them; "
              "%d chains as expect.json says" % (name, len(lines), driven, len(steps)))
    with open(result, "w") as f:
        f.write("fail\n" if failures else "pass\n")


if __name__ == "__main__":
    main()
