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

# Drift: each class of change (from, to) a program makes with no fault injected,
# no operator's hand in it (manual tools) and not its first change (which
# starts from wherever the last program or flow left the spindle).
# A fetch into an empty spindle starts where the T0 before it left its tool:
# its class names that tool too (T5>T0>T4).
classes = collections.OrderedDict()
for before, e in zip([None] + changes, changes):
    if e["clean"] and e["seconds"] and not e.get("first") and not e.get("manual"):
        came = "T%d>" % before["frm"] if e["frm"] == 0 and before and before["to"] == 0 else ""
        classes.setdefault("%sT%d>T%d" % (came, e["frm"], e["to"]), []).append(e["seconds"])


def median(values):
    return sorted(values)[len(values) // 2]


drift = {name: {"n": len(s), "first": s[0], "slowest": max(s), "ratio": max(s) / s[0],
                "early": median(s[:3]), "late": median(s[-3:]),
                "late_over_early": median(s[-3:]) / median(s[:3])}
         for name, s in classes.items() if len(s) >= 2}
worst = max(drift.items(), key=lambda kv: kv[1]["ratio"]) if drift else None
trend = max(drift.items(), key=lambda kv: kv[1]["late_over_early"]) if drift else None

# The slowest change the machine makes on its own: no fault injected, no
# operator's hand in it.
timed = [e for e in changes if e["clean"] and e["seconds"] and not e.get("manual")]
slowest = max(timed, key=lambda e: e["seconds"]) if timed else None

cpu = [e for e in events if e["kind"] == "program cpu"]
cpu_changes = sum(e["changes"] for e in cpu)
cpu_per_change = 1000.0 * sum(e["cpu_s"] for e in cpu) / cpu_changes if cpu_changes else None
recoveries = [e for e in events if e["kind"] == "recovery"]
unprovoked = [e["where"] for e in recoveries if not e.get("provoked")]
not_reached = count("fault not reached", "fault")
plan = json.load(open(os.path.join(work, "soak_plan.json")))
missing_kinds = []
if plan.get("fault_cycle"):
    kinds = next((e["kinds"] for e in events if e["kind"] == "fault kinds"),
                 ["flicker", "late", "never", "estop", "abort", "kill", "restart_linuxcnc"])
    missing_kinds = [k for k in kinds if not faults.get(k)]
    if any(e["kind"] == "fault" and e["fault"] == "flicker" and not e.get("fired") for e in events):
        missing_kinds.append("flicker that fired")

usage = [e for e in events if e["kind"] == "usage" and e.get("pid")]
log_bytes = usage[-1]["log_bytes"] + usage[-1]["log_old_bytes"] if usage else 0
written = 0  # bytes the log grew by, rotations counted (it moves to .1 past 1 MiB)
for before, after in zip(usage, usage[1:]):
    grew = after["log_bytes"] - before["log_bytes"]
    written += grew if grew >= 0 else after["log_bytes"]
messages = []
for e in events:
    if e["kind"] == "messages":
        messages += e["messages"]
said = collections.Counter(m.split(": ", 1)[-1][:70] for m in messages if not m.startswith("..."))
# What the processes printed: the component's internal errors, a crash, a Python traceback.
starts_log = os.path.join(work, "linuxcnc_starts.log")
printed = open(starts_log, errors="replace").read() if os.path.exists(starts_log) else ""
crashes = [line for line in printed.splitlines()
           if any(w in line for w in ("internal error", "Segmentation fault", "Traceback",
                                      "exited without becoming ready"))]

report = {
    "changes": len(changes), "seconds": events[-1]["t"] - t0,
    "starts": len({e["start"] for e in events}),
    "programs": len([e for e in events if e["kind"] == "program"]),
    "operator_flows": dict(count("operator", "flow")),
    "faults": dict(faults), "faults_not_reached": dict(not_reached),
    "recoveries": len(recoveries), "recoveries_unprovoked": unprovoked,
    "uncertain_seen": len([e for e in events if e["kind"] == "uncertain"]),
    "checks": len([e for e in events if e["kind"] in ("agree", "mismatch") or e.get("checked")]),
    "mismatches": len(mismatches), "mismatch_list": mismatches[:5],
    "errors": [e["what"] for e in errors], "processes": lifetimes,
    "cpu_ms_per_change_in_programs": cpu_per_change,
    "drift": drift, "drift_worst": {"class": worst[0], **worst[1]} if worst else None,
    "slowest_change": {"seconds": slowest["seconds"], "frm": slowest["frm"], "to": slowest["to"],
                       "change": slowest["changes"]} if slowest else None,
    "classes_over_5_percent": sorted(n for n, v in drift.items() if v["ratio"] > 1.05),
    "classes_trending_over_5_percent": sorted(n for n, v in drift.items()
                                              if v["late_over_early"] > 1.05),
    "log_bytes_at_end": log_bytes,
    "log_bytes_per_1000_changes": 1000.0 * written / len(changes) if changes else None,
    "messages": dict(said.most_common(12)),
    "crashes_printed": crashes[:10],
}
json.dump(report, open(os.path.join(work, "soak_report.json"), "w"), indent=1)

print("soak: %d changes in %.0f s over %d LinuxCNC starts, %d programs, operator flows %s" % (
    report["changes"], report["seconds"], report["starts"], report["programs"],
    report["operator_flows"]))
print("faults injected: %s (planned, not reached before the program ended: %s); recoveries "
      "(confirm and clear): %d, of them without an injected fault: %d %s" % (
          report["faults"], report["faults_not_reached"], report["recoveries"], len(unprovoked),
          unprovoked[:4]))
print("checks against the rack: %d (after every change and every recovery), mismatches: %d" % (
    report["checks"], report["mismatches"]))
if slowest:
    print("slowest change without a fault or a hand in it: %.2f s, T%d to T%d (change %d of %d)" % (
        slowest["seconds"], slowest["frm"], slowest["to"], slowest["changes"], len(changes)))
if cpu_per_change is not None:
    print("component CPU: %.1f ms a change inside programs" % cpu_per_change)
for p in lifetimes:
    print("component pid %d: %d changes; RSS %d -> %d KiB, open files %d -> %d, CPU %s ms a change" % (
        p["pid"], p["changes"], p["rss_kib"][0], p["rss_kib"][1], p["fds"][0], p["fds"][1],
        "%.1f" % p["cpu_ms_per_change"] if p["cpu_ms_per_change"] is not None else "-"))
if worst:
    print("drift over %d classes: worst slowest-against-first %s, first %.3f s, slowest %.3f s of "
          "%d (x%.3f); classes over 5%%: %d; worst trend %s, median of the last three against "
          "the first three x%.3f" % (
              len(drift), worst[0], worst[1]["first"], worst[1]["slowest"], worst[1]["n"],
              worst[1]["ratio"], len(report["classes_over_5_percent"]), trend[0],
              trend[1]["late_over_early"]))
print("state log: %d bytes at the end, written %s per 1000 changes (it moves to .1 past 1 MiB)" % (
    log_bytes, "%.0f" % report["log_bytes_per_1000_changes"] if changes else "-"))
for m in mismatches[:5]:
    print("MISMATCH %s: %s" % (m["where"], m["what"]))
for e in errors:
    print("ERROR: %s" % e["what"])
print("printed by LinuxCNC and the component: %d lines of internal errors, crashes or "
      "tracebacks %s" % (len(crashes), crashes[:3]))
print("messages seen most: %s" % list(said.most_common(6)))


# ---------------------------------------------------------------- the picture
W, H, L, R, T, B = 960, 420, 70, 70, 30, 50
span = max(report["seconds"], 1.0)
x = lambda t: L + (t - t0) / span * (W - L - R)  # noqa: E731
top = max(len(changes), 1)
rss = [(e["t"], e["rss_kib"]) for e in usage]
rss_low = min([r for _, r in rss] + [0]) if rss else 0
rss_top = max([r for _, r in rss] + [rss_low + 1]) + 256  # KiB: a leak of a quarter MiB shows
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
    points = " ".join("%.1f,%.1f" % (x(t), H - B - (r - rss_low) / (rss_top - rss_low) * (H - B - T))
                      for t, r in rss)
    out.append('<polyline points="%s" fill="none" stroke="#009e73" stroke-width="2" '
               'stroke-dasharray="5,3"/>' % points)
out.append('<text x="%d" y="%d" fill="#0072b2">changes (0..%d)</text>' % (L + 5, T + 28, top))
out.append('<text x="%d" y="%d" fill="#009e73">component RSS (%d..%d KiB), dashed</text>' % (
    L + 5, T + 44, rss_low, rss_top))
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

bad = ["fault kinds never injected: %s" % missing_kinds] if missing_kinds else []
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
