#!/usr/bin/python3
"""Your own machine rehearsed in simulation (issue 44): a simulated copy of the
machine your INI describes (its axes, soft limits, velocities, accelerations
and units), with your config.json and tool table, the simulated rack of the
sensors run wired in place of your hardware, and the soak's random tool
changes with faults injected on it (tests/soak); then what held, what
faulted, the slowest change and the soak's picture.

    fixed_atc_probe-rehearse --ini YOUR.ini [--config config.json]
        [--tool-table FILE] [--changes N] [--seed S] [--workdir DIR]

The INI is read with LinuxCNC's own reader (python `linuxcnc.ini`); config.json
must pass `fixed_atc_probe --check --ini` first. Bad input: one line naming
what and where, and nothing starts. Exit 0 when every check held."""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

NAME = "fixed_atc_probe-rehearse"
HERE = os.path.dirname(os.path.abspath(__file__))
# The project's files: this checkout, or the installed package's share folder.
ROOT = os.path.abspath(os.path.join(HERE, ".."))
if not os.path.isdir(os.path.join(ROOT, "tests", "soak")):
    ROOT = os.path.join(ROOT, "share", "fixed_atc_probe")
# The INI's keys of the machine the copy keeps; everything else is the simulated mill's.
TRAJ_KEYS = ("COORDINATES", "LINEAR_UNITS", "ANGULAR_UNITS", "DEFAULT_LINEAR_VELOCITY",
             "MAX_LINEAR_VELOCITY", "DEFAULT_LINEAR_ACCELERATION", "MAX_LINEAR_ACCELERATION",
             "DEFAULT_ANGULAR_VELOCITY", "MAX_ANGULAR_VELOCITY", "DEFAULT_ANGULAR_ACCELERATION",
             "MAX_ANGULAR_ACCELERATION")
AXIS_KEYS = ("MAX_VELOCITY", "MAX_ACCELERATION", "MIN_LIMIT", "MAX_LIMIT")
JOINT_KEYS = ("TYPE", "HOME", "MAX_VELOCITY", "MAX_ACCELERATION", "MIN_LIMIT", "MAX_LIMIT",
              "FERROR", "MIN_FERROR")
# [FIXED_ATC_PROBE] keys that change what the changer does; its pin numbers
# and MACHINE_ON_SIGNAL name the user's wiring, which the copy replaces.
BEHAVIOUR_KEYS = ("STEP_TIMEOUT", "RETURN_TO_XY")
SECTION_KEYS = ("CONFIG", "STATE", "STEP_READY_IN", "STEP_REQUEST_OUT", "PROBE_Z_OUT",
                "PROBE_RESULT_OUT", "EXECUTOR_CALL_OUT", "STEP_TIMEOUT", "RETURN_TO_XY",
                "MACHINE_ON_SIGNAL")
# Every sensor wired to the simulated rack (the soak's faults need them), each
# tool measured at its first change (the soak holds every length against the
# simulated setter's): the rest of config.json is the user's own.
CONFIG_SET = {"sensors": {"tool_present": True, "drawbar_open": True, "drawbar_closed": True,
                          "air_pressure": True, "pocket_occupancy": True, "zero_speed": True},
              "probe_after_change": "new"}
MM = {"mm": 1.0, "inch": 25.4, "in": 25.4}


class Parser(argparse.ArgumentParser):
    def error(self, message):
        """A usage mistake: one line, exit 2, as fixed_atc_probe's own."""
        self.exit(2, "%s: %s\n" % (NAME, message))


class Refused(Exception):
    """One line: what is wrong and where; nothing starts."""


def text_of(path):
    with open(path) as f:
        return f.read()


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def units_of(word, where):
    unit = (word or "").strip().lower()
    if unit not in MM:
        raise Refused("%s: expected mm or inch, got %r" % (where, word))
    return "inch" if unit == "in" else unit


