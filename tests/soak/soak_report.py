#!/usr/bin/env python3
"""The soak's report from WORKDIR/soak_events.jsonl (soak.py): the figures
docs/guarantees.md gives, as soak_report.json and printed, and soak.svg, one
picture of the run: changes over time, the component's memory, each fault.

    soak_report.py WORKDIR [MIN_CHANGES]

Exits 1 when the soak made fewer than MIN_CHANGES changes (default: none
asked), saw a mismatch, ended on an error, or its memory or files grew."""
import collections
import json
import os
import sys

work = sys.argv[1]
wanted = int(sys.argv[2]) if len(sys.argv) > 2 else 0
events = [json.loads(line) for line in open(os.path.join(work, "soak_events.jsonl"))]
t0 = events[0]["t"]


def count(kind, key=None):
    return collections.Counter(e.get(key) if key else kind for e in events if e["kind"] == kind)


changes = [e for e in events if e["kind"] == "change"]
faults = count("fault", "fault")
mismatches = [e for e in events if e["kind"] == "mismatch"]
errors = [e for e in events if e["kind"] == "error"]

# Each component process: its memory and files at its 50th change and at its last.
processes = collections.OrderedDict()
for e in events:
    if e["kind"] == "usage" and e.get("pid"):
        processes.setdefault(e["pid"], []).append(e)
lifetimes = []
for pid, seen in processes.items():
    first = next((u for u in seen if u["changes"] - seen[0]["changes"] >= 50), seen[0])
    last = seen[-1]
    served = last["changes"] - first["changes"]
    lifetimes.append({"pid": pid, "changes": last["changes"] - seen[0]["changes"],
                      "rss_kib": [first["rss_kib"], last["rss_kib"]], "fds": [first["fds"], last["fds"]],
                      "cpu_ms_per_change": 1000.0 * (last["cpu_s"] - first["cpu_s"]) / served
                      if served > 0 else None})
longest = max(lifetimes, key=lambda p: p["changes"]) if lifetimes else None

# Drift: each class of change (from, to), undisturbed by a fault, its slowest against its first.
classes = collections.OrderedDict()
for e in changes:
    if e["clean"] and e["seconds"]:
        classes.setdefault("T%d>T%d" % (e["frm"], e["to"]), []).append(e["seconds"])
drift = {name: {"first": s[0], "slowest": max(s), "n": len(s), "ratio": max(s) / s[0]}
         for name, s in classes.items() if len(s) >= 2}
worst = max(drift.items(), key=lambda kv: kv[1]["ratio"]) if drift else None

usage = [e for e in events if e["kind"] == "usage" and e.get("pid")]
log_bytes = usage[-1]["log_bytes"] + usage[-1]["log_old_bytes"] if usage else 0
messages = []
for e in events:
    if e["kind"] == "messages":
        messages += e["messages"]
said = collections.Counter(m.split(":")[1].strip()[:60] if ":" in m else m[:60] for m in messages)

report = {
    "changes": len(changes), "seconds": events[-1]["t"] - t0,
    "starts": len({e["start"] for e in events}),
    "programs": len([e for e in events if e["kind"] == "program"]),
    "operator_flows": dict(count("operator", "flow")),
    "faults": dict(faults), "recoveries": len([e for e in events if e["kind"] == "recovery"]),
    "uncertain_seen": len([e for e in events if e["kind"] == "uncertain"]),
    "checks": len([e for e in events if e["kind"] in ("agree", "mismatch")]),
    "mismatches": len(mismatches), "mismatch_list": mismatches[:5],
    "errors": [e["what"] for e in errors], "processes": lifetimes,
    "drift_worst": {"class": worst[0], **worst[1]} if worst else None,
    "classes_over_5_percent": sorted(n for n, v in drift.items() if v["ratio"] > 1.05),
    "log_bytes_at_end": log_bytes,
    "log_bytes_per_1000_changes": 1000.0 * log_bytes / len(changes) if changes else None,
    "messages": dict(said.most_common(12)),
}
json.dump(report, open(os.path.join(work, "soak_report.json"), "w"), indent=1)

print("soak: %d changes in %.0f s over %d LinuxCNC starts, %d programs, operator flows %s" % (
    report["changes"], report["seconds"], report["starts"], report["programs"],
    report["operator_flows"]))
print("faults injected: %s; recoveries (confirm and clear): %d; checks against the rack: %d, "
      "mismatches: %d" % (report["faults"], report["recoveries"], report["checks"],
                          report["mismatches"]))
