"""LinuxCNC's tool table as a GUI's tool page sees it (issue 34): the file
iocontrol writes and the table in its memory, with each tool's pocket (P).

LinuxCNC 2.9's Python module has no pocket in stat.tool_table, so the memory
is read where that module reads it: the tool data iocontrol maps from
$HOME/.tool.mmap (src/emc/tooldata/tooldata_mmap.cc): a header (rtapi_mutex_t,
last_index, is_random_toolchanger), then CANON_TOOL_TABLE entries (toolno,
pocketno, the EmcPose's nine offsets, diameter, frontangle, backangle,
orientation). Each entry's tool and Z are recorded beside stat.tool_table's,
so the checker proves the layout read is the one LinuxCNC has."""
import os
import re
import struct
import time


HEADER = struct.Struct("=QIi")
ENTRY = struct.Struct("=ii9d3di4x")


def memory():
    """Every entry of iocontrol's table, index 0 (the spindle) first."""
    with open(os.path.join(os.environ["HOME"], ".tool.mmap"), "rb") as f:
        data = f.read()
    _, last, _ = HEADER.unpack_from(data, 0)
    entries = []
    for idx in range(last + 1):
        fields = ENTRY.unpack_from(data, HEADER.size + idx * ENTRY.size)
        entries.append({"idx": idx, "tool": fields[0], "pocket": fields[1], "z": fields[4]})
    return entries


def file_lines(text):
    """tool -> (P, Z, comment) of each line of a tool table file."""
    lines = {}
    for line in text.splitlines():
        fields, _, comment = line.partition(";")
        words = {w[0].upper(): w[1:] for w in fields.split()}
        if "T" in words:
            lines[int(words["T"])] = (int(words["P"]) if "P" in words else None,
                                      float(words.get("Z", 0)), comment.strip())
    return lines


def agrees(entries, lines):
    """Each tool of the memory has the file's P and Z."""
    return all((m["pocket"], round(m["z"], 6)) == (lines[m["tool"]][0], round(lines[m["tool"]][1], 6))
               for m in entries[1:] if m["tool"] in lines)


def record(stat, path, settled):
    """The file and the memory once `settled` (changer idle, task free) held
    and the file stood unchanged for a second (the component writes it then),
    and the memory agrees with it or 5 s more passed; `agreed_after`: the
    seconds from the file's last change until it did (None: it did not)."""
    deadline = time.monotonic() + 20
    stamp, since = None, time.monotonic()
    while time.monotonic() < deadline:
        stat.poll()
        now = os.stat(path).st_mtime_ns
        if now != stamp or not settled():
            stamp, since = now, time.monotonic()
        elif time.monotonic() - since > 1.0:
            break
        time.sleep(0.05)
    lines = file_lines(open(path).read())
    agreed_after = None
    while time.monotonic() - since < 6.0:
        if agrees(memory(), lines):
            agreed_after = time.monotonic() - since
            break
        time.sleep(0.05)
    stat.poll()
    return {"file": open(path).read(), "memory": memory(), "agreed_after": agreed_after,
            "stat": [{"tool": t.id, "z": t.zoffset} for t in stat.tool_table]}


def edit_p(command, path, tool, pocket):
    """An operator edits tool's P on a GUI's tool page: the editor saves the
    file in place and has LinuxCNC read it again (AXIS's tooledit, gmoccapy)."""
    text = open(path).read()
    edited = re.sub(r"(?m)^(T%d\s+)P-?\d+" % tool, r"\g<1>P%d" % pocket, text)
    with open(path, "w") as f:
        f.write(edited)
    command.load_tool_table()
    command.wait_complete()
    return edited