def read_ini(path):
    """LinuxCNC's reader of the INI, after the checks it cannot make."""
    if not os.path.isfile(path):
        raise Refused("%s: no such file" % path)
    with open(path, errors="replace") as f:
        lines = f.read().splitlines()
    for number, line in enumerate(lines, 1):
        if line.startswith("#INCLUDE"):
            raise Refused("%s line %d: #INCLUDE: give the INI LinuxCNC expanded (%s.expanded, "
                          "written when it starts)" % (path, number, os.path.basename(path)))
    import linuxcnc  # LinuxCNC's own IniFile reader (/usr/bin/python3)
    ini = linuxcnc.ini(path)
    if not any(ini.find("FIXED_ATC_PROBE", key) for key in SECTION_KEYS):
        raise Refused("%s: no [FIXED_ATC_PROBE] section: add setup step 4's lines "
                      "(docs/setup.md) first" % path)
    return ini


def need(ini, section, key, path):
    value = ini.find(section, key)
    if value is None:
        raise Refused("%s: [%s]%s missing" % (path, section, key))
    return value


def joints_of(ini, path):
    """Where the touch-off sensor and the rack read X, Y and Z: the joint of each,
    as trivkins maps them (its coordinates= or [TRAJ]COORDINATES, the first
    joint of a letter)."""
    kins = need(ini, "KINS", "KINEMATICS", path).split()
    if not kins or kins[0] != "trivkins":
        raise Refused("%s: [KINS]KINEMATICS %s: the rehearsal simulates trivkins machines only"
                      % (path, " ".join(kins)))
    letters = next((w.split("=", 1)[1] for w in kins[1:] if w.startswith("coordinates=")),
                   need(ini, "TRAJ", "COORDINATES", path))
    letters = letters.replace(" ", "").upper()
    joints = {}
    for axis in "XYZ":
        if axis not in letters:
            raise Refused("%s: [KINS]/[TRAJ] coordinates %s: no %s axis" % (path, letters, axis))
        joints[axis] = letters.index(axis)
    return joints


def machine_sections(ini, path):
    """[TRAJ], [KINS], [AXIS_*] and [JOINT_*] of the user's machine as the copy has
    them: the limits, velocities and accelerations as they are, each joint
    homed where it stands (HOME_SEARCH_VEL 0, one HOME_SEQUENCE), as the
    simulated mill's."""
    out = ["[TRAJ]"] + ["%s = %s" % (k, ini.find("TRAJ", k)) for k in TRAJ_KEYS
                        if ini.find("TRAJ", k) is not None]
    joints = int(need(ini, "KINS", "JOINTS", path))
    out += ["", "[KINS]", "KINEMATICS = %s" % need(ini, "KINS", "KINEMATICS", path),
            "JOINTS = %d" % joints]
    letters = need(ini, "TRAJ", "COORDINATES", path).replace(" ", "").upper()
    for axis in dict.fromkeys(letters):
        out += ["", "[AXIS_%s]" % axis] + ["%s = %s" % (k, ini.find("AXIS_" + axis, k))
                                           for k in AXIS_KEYS if ini.find("AXIS_" + axis, k) is not None]
    for joint in range(joints):
        section = "JOINT_%d" % joint
        for key in ("MIN_LIMIT", "MAX_LIMIT", "MAX_VELOCITY", "MAX_ACCELERATION"):
            need(ini, section, key, path)
        out += ["", "[%s]" % section] + ["%s = %s" % (k, ini.find(section, k)) for k in JOINT_KEYS
                                         if ini.find(section, k) is not None]
        out += ["HOME_SEARCH_VEL = 0", "HOME_SEQUENCE = 0"]
    return "\n".join(out) + "\n"


def setter(config, config_path):
    """The simulated touch-off sensor under probe_limit's X and Y, tripping a
    quarter of the way from probe_limit.z up to loading.z (config/sim's -70
    between -90 and -10), and the length every tool measures there."""
    try:
        limit, loading = config["probe_limit"], config["loading"]
        offset = config["probe_length_compensation_offset"]
        z = limit["z"] + 0.25 * (loading["z"] - limit["z"])
    except (KeyError, TypeError) as e:
        raise Refused("%s: %s missing: the simulated setter sits under probe_limit" % (config_path, e))
    half = 5.0 / MM[config.get("units", "mm")]
    return {"SIM_SENSOR_Z": z, "SIM_SENSOR_XMIN": limit["x"] - half,
            "SIM_SENSOR_XMAX": limit["x"] + half, "SIM_SENSOR_YMIN": limit["y"] - half,
            "SIM_SENSOR_YMAX": limit["y"] + half}, z - offset