for p in lifetimes:
    print("component pid %d: %d changes; RSS %d -> %d KiB, open files %d -> %d, CPU %s ms a change" % (
        p["pid"], p["changes"], p["rss_kib"][0], p["rss_kib"][1], p["fds"][0], p["fds"][1],
        "%.1f" % p["cpu_ms_per_change"] if p["cpu_ms_per_change"] is not None else "-"))
if worst:
    print("drift: worst class %s, first %.2f s, slowest %.2f s of %d (x%.3f); classes over 5%%: %s" % (
        worst[0], worst[1]["first"], worst[1]["slowest"], worst[1]["n"], worst[1]["ratio"],
        report["classes_over_5_percent"]))
print("state log: %d bytes at the end (%s per 1000 changes; it moves to .1 past 1 MiB)" % (
    log_bytes, "%.0f" % report["log_bytes_per_1000_changes"] if changes else "-"))
for m in mismatches[:5]:
    print("MISMATCH %s: %s" % (m["where"], m["what"]))
for e in errors:
    print("ERROR: %s" % e["what"])


# ---------------------------------------------------------------- the picture
W, H, L, R, T, B = 960, 420, 70, 70, 30, 50
span = max(report["seconds"], 1.0)
x = lambda t: L + (t - t0) / span * (W - L - R)  # noqa: E731
top = max(len(changes), 1)
rss = [(e["t"], e["rss_kib"]) for e in usage]
rss_top = max([r for _, r in rss] + [1]) * 1.1
colors = {"flicker": "#999", "late": "#e69f00", "never": "#d55e00", "estop": "#cc0000",
          "abort": "#0072b2", "kill": "#7b3294", "restart_linuxcnc": "#000"}
out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" '
       'font-size="12">' % (W, H), '<rect width="100%" height="100%" fill="white"/>',
       '<text x="%d" y="18" font-size="14">Soak: %d tool changes, %d faults, %d mismatches</text>' % (
           L, len(changes), sum(faults.values()), len(mismatches))]
out.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="black"/>' % (L, H - B, W - R, H - B))
out.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="black"/>' % (L, T, L, H - B))
for e in events:
    if e["kind"] == "fault":
        c = colors.get(e["fault"], "#555")
        out.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="%s" stroke-width="1" '
                   'opacity="0.7"><title>%s at change %d</title></line>' % (
                       x(e["t"]), T, x(e["t"]), H - B, c, e["fault"], e["changes"]))
    if e["kind"] == "mismatch":
        out.append('<text x="%.1f" y="%d" fill="red" font-size="16">x</text>' % (x(e["t"]), T + 12))
points = " ".join("%.1f,%.1f" % (x(e["t"]), H - B - (i + 1) / top * (H - B - T))
                  for i, e in enumerate(changes))
out.append('<polyline points="%s" fill="none" stroke="#0072b2" stroke-width="2"/>' % points)
if rss:
    points = " ".join("%.1f,%.1f" % (x(t), H - B - r / rss_top * (H - B - T)) for t, r in rss)
    out.append('<polyline points="%s" fill="none" stroke="#009e73" stroke-width="2" '
               'stroke-dasharray="5,3"/>' % points)
out.append('<text x="%d" y="%d" fill="#0072b2">changes (0..%d)</text>' % (L + 5, T + 28, top))
out.append('<text x="%d" y="%d" fill="#009e73">component RSS (0..%d KiB), dashed</text>' % (
    L + 5, T + 44, rss_top))
out.append('<text x="%d" y="%d" text-anchor="middle">time, s (0..%.0f)</text>' % (
    (L + W - R) / 2, H - 15, span))
legend = W - R - 130
for i, (kind, c) in enumerate(colors.items()):
    out.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="%s" stroke-width="3"/>'
               '<text x="%d" y="%d">%s (%d)</text>' % (legend, T + 12 + 16 * i, legend + 18,
                                                      T + 12 + 16 * i, c, legend + 24,
                                                      T + 16 + 16 * i, kind, faults.get(kind, 0)))
out.append("</svg>")
with open(os.path.join(work, "soak.svg"), "w") as f:
    f.write("\n".join(out) + "\n")

bad = []
if len(changes) < wanted:
    bad.append("%d changes, fewer than %d" % (len(changes), wanted))
if mismatches:
    bad.append("%d mismatches" % len(mismatches))
if errors:
    bad.append("ended on an error")
if longest and longest["changes"] >= 100:
    if longest["rss_kib"][1] - longest["rss_kib"][0] > 1024 or longest["fds"][1] != longest["fds"][0]:
        bad.append("the component grew: %s" % longest)
for b in bad:
    print("FAIL: " + b)
sys.exit(1 if bad else 0)
