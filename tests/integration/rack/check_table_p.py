#!/usr/bin/env python3
"""Checks the rack map in LinuxCNC's tool table (issue 34) after the rack run
(scenarios_rack.json): every rack tool's pocket in the P column of the file
LinuxCNC writes and in LinuxCNC's memory, after the program's changes with
tools outside their numbered pockets and T20 loaded into pocket 3; a G10 L1
keeps them and its length stays; a P edited as a GUI's tool page does is
written back, the operator told, the length kept.
   check_table_p.py RESULTS.json
Prints what it checked and the table lines; exits 1 on the first failed expectation."""
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "harness"))
from check import fail, load_results, ok, scenario  # noqa: E402
from tool_table import file_lines  # noqa: E402

# rack_config.json's pockets after the run: T20 loaded into 3, T3 in the spindle (belongs in 4).
POCKETS = {12: 1, 7: 2, 20: 3, 3: 4, 5: 5, 6: 6}
COMMENTS = {3: "10mm face mill, pocket 4 (top)", 20: "4mm end mill, loaded into pocket 3 by the run"}


def check_table(table, what, lengths):
    print("%s, the file LinuxCNC wrote:\n%s" % (what, table["file"]))
    lines = file_lines(table["file"])
    for tool, pocket in POCKETS.items():
        if lines.get(tool, (None,))[0] != pocket:
            fail("%s: the file's line of T%d has P %s, not %d" % (what, tool, lines.get(tool), pocket))
    for tool, comment in COMMENTS.items():
        if lines[tool][2] != comment:
            fail("%s: T%d's comment %r, not %r" % (what, tool, lines[tool][2], comment))
    for tool, z in lengths.items():
        if abs(lines[tool][1] - z) > 1e-6:
            fail("%s: T%d's Z %s in the file, not %s" % (what, tool, lines[tool][1], z))
    ok("%s: the file has every rack tool's pocket in P and the lengths %s" % (what, lengths))
    # The memory as read from the mmap is the one stat shows: same tools, same Z.
    memory, stat = table["memory"], table["stat"]
    if [(m["tool"], round(m["z"], 6)) for m in memory] != [(s["tool"], round(s["z"], 6)) for s in stat]:
        fail("%s: the tool data read (%s) is not stat.tool_table's (%s)" % (what, memory, stat))
    print("%s, LinuxCNC's memory: %s" % (what, " ".join(
        "[%d] T%d P%d Z%g" % (m["idx"], m["tool"], m["pocket"], m["z"]) for m in memory)))
    for m in memory[1:]:
        if m["tool"] in lines and (m["pocket"], round(m["z"], 6)) != (lines[m["tool"]][0],
                                                                      round(lines[m["tool"]][1], 6)):
            fail("%s: LinuxCNC's memory has T%d in P%d Z%s, the file P%s Z%s" % (
                what, m["tool"], m["pocket"], m["z"], lines[m["tool"]][0], lines[m["tool"]][1]))
    if memory[0]["tool"] != 3 or memory[0]["pocket"] != POCKETS[3]:
        fail("%s: LinuxCNC's spindle entry is %s, not T3 with its pocket %d" % (what, memory[0], POCKETS[3]))
    ok("%s: LinuxCNC's memory agrees with the file (%.2f s after the file's last change, the file"
       " standing 1 s), the spindle's T3 keeps P%d" % (what, table["agreed_after"], POCKETS[3]))
    return lines


def main():
    results = load_results(sys.argv[1], "rack_table_p")
    r = scenario(results, "rack_table_p")
    tables = r.get("tool_tables", {})
    for name in ("after_changes", "after_g10", "after_edit"):
        if name not in tables:
            fail("no tool table recorded %s: %s" % (name, results.get("error")))
    first = check_table(tables["after_changes"], "after the changes and the load", {})
    t20 = first[20][1]
    if t20 == 0.0:
        fail("T20's length measured at its load is not in the table (Z0)")
    ok("T20's length measured at its load (%g) survived the rewrites" % t20)
    check_table(tables["after_g10"], "after G10 L1 P5 Z47.5", {5: 47.5, 20: t20})
    if not re.search(r"(?m)^T5\s+P2\b", r.get("edited_table", "")):
        fail("the edit did not write T5 P2: %s" % r.get("edited_table"))
    said = [m for m in r["messages"] if "the table said P2" in m]
    if not said or "tool 5 is in pocket 5" not in said[0] or "unload it, then load it" not in " ".join(
            r["messages"]):
        fail("the operator was not told where T5 is: %s" % r["messages"])
    ok("the operator was told: %s" % said[0])
    check_table(tables["after_edit"], "after T5's P edited to 2 and read by LinuxCNC", {5: 47.5, 20: t20})


if __name__ == "__main__":
    main()