def length_tolerance(config):
    """How far a length measured on the simulated setter may be from its truth:
    the config's probe_check_tolerance, within which the changer itself takes
    a checked length as the stored one (a latch feed of its own moves the
    touch by a servo period's travel)."""
    return float(config.get("probe_check_tolerance", 0.1 / MM[config.get("units", "mm")]))


def sim_ini(ini, path, config, config_path, work):
    """The simulated mill's INI (config/sim) with the user's machine in it, its
    [FIXED_ATC_PROBE] behaviour keys and iocontrol's cycle, the simulated setter
    where theirs is and the simulated rack (tests/integration/sensors) wired;
    the touch-off sensor's HAL on the user's joints."""
    template = text_of(os.path.join(ROOT, "config", "sim", "fixed_atc_sim.ini"))
    head = template[:template.index("\n[TRAJ]") + 1]
    sensor, length = setter(config, config_path)
    for key, value in list(sensor.items()) + [(k, ini.find("FIXED_ATC_PROBE", k)) for k in BEHAVIOUR_KEYS]:
        if value is not None:
            head = re.sub(r"(?m)^%s = .*$" % key, "%s = %s" % (key, value), head)
    cycle = ini.find("EMCIO", "CYCLE_TIME")
    if cycle:
        head = re.sub(r"(?m)^CYCLE_TIME = 0.010$", "CYCLE_TIME = %s" % cycle, head)
    rack = os.path.join(ROOT, "tests", "integration", "sensors")
    head = head.replace("RETURN_TO_XY = ", "RACK_SIM = %s/rack_sim.py\nRETURN_TO_XY = " % rack, 1)
    joints = joints_of(ini, path)
    touchoff = os.path.join(ROOT, "config", "sim", "touchoff_sensor.hal")
    if joints != {"X": 0, "Y": 1, "Z": 2}:
        text = text_of(touchoff)
        for axis, name in (("X", "x"), ("Y", "y"), ("Z", "z")):
            text = text.replace("net fatc-sim-%s joint.%d.pos-fb" % (name, "XYZ".index(axis)),
                                "net fatc-sim-%s joint.%d.pos-fb" % (name, joints[axis]))
        touchoff = os.path.join(work, "touchoff_sensor.hal")
        write(touchoff, text)
    head = head.replace("HALFILE = touchoff_sensor.hal", "HALFILE = %s\nHALFILE = %s\nHALFILE = %s" % (
        touchoff, os.path.join(work, "rack_sim.hal"), os.path.join(ROOT, "tests", "soak", "soak_rack.hal")))
    # config/sim's plate with bores for a touch probe is the sample rack's, not theirs.
    head = re.sub(r"(?m)^# The simulated rack a touch probe touches.*\nHALFILE = sim_rack.hal\n", "", head)
    return head + "\n" + machine_sections(ini, path), length


def rack_hal(config):
    """tests/integration/sensors/rack_sim.hal with a pocket sensor for each of the user's pockets."""
    lines = [line for line in text_of(os.path.join(ROOT, "tests", "integration", "sensors",
                                                   "rack_sim.hal")).splitlines()
             if "pocket-occupied-" not in line]
    lines += ["net fatc-sim-pocket-%s fatc-rack-sim.pocket-occupied-%s => "
              "fixed_atc_probe.pocket-occupied-%s" % (p, p, p) for p in sorted(config["pockets"], key=int)]
    return "\n".join(lines) + "\n"


