#!/usr/bin/python3
"""Every HAL line docs/setup.md shows under "Wiring for real hardware" is a
line of a hal/wiring file (spaces aside), so the page shows what the test
loads.
    docs_lines.py ROOT"""
import glob
import sys


def words(line):
    return " ".join(line.split("#")[0].split())


def main():
    root = sys.argv[1]
    wired = {words(line) for path in glob.glob(root + "/hal/wiring/*.hal") for line in open(path)}
    page = open(root + "/docs/setup.md").read()
    section = page.split("### Wiring for real hardware", 1)[1].split("\n### ", 1)[0]
    shown, missing, in_block = 0, [], False
    for line in section.splitlines():
        if line.startswith("```"):
            in_block = line.strip() == "```hal"
        elif in_block and words(line):
            shown += 1
            if words(line) not in wired:
                missing.append(line)
    for line in missing:
        print("FAIL: docs/setup.md, Wiring for real hardware, shows a line no hal/wiring file has: " + line)
    if not shown:
        print("FAIL: docs/setup.md has no HAL lines under Wiring for real hardware")
    if missing or not shown:
        sys.exit(1)
    print("ok: the %d HAL lines docs/setup.md shows under Wiring for real hardware are hal/wiring's" % shown)


if __name__ == "__main__":
    main()
