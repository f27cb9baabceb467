#!/usr/bin/env python3
"""Draws one tool change as LinuxCNC reported it: machine X, Y and Z over
time, one panel each, and below them when the chuck was open, as an SVG.
   timeline_svg.py RESULTS.json OUT.svg [N]
RESULTS.json: what tests/integration/harness/driver.py wrote (the demo's run, or one
scenario's file of RESULTS.json.d). N: the change to draw, counted from 1
among the spans the changer was busy; default the first that returns one
tool and fetches another."""
import json
import sys
from xml.sax.saxutils import escape

from demo_report import intervals

WIDTH, LEFT, RIGHT = 900.0, 70.0, 20.0
PANEL, GAP, TOP = 110.0, 28.0, 50.0
CHUCK = 24.0
COLOURS = {"X": "#c33", "Y": "#2a2", "Z": "#36c"}


def scenario_of(results):
    return results["scenarios"][0] if "scenarios" in results else results


def pick(samples, wanted):
    """The busy span to draw: the wanted one, or the first between two tools."""
    spans = intervals(samples, "fixed_atc_probe.busy")
    if not spans:
        sys.exit("timeline_svg.py: the changer was never busy in these results")
    if wanted:
        if not 1 <= wanted <= len(spans):
            sys.exit("timeline_svg.py: change %d asked for, the results have %d" % (wanted, len(spans)))
        return wanted, spans[wanted - 1]
    for number, (a, b) in enumerate(spans, 1):
        after = samples[b - 1]["fixed_atc_probe.tool-in-spindle"]  # None: the pin was gone
        if samples[a]["tool_in_spindle"] and after not in (None, 0, samples[a]["tool_in_spindle"]):
            return number, (a, b)
    return 1, spans[0]


def polyline(points, colour, width=1.8):
    return '<polyline fill="none" stroke="%s" stroke-width="%s" points="%s"/>\n' % (
        colour, width, " ".join("%.1f,%.1f" % p for p in points))


def main():
    results = json.load(open(sys.argv[1]))
    if "error" in results and results["error"]:
        sys.exit("timeline_svg.py: the run failed: %s" % results["error"])
    samples = scenario_of(results)["samples"]
    number, (a, b) = pick(samples, int(sys.argv[3]) if len(sys.argv) > 3 else 0)
    span = samples[a:b + 1]
    t0, t1 = span[0]["t"], span[-1]["t"]
    before, after = span[0]["tool_in_spindle"], span[-1]["fixed_atc_probe.tool-in-spindle"]
    plot_width = WIDTH - LEFT - RIGHT

    def x_of(t):
        return LEFT + (t - t0) / max(t1 - t0, 1e-9) * plot_width

    height = TOP + 3 * (PANEL + GAP) + CHUCK + 50
    out = ['<?xml version="1.0" encoding="UTF-8"?>\n',
           '<svg xmlns="http://www.w3.org/2000/svg" width="%.0f" height="%.0f" viewBox="0 0 %.0f %.0f" '
           'font-family="sans-serif" font-size="12">\n' % (WIDTH, height, WIDTH, height),
           '<rect width="100%" height="100%" fill="white"/>\n',
           '<text x="%.0f" y="24" font-size="15">%s</text>\n' % (LEFT, escape(
               "Change %d: T%s to T%s, %.2f s: the machine's position and the chuck over time"
               % (number, before, after, t1 - t0)))]
    for k, axis in enumerate("XYZ"):
        top = TOP + k * (PANEL + GAP)
        values = [s["pos"][k] for s in span]
        low, high = min(values), max(values)
        if high - low < 1e-6:
            low, high = low - 1, high + 1

        def y_of(v):
            return top + PANEL - (v - low) / (high - low) * PANEL

        out.append('<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="#f6f6f6" stroke="#ccc"/>\n'
                   % (LEFT, top, plot_width, PANEL))
        out.append('<text x="10" y="%.1f" fill="%s" font-weight="bold">%s</text>\n'
                   % (top + PANEL / 2, COLOURS[axis], axis))
        out.append('<text x="%.1f" y="%.1f" text-anchor="end" fill="#555">%.1f</text>\n'
                   % (LEFT - 6, top + 10, high))
        out.append('<text x="%.1f" y="%.1f" text-anchor="end" fill="#555">%.1f</text>\n'
                   % (LEFT - 6, top + PANEL, low))
        out.append(polyline([(x_of(s["t"]), y_of(s["pos"][k])) for s in span], COLOURS[axis]))
    chuck_top = TOP + 3 * (PANEL + GAP) - GAP / 2
    out.append('<text x="10" y="%.1f" font-weight="bold">chuck</text>\n' % (chuck_top + CHUCK * 0.7))
    for first, last in intervals(span, "fixed_atc_probe.chuck"):
        out.append('<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="#d70"/>\n'
                   % (x_of(span[first]["t"]), chuck_top,
                      max(x_of(span[last]["t"]) - x_of(span[first]["t"]), 1.0), CHUCK))
    out.append('<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="none" stroke="#ccc"/>\n'
               % (LEFT, chuck_top, plot_width, CHUCK))
    axis_y = chuck_top + CHUCK + 18
    whole = int(t1 - t0)
    step = 1 if whole <= 20 else 5
    for second in range(0, whole + 1, step):
        out.append('<text x="%.1f" y="%.1f" text-anchor="middle" fill="#555">%d s</text>\n'
                   % (x_of(t0 + second), axis_y, second))
    out.append('<text x="%.0f" y="%.1f" fill="#555">machine position (LinuxCNC\'s actual position) '
               'in the config\'s units; orange: the chuck open</text>\n' % (LEFT, axis_y + 20))
    out.append("</svg>\n")
    with open(sys.argv[2], "w") as f:
        f.write("".join(out))
    print("wrote %s: change %d, T%s to T%s, %.2f s" % (sys.argv[2], number, before, after, t1 - t0))


if __name__ == "__main__":
    main()