def rack_of(config, config_path, tools, table):
    """The tool each pocket holds at the first start (`"tool"`, default the
    pocket's number), each one a tool of the table. A rack all empty (setup
    step 2's first start) gets the table's tools in order, so that the
    rehearsal changes tools; the pockets as the copy's config.json has them,
    and what was filled."""
    pockets = {p: dict(own) for p, own in config["pockets"].items()}
    held = {p: int(own.get("tool", p)) for p, own in pockets.items()}
    filled = []
    if not any(held.values()):
        for (p, own), tool in zip(sorted(pockets.items(), key=lambda kv: int(kv[0])), sorted(tools)):
            own["tool"] = held[p] = tool
            filled.append("pocket %s T%d" % (p, tool))
    for p, tool in sorted(held.items(), key=lambda kv: int(kv[0])):
        if tool and tool not in tools:
            raise Refused("%s: pocket %s holds tool %d at the first start, which %s does not list"
                          % (config_path, p, tool, table))
    return pockets, filled


def check(binary, ini_path, config_path, table):
    """`fixed_atc_probe --check`: the config against this machine's limits; its
    first problem, and the command that lists them all."""
    command = [binary, "--check", "--config", config_path, "--ini", ini_path, "--tool-table", table]
    run = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if run.returncode != 0:
        problems = [line for line in run.stderr.splitlines() if line.strip()]
        # The sequences' problems are on stdout, indented under their heading.
        lines = run.stdout.splitlines()
        heading = next((i for i, line in enumerate(lines) if line.startswith("checking every sequence")),
                       len(lines))
        for line in lines[heading + 1:]:
            if not line.startswith("  "):
                break
            problems.append(line.strip())
        problems = problems or ["exit %d" % run.returncode]
        raise Refused("%s does not fit %s: %s (the first problem `%s` names)" % (
            config_path, ini_path, problems[0], " ".join(command)))


def prepare(args):
    """Everything read, checked and written before LinuxCNC starts: the
    environment soak_run.py and run_sim.sh take, the soak's folder and the
    pockets an empty rack had filled."""
    ini_path = os.path.abspath(args.ini)
    ini = read_ini(ini_path)
    folder = os.path.dirname(ini_path)
    config_path = os.path.abspath(args.config or os.path.join(
        folder, need(ini, "FIXED_ATC_PROBE", "CONFIG", ini_path)))
    if not os.path.isfile(config_path):
        raise Refused("%s: no such file ([FIXED_ATC_PROBE]CONFIG of %s)" % (config_path, ini_path))
    table = os.path.abspath(args.tool_table or os.path.join(
        folder, need(ini, "EMCIO", "TOOL_TABLE", ini_path)))
    if not os.path.isfile(table):
        raise Refused("%s: no such file (the tool table)" % table)
    try:
        with open(config_path) as f:
            config = json.load(f)
    except ValueError as e:
        raise Refused("%s: not JSON: %s" % (config_path, e))
    machine = units_of(need(ini, "TRAJ", "LINEAR_UNITS", ini_path), ini_path + ": [TRAJ]LINEAR_UNITS")
    own = units_of(config.get("units", "mm"), config_path + ": units")
    if own != machine:
        raise Refused("%s: units %s, but %s [TRAJ]LINEAR_UNITS %s: the simulated rack reads both "
                      "in one unit" % (config_path, own, ini_path, machine))
    joints_of(ini, ini_path)
    sys.path.insert(0, os.path.join(ROOT, "tests", "integration", "harness"))
    import tool_table  # a tool table file's lines, as the soak reads them
    tools = [t for t in tool_table.file_lines(text_of(table)) if t > 0]
    pockets, filled = rack_of(config, config_path, tools, table)
    check(args.binary, ini_path, config_path, table)
    work = os.path.abspath(args.workdir)
    os.makedirs(work, exist_ok=True)
    soak = os.path.join(work, "soak")  # soak_run.py makes it afresh
    text, length = sim_ini(ini, ini_path, config, config_path, work)
    if length <= 0:
        raise Refused("%s: probe_length_compensation_offset %s is not below probe_limit.z: no "
                      "tool length to measure" % (config_path, config["probe_length_compensation_offset"]))
    write(os.path.join(work, "rehearsal.ini"), text)
    write(os.path.join(work, "rack_sim.hal"), rack_hal(config))
    env = dict(os.environ, FATC_BINARY=args.binary, FATC_SIM_INI=os.path.join(work, "rehearsal.ini"),
               FATC_CONFIG=config_path, FATC_TOOL_TABLE=table,
               FATC_CONFIG_SET=json.dumps(dict(CONFIG_SET, pockets=pockets)),
               FATC_SOAK_TRUE_LENGTH=repr(length),
               FATC_SOAK_LENGTH_TOLERANCE=repr(length_tolerance(config)))
    for key in ("FATC_INI_SED", "FATC_INI_EXTRA", "FATC_INI_FILTER", "FATC_SOAK_CYCLE"):
        env.pop(key, None)
    return env, soak, filled


def summary(soak, ini_path, wanted):
    """What held, what faulted, the slowest change: from the soak's report."""
    report = json.loads(text_of(os.path.join(soak, "soak_report.json")))
    faults = report["faults"]
    slow = report["slowest_change"]
    lines = [
        "rehearsal of %s: %d changes made of %d asked; the changer's belief held against the "
        "simulated rack %d times, %d mismatches" % (ini_path, report["changes"], wanted,
                                                    report["checks"] - report["mismatches"],
                                                    report["mismatches"]),
        "faulted: %s; %d recoveries (confirm and clear), %d without an injected fault" % (
            ", ".join("%s %d" % kv for kv in sorted(faults.items())) or "nothing",
            report["recoveries"], len(report["recoveries_unprovoked"])),
        "slowest change: " + ("%.2f s, T%d to T%d (change %d)" % (
            slow["seconds"], slow["frm"], slow["to"], slow["change"]) if slow else "none timed"),
        "picture: %s; events: %s" % (os.path.join(soak, "soak.svg"),
                                     os.path.join(soak, "soak_events.jsonl"))]
    return lines


def main(argv):
    parser = Parser(prog=NAME, description=__doc__.split("\n\n")[0])
    parser.add_argument("--ini", required=True, help="your machine's INI")
    parser.add_argument("--config", help="config.json (else the INI's [FIXED_ATC_PROBE]CONFIG)")
    parser.add_argument("--tool-table", help="LinuxCNC's tool table (else the INI's [EMCIO]TOOL_TABLE)")
    parser.add_argument("--changes", type=int, default=300, help="tool changes to make (300)")
    parser.add_argument("--seed", type=int, default=1, help="the random programs' seed (1)")
    parser.add_argument("--workdir", help="where the copy runs (a new folder under /tmp)")
    parser.add_argument("--binary", default=os.environ.get("FATC_BINARY") or shutil.which("fixed_atc_probe")
                        or os.path.join(ROOT, "build", "fixed_atc_probe"), help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.changes < 1:
        parser.error("--changes: expected 1 or more, got %d" % args.changes)
    made = not args.workdir
    if made:
        # Open to the user LinuxCNC runs as (as root: run_sim.sh's own).
        args.workdir = tempfile.mkdtemp(prefix="fatc-rehearsal-")
        os.chmod(args.workdir, 0o755)
    try:
        env, soak, filled = prepare(args)
    except Refused as e:
        if made:
            shutil.rmtree(args.workdir)
        print("%s: %s; nothing started" % (NAME, e), file=sys.stderr)
        return 2
    if filled:
        print("%s: the rack is empty at the first start; the rehearsal fills it: %s" % (
            NAME, ", ".join(filled)))
    here = os.path.join(ROOT, "tests", "soak")
    run = subprocess.run([sys.executable, os.path.join(here, "soak_run.py"), soak, str(args.changes),
                          str(args.seed)], env=env)
    if run.returncode != 0:
        print("%s: the soak stopped (exit %d); see %s" % (NAME, run.returncode, soak), file=sys.stderr)
        return 1
    report = subprocess.run([sys.executable, os.path.join(here, "soak_report.py"), soak,
                             str(args.changes)], env=env)
    print("\n".join(summary(soak, os.path.abspath(args.ini), args.changes)))
    return report.returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
