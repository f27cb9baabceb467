#!/usr/bin/python3
"""[DISPLAY]DISPLAY of the integration runs: brings the simulated machine up,
runs each scenario's G-code, samples what LinuxCNC reports (position, tool in
spindle, HAL pins) and writes it all to FATC_RESULTS as JSON. LinuxCNC shuts
down when this exits."""
import ctypes
import faulthandler
import json
import os
import re
import signal
import subprocess
import sys
import time

import hal
import linuxcnc
import tool_table

import operator_command

PINS = ["fixed_atc_probe.chuck", "fixed_atc_probe.waiting-for-operator", "fixed_atc_probe.last-length", "fixed_atc_probe.state", "fixed_atc_probe.fault",
        "fixed_atc_probe.busy", "fixed_atc_probe.tool-in-spindle", "fixed_atc_probe.step-ready",
        "fixed_atc_probe.step-request", "iocontrol.0.tool-prepare", "iocontrol.0.tool-prepared",
        "iocontrol.0.tool-change", "iocontrol.0.tool-changed", "iocontrol.0.tool-number",
        "motion.probe-input", "spindle.0.on", "iocontrol.0.coolant-flood", "fatc-chuck-guard.chuck",
        "fatc-chuck-guard.alive", "fixed_atc_probe.cut-off-pocket", "fixed_atc_probe.pocket-served",
        "fixed_atc_probe.batch-done", "fixed_atc_probe.batch-total", "fixed_atc_probe.step-number",
        "fixed_atc_probe.can-cancel", "fixed_atc_probe.rack-cover-open",
        "fixed_atc_probe.rack-cover-opened", "fixed_atc_probe.rack-cover-closed",
        "fixed_atc_probe.air-blast", "fixed_atc_probe.chuck-held", "motion.feed-inhibit",
        "spindle.0.inhibit", "fixed_atc_probe.rack-keepout", "fatc-rack-guard.tripped", "fatc-rack-guard.trips",
        "motion.jog-is-active", "fixed_atc_probe.zero-speed", "fixed_atc_probe.rack-keepout-tool-length",
        "fixed_atc_probe.step-kind", "fixed_atc_probe.step-feed",
        "motion.digital-out-02"]  # the benchmark programs' mark between two changes
COMPONENT = "fixed_atc_probe"
# A scenario's own pins sampled beside PINS ("sample_pins": the simulated
# collet-nut magazine's, the joints', the spindle guard's).
sample_pins = []

stat = linuxcnc.stat()
command = linuxcnc.command()
errors = linuxcnc.error_channel()
messages = []
# NML keeps one read mark for all readers of the message channel: what the
# driver reads, a GUI beside it never shows. The gmoccapy GUI test leaves the
# messages to gmoccapy (False) and reads them on the panel.
read_messages = True


def drain_errors():
    if not read_messages:
        return
    while True:
        error = errors.poll()
        if not error:
            return
        messages.append(error[1])


def wait_for(condition, timeout, what):
    """Waits on a condition LinuxCNC reports, generously: these machines are shared."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        stat.poll()
        drain_errors()
        if condition():
            return
        time.sleep(0.01)
    raise TimeoutError("timed out waiting for " + what)


def bring_up():
    wait_for(lambda: stat.task_state in (linuxcnc.STATE_ESTOP, linuxcnc.STATE_ESTOP_RESET,
                                         linuxcnc.STATE_ON, linuxcnc.STATE_OFF), 120, "task")
    stat.poll()
    if stat.task_state != linuxcnc.STATE_ON:  # the GUI test may have turned it on through its GUI
        command.state(linuxcnc.STATE_ESTOP_RESET)
        command.state(linuxcnc.STATE_ON)
    wait_for(lambda: stat.task_state == linuxcnc.STATE_ON, 60, "machine on")
    command.mode(linuxcnc.MODE_MANUAL)
    command.wait_complete()
    command.home(-1)
    wait_for(lambda: all(stat.homed[i] for i in range(stat.joints)), 120, "homing")
    if not os.environ.get("FATC_NO_CHANGER"):  # the benchmark's peer runs without it
        wait_for(lambda: hal.get_value("fixed_atc_probe.state") == 1, 60, "fixed_atc_probe idle")


def pin_value(pin):
    """None while the pin does not exist (the component is being restarted)."""
    try:
        return hal.get_value(pin)
    except (NameError, RuntimeError):
        return None


def sample(start):
    values = {pin: pin_value(pin) for pin in PINS + sample_pins}
    values["t"] = time.monotonic() - start
    values["pos"] = list(stat.actual_position[:3])
    values["cmd"] = list(stat.position[:3])
    values["vel"] = stat.current_vel
    values["tool_in_spindle"] = stat.tool_in_spindle
    values["interp"] = stat.interp_state
    values["paused"] = stat.paused
    return values


# ---------------------------------------------------------------- kill and restart
def ini():
    return linuxcnc.ini(os.environ["INI_FILE_NAME"])


def ini_dir():
    """LinuxCNC runs halcmd (and so the component) in the INI's folder."""
    return os.path.dirname(os.path.abspath(os.environ["INI_FILE_NAME"]))


def state_path():
    return os.path.join(ini_dir(), ini().find("FIXED_ATC_PROBE", "STATE"))


def config_path():
    return os.path.join(ini_dir(), ini().find("FIXED_ATC_PROBE", "CONFIG"))


def read_text(path):
    """The file's text exactly (None when there is none)."""
    try:
        with open(path, newline="") as f:
            return f.read()
    except OSError:
        return None


def read_json(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        return {"unreadable": str(e)}


def halcmd(*args):
    return subprocess.run(["halcmd"] + list(args), capture_output=True, text=True, timeout=60,
                          cwd=ini_dir())


def hal_components():
    """`halcmd show comp`: name -> {id, type, pid, state}."""
    comps = {}
    for line in halcmd("show", "comp").stdout.splitlines():
        words = line.split()
        if len(words) >= 3 and words[0].isdigit() and words[1] in ("User", "RT"):
            pid = int(words[3]) if words[1] == "User" and len(words) > 4 else None
            comps[words[2]] = {"id": int(words[0]), "type": words[1], "pid": pid,
                               "state": words[-1]}
    return comps


def pin_links(prefix=COMPONENT + "."):
    """`halcmd show pin`: every pin of the component -> the signal it is on (or None)."""
    links = {}
    for line in halcmd("show", "pin", prefix).stdout.splitlines():
        words = line.split()
        if len(words) >= 5 and words[0].isdigit() and words[4].startswith(prefix):
            links[words[4]] = words[6] if len(words) >= 7 else None
    return links


def component_pids():
    """The component's process as HAL registered it (`halcmd show comp` gives its
    PID): [pid] while that process lives, [] when none is registered or it died.
    Never by name across the machine: another fixed_atc_probe (a --check or
    --lint in another terminal, the panel's preflight) is not the component."""
    comp = hal_components().get(COMPONENT)
    if comp is None or comp["pid"] is None or process_gone(comp["pid"]):
        return []
    return [comp["pid"]]


def component_usage():
    """The component's CPU seconds so far, its resident memory and peak (KiB);
    None without one component process."""
    pids = component_pids()
    if len(pids) != 1:
        return None
    try:
        fields = open("/proc/%d/stat" % pids[0]).read().rsplit(")", 1)[1].split()
        memory = {line.split(":")[0]: int(line.split()[1]) for line in open("/proc/%d/status" % pids[0])
                  if line.startswith(("VmRSS", "VmHWM"))}
    except OSError:
        return None
    return {"cpu_seconds": (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK"),
            "rss_kib": memory.get("VmRSS"), "peak_kib": memory.get("VmHWM")}


def process_state(pid):
    """The state letter /proc gives the process (R, S, T, Z, ...), None when there is none."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0]
    except OSError:
        return None


def process_gone(pid):
    """Dead: no such process, or a zombie its parent has not reaped."""
    return process_state(pid) in (None, "Z", "X")


def the_component_pid():
    pids = component_pids()
    if len(pids) != 1:
        raise RuntimeError("expected one %s process, found %s" % (COMPONENT, pids))
    return pids[0]


# LinuxCNC's NML buffers (the sim runs with LinuxCNC's default NML file) each
# have a SysV semaphore as their lock, taken without SEM_UNDO: a process that
# dies holding one leaves it taken, and task then blocks on every status
# write ("SHMEM: Can't take semaphore"). True of any NML client (a GUI too);
# so the driver stops and kills the component only outside these locks.
NML_BUFFER_KEYS = (1001, 1002, 1003, 1004, 1005)
GETPID, GETVAL = 11, 12  # semctl commands, <linux/sem.h>
libc = ctypes.CDLL(None, use_errno=True)


def holds_nml_lock(pid):
    for key in NML_BUFFER_KEYS:
        ident = libc.semget(key, 0, 0)
        if ident >= 0 and libc.semctl(ident, 0, GETVAL) == 0 and libc.semctl(ident, 0, GETPID) == pid:
            return True
    return False


def stop_outside_nml_locks(pid):
    """SIGSTOP at a moment `pid` holds none of LinuxCNC's NML locks."""
    for _ in range(1000):
        os.kill(pid, signal.SIGSTOP)
        deadline = time.monotonic() + 10
        while not process_stopped(pid):  # no stat.poll here: it would wait on the lock
            if time.monotonic() > deadline:
                raise TimeoutError("the component did not stop on SIGSTOP")
            time.sleep(0.001)
        if not holds_nml_lock(pid):
            return
        os.kill(pid, signal.SIGCONT)
    raise RuntimeError("the component held LinuxCNC's NML lock at every one of 1000 stops")


def die_holding_nml_lock(key):
    """A process that takes NML buffer `key`'s lock and dies holding it."""
    child = os.fork()
    if child == 0:
        take = (ctypes.c_short * 3)(0, -1, 0)  # struct sembuf: the first semaphore, -1, no SEM_UNDO
        os._exit(0 if libc.semop(libc.semget(key, 0, 0), take, 1) == 0 else 1)
    if os.waitpid(child, 0)[1] != 0:
        raise RuntimeError("could not take the lock of NML buffer %d" % key)


def process_stopped(pid):
    return process_state(pid) in ("T", "t")


def kill_component():
    """SIGKILL: the component gets no chance to close its chuck or save anything."""
    pid = the_component_pid()
    stop_outside_nml_locks(pid)
    os.kill(pid, signal.SIGKILL)
    killed = time.monotonic()
    wait_for(lambda: process_gone(pid), 10, "the killed component to die")
    return pid, killed


def start_decoy():
    """Another fixed_atc_probe on the machine, as a --lint in another terminal:
    a program that loops keeps it running for its 15 s."""
    program = os.path.join(ini_dir(), "decoy_endless.ngc")
    with open(program, "w") as f:
        f.write("o100 while [1]\n  G0 X1\n  G0 X2\no100 endwhile\nM2\n")
    return subprocess.Popen([COMPONENT, "--lint", program, "--config", config_path()],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=ini_dir())


def stat_modes():
    """The modes LinuxCNC reports: the interpreter's G and M codes and settings,
    and what motion applies (tool offset, override enables)."""
    stat.poll()
    table = {t.id: t.zoffset for t in stat.tool_table if t.id >= 0}
    return {"gcodes": [g for g in stat.gcodes if g >= 0], "mcodes": [m for m in stat.mcodes if m >= 0],
            "feed": stat.settings[1], "tool_offset": list(stat.tool_offset[:3]),
            "program_units": stat.program_units, "linear_units": stat.linear_units,
            "feed_override_enabled": bool(stat.feed_override_enabled),
            "spindle_override_enabled": bool(stat.spindle[0]["override_enabled"]),
            "tool_in_spindle": stat.tool_in_spindle,
            "tool_z": table.get(stat.tool_in_spindle), "interp": stat.interp_state}


_reapers = []


def remove_dead_component(comp):
    """LinuxCNC 2.9 has no command that removes a userspace component whose
    process died: `halcmd unloadusr`/`unload` only send SIGTERM to its pid
    (src/hal/utils/halcmd_commands.c, do_unloadusr_cmd) and return 0, so its
    registration and pins stay; a new process then fails hal_init with
    "duplicate component name", while `loadusr -W` returns 0 at once: the dead
    registration is "ready". hal_exit(id) removes any component by id
    (hal_lib.c: it unlinks and frees its pins), from any process attached to
    HAL; it also drops that process's hal_lib reference count, and at zero the
    process detaches from HAL. So a component of our own is registered first
    to hold the reference: it stays registered (with this driver's pid) until
    LinuxCNC stops realtime; its shutdown waits up to 2 s for it to go."""
    lib = ctypes.CDLL("liblinuxcnchal.so.0")  # the library the hal module uses: one reference count
    name = "fatc-reaper-%d" % (len(_reapers) + 1)
    reaper = lib.hal_init(name.encode())
    if reaper < 0:
        raise RuntimeError("hal_init(%s) failed: %d" % (name, reaper))
    lib.hal_ready(reaper)
    _reapers.append(reaper)
    result = lib.hal_exit(comp["id"])
    if result != 0:
        raise RuntimeError("hal_exit(%d) of the dead %s failed: %d" % (comp["id"], COMPONENT, result))
    return name


def hal_file_lines(path, resolve):
    """The lines of a HAL file with [SECTION]KEY resolved and comments dropped."""
    lines = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if line:
                lines.append(re.sub(r"\[([A-Za-z0-9_]+)\]([A-Za-z0-9_]+)", resolve, line).split())
    return lines


def component_hal_commands():
    """What the machine's HAL files do to the component: its loadusr, then every
    `net` and `setp` that names one of its pins, as halcmd commands."""
    inifile = ini()

    def resolve(m):
        value = inifile.find(m.group(1), m.group(2))
        if value is None:
            raise RuntimeError("[%s]%s not in the INI" % (m.group(1), m.group(2)))
        return value

    files = [f for f in inifile.findall("HAL", "HALFILE") or []]
    # The panel's file is loaded only after a GUI made its component.
    if hal.component_exists("fatc-panel"):
        files += inifile.findall("HAL", "POSTGUI_HALFILE") or []
    load, nets, setps = None, [], []
    for name in files:
        if name.startswith("LIB:") or not name.endswith(".hal"):
            continue  # the machine's own Tcl files do not name the component
        path = name if os.path.isabs(name) else os.path.join(ini_dir(), name)
        for words in hal_file_lines(path, resolve):
            if words[0] == "loadusr" and COMPONENT in words:
                load = words
            elif words[0] == "net":
                nets += [("net", words[1], w) for w in words[2:] if w.startswith(COMPONENT + ".")]
            elif words[0] == "setp" and words[1].startswith(COMPONENT + "."):
                setps.append(("setp", words[1], words[2]))
    if load is None:
        raise RuntimeError("no loadusr of %s in %s" % (COMPONENT, files))
    return [tuple(load)] + nets + setps


def restart_component():
    """Brings a SIGKILLed component back as the machine's HAL files did: remove
    the dead registration, loadusr -W with the same arguments, net every pin to
    the signal the HAL files name, setp what they set."""
    report = {"pid_alive": component_pids()}
    comps = hal_components()
    dead = comps.get(COMPONENT)
    if dead is None:
        raise RuntimeError("%s is not registered in HAL: %s" % (COMPONENT, sorted(comps)))
    if not process_gone(dead["pid"]):
        raise RuntimeError("%s (pid %d) is still running: kill it first" % (COMPONENT, dead["pid"]))
    report["dead"] = dead
    report["links_before"] = pin_links()  # the dead component's pins are still on their signals
    # What LinuxCNC offers for it: both only send SIGTERM to the dead pid.
    report["unloadusr"] = halcmd("unloadusr", COMPONENT).returncode
    report["unload"] = halcmd("unload", COMPONENT).returncode
    report["registered_after_unload"] = COMPONENT in hal_components()
    report["reaper"] = remove_dead_component(dead)
    report["registered_after_hal_exit"] = COMPONENT in hal_components()
    commands = component_hal_commands()
    report["commands"] = [" ".join(c) for c in commands]
    hal_path = os.path.join(ini_dir(), "fixed_atc_probe_restart.hal")
    with open(hal_path, "w") as f:
        f.write("\n".join(report["commands"]) + "\n")
    # The component keeps halcmd's output files: a log, not a pipe we would wait on.
    log_path = os.path.join(ini_dir(), "fixed_atc_probe_restart.log")
    began = time.monotonic()
    with open(log_path, "a") as log:
        code = subprocess.run(["halcmd", "-f", hal_path], stdout=log, stderr=subprocess.STDOUT,
                              stdin=subprocess.DEVNULL, cwd=ini_dir(), timeout=120).returncode
    report["load_seconds"] = time.monotonic() - began
    if code != 0:
        raise RuntimeError("halcmd -f %s failed (%d): %s" % (hal_path, code, open(log_path).read()[-2000:]))
    report["new"] = hal_components().get(COMPONENT)
    report["pid_new"] = component_pids()
    report["links_after"] = pin_links()
    return report


def snapshot(start):
    """What the component and LinuxCNC say at one moment: pins, files, tool."""
    stat.poll()
    return {"t": time.monotonic() - start, "pins": {p: pin_value(p) for p in PINS + sample_pins},
            "tool_in_spindle": stat.tool_in_spindle, "pos": list(stat.actual_position[:3]),
            "state_file": read_json(state_path()), "status_file": read_json(state_path() + ".status")}


def run_scenario(scenario):
    result = {"name": scenario["name"], "samples": [], "messages": []}
    first_message = len(messages)
    for pin, value in scenario.get("set_pins", {}).items():
        hal.set_p(pin, value)
    for line in scenario.get("mdi", []):
        command.mode(linuxcnc.MODE_MDI)
        command.wait_complete()
        command.mdi(line)
        command.wait_complete(60)
    result["usage_before"] = component_usage()
    decoy = start_decoy() if scenario.get("decoy") else None
    start_program(scenario["program"])
    start = time.monotonic()
    wait_for(lambda: stat.interp_state != linuxcnc.INTERP_IDLE or stat.exec_state != 0, 30,
             "the program to start")
    acted = set()
    releases = []  # (time, pin): buttons pressed during the program, released 100 ms later
    deadline = start + scenario.get("timeout", 300)
    while time.monotonic() < deadline:
        stat.poll()
        drain_errors()
        s = sample(start)
        result["samples"].append(s)
        for at, pin in [r for r in releases if time.monotonic() - r[0] > 0.1]:
            hal.set_p(pin, "0")
            releases.remove((at, pin))
        for action in scenario.get("actions", []):
            key = json.dumps(action)
            if key in acted or not when(action, s, result):
                continue
            acted.add(key)
            if action["do"] == "press":
                hal.set_p(action["pin"], "1")
                releases.append((time.monotonic(), action["pin"]))
                result.setdefault("pressed", []).append([action["pin"], s["t"]])
            elif action["do"] == "pause":
                command.auto(linuxcnc.AUTO_PAUSE)
                result["paused_at"] = s["t"]
            elif action["do"] == "resume":
                command.auto(linuxcnc.AUTO_RESUME)
                result["resumed_at"] = s["t"]
            elif action["do"] == "abort":
                command.abort()
                result["aborted_at"] = s["t"]
            elif action["do"] == "kill":
                result["killed_pid"], killed = kill_component()
                result["killed_at"] = killed - start
                result["kill_sample"] = s
            elif action["do"] == "stop":
                # The component hangs: SIGSTOP, SIGCONT in an after step.
                result["stopped_pid"] = the_component_pid()
                stop_outside_nml_locks(result["stopped_pid"])
                result["stopped_at"] = s["t"]
            elif action["do"] == "estop":
                command.state(linuxcnc.STATE_ESTOP)
                result["estop_at"] = s["t"]
            elif action["do"] in ("restart", "confirm", "snapshot"):
                perform(action, result, start)
            elif action["do"] == "snapshot_abort":
                result["snapshot"] = {"gcodes": list(stat.gcodes),
                                      "path_tolerance": stat.settings[3],
                                      "naive_cam_tolerance": stat.settings[4],
                                      "tool_offset": list(stat.tool_offset[:3]),
                                      "program_units": stat.program_units,
                                      "pos": list(stat.actual_position[:3])}
                command.abort()
        if stat.interp_state == linuxcnc.INTERP_IDLE and s["t"] > 0.5 and not releases:
            break
        time.sleep(0.002)
    if scenario.get("settle_pin"):
        pin, value = scenario["settle_pin"]
        try:
            wait_for(lambda: hal.get_value(pin) == value, 10, pin)
        except TimeoutError:
            pass  # the checker reports what it finds
    if decoy:
        result["decoy_ran"] = decoy.poll() is None  # still there when the component was wanted
        decoy.kill()
        decoy.wait()
    # Let the level handshakes fall back before the last sample.
    wait_for(lambda: not hal.get_value("iocontrol.0.tool-change") and
             not hal.get_value("iocontrol.0.tool-changed"), 10, "the change handshake to end")
    finish(result, start, first_message)
    for pin in scenario.get("set_pins", {}):
        hal.set_p(pin, "0")
    for step in scenario.get("after", []):
        if isinstance(step, dict):
            perform(step, result, start)
        elif step == "clear_fault":
            # The operator has checked the spindle: it holds what LinuxCNC says.
            hal.set_p("fixed_atc_probe.clear-fault", "1")
            wait_for(lambda: hal.get_value("fixed_atc_probe.state") == 1, 30, "the fault to clear")
            hal.set_p("fixed_atc_probe.clear-fault", "0")
    return result


def sampled_wait_in(result, start, condition, timeout, what):
    """Waits on what LinuxCNC or HAL reports, sampling into the result meanwhile."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        stat.poll()
        drain_errors()
        result["samples"].append(sample(start))
        if condition():
            return
        time.sleep(0.002)
    raise TimeoutError("timed out waiting for " + what)


def start_program(program):
    command.mode(linuxcnc.MODE_AUTO)
    command.wait_complete()
    command.program_open(os.path.join(os.environ["FATC_ROOT"], program))
    command.wait_complete()
    command.auto(linuxcnc.AUTO_RUN, 0)


def perform(step, result, start):
    """A step that is the same in a program scenario (an action) and an operator one."""
    def wait(condition, timeout, what):
        sampled_wait_in(result, start, condition, timeout, what)

    def now():
        return time.monotonic() - start

    if step["do"] == "kill":
        # SIGKILL from an operator scenario: mid-flow, as a crash would.
        result["killed_pid"], killed = kill_component()
        result["killed_at"] = killed - start
    elif step["do"] == "restart":
        began = now()
        result["restart"] = restart_component()
        result["restart"]["began"], result["restart"]["done"] = began, now()
    elif step["do"] == "confirm":
        # The operator says what the spindle holds and whether the cut-off pocket
        # holds its tool, then presses Clear fault (a 100 ms pulse).
        hal.set_p(COMPONENT + ".confirm-tool", str(step["tool"]))
        hal.set_p(COMPONENT + ".confirm-pocket", str(step["pocket"]))
        hal.set_p(COMPONENT + ".clear-fault", "1")
        pressed = time.monotonic()
        wait(lambda: time.monotonic() - pressed > 0.1, 5, "the press")
        hal.set_p(COMPONENT + ".clear-fault", "0")
        result["confirmed_at"] = now()
        # Idle, and done comparing the sensors (a rack cover may still be closing).
        wait(lambda: hal.get_value(COMPONENT + ".state") == 1 and
             hal.get_value(COMPONENT + ".awaiting") == 0, 30, "the changer idle after the confirm")
        result["idle_after_confirm_at"] = now()
        hal.set_p(COMPONENT + ".confirm-tool", "-1")
        hal.set_p(COMPONENT + ".confirm-pocket", "-1")
    elif step["do"] == "snapshot":
        result.setdefault("snapshots", {})[step["name"]] = snapshot(start)
    elif step["do"] == "modes":
        # After an abort: once the interpreter is idle, until the G code
        # `until` (G43: 430) shows, an abort handler's commands running after
        # the abort, or 20 s; the checker judges.
        until = step.get("until", 430)

        def restored():
            return stat.interp_state == linuxcnc.INTERP_IDLE and until in stat.gcodes
        try:
            wait(restored, 20, "G%g after the abort" % (until / 10.0))
        except TimeoutError:
            pass
        modes = stat_modes()
        modes["t"] = now()
        result.setdefault("modes", {})[step["name"]] = modes
    elif step["do"] == "continue":
        if "stopped_pid" not in result:
            return  # never stopped: the checker says so
        os.kill(result["stopped_pid"], signal.SIGCONT)
        result["continued_at"] = now()
        wait(lambda: hal.get_value(COMPONENT + ".fault"), 30, "the component to fault")
    elif step["do"] == "machine_on":
        command.state(linuxcnc.STATE_ESTOP_RESET)
        command.state(linuxcnc.STATE_ON)
        wait(lambda: stat.task_state == linuxcnc.STATE_ON, 30, "the machine on")
    elif step["do"] == "files":
        # config.json and its backup as they are on disk now (teaching writes them),
        # the state file and the tool table (an air run writes neither).
        stat.poll()
        result.setdefault("files", {})[step["name"]] = {
            "t": now(), "pos": list(stat.actual_position[:3]),
            "config": read_text(config_path()), "bak": read_text(config_path() + ".bak"),
            "state": read_text(state_path()), "table": read_text(os.path.join(ini_dir(), "sim.tbl"))}
    elif step["do"] == "tool_table":
        table = tool_table.record(stat, os.path.join(ini_dir(), "sim.tbl"), lambda: (
            hal.get_value(COMPONENT + ".state") == 1 and stat.interp_state == linuxcnc.INTERP_IDLE))
        result.setdefault("tool_tables", {})[step["name"]] = dict(table, t=now())
    elif step["do"] == "edit_tool_table":
        result["edited_table"] = tool_table.edit_p(command, os.path.join(ini_dir(), "sim.tbl"),
                                                   step["tool"], step["p"])
    elif step["do"] == "program_open":
        # A program loaded as a GUI's File > Open does, not run (measure-which 2 reads it).
        command.mode(linuxcnc.MODE_AUTO)
        command.wait_complete()
        command.program_open(os.path.join(os.environ["FATC_ROOT"], step["program"]))
        command.wait_complete()
        wait(lambda: stat.file.endswith(step["program"]), 10, "LinuxCNC to load " + step["program"])
    elif step["do"] == "program":
        # A program run from an operator scenario: sampled until the interpreter is idle again.
        wait(lambda: stat.interp_state == linuxcnc.INTERP_IDLE, 60, "task free for the program")
        began = now()
        start_program(step["program"])
        seen = []

        def ended():
            if stat.interp_state != linuxcnc.INTERP_IDLE:
                seen.append(True)
            return stat.interp_state == linuxcnc.INTERP_IDLE and (seen or now() - began > 2.0)
        wait(ended, step.get("timeout", 180), "the program %s to end" % step["program"])
        wait(lambda: not hal.get_value("iocontrol.0.tool-change") and
             not hal.get_value("iocontrol.0.tool-changed"), 10, "the change handshake to end")
        result.setdefault("programs", {})[step["name"]] = {"began": began, "ended": now(),
                                                           "program": step["program"]}
    elif step["do"] == "shift_rack":
        # The simulated rack bumped (config/sim/sim_rack.hal): moved by x, y, z
        # from where its HAL file set it up.
        for axis in "xyz":
            hal.set_p(RACK + "shift-" + axis, repr(float(step.get(axis, 0.0))))
        result.setdefault("shifts", []).append({"t": now(), "shift": [step.get(a, 0.0) for a in "xyz"]})
    elif step["do"] == "rack_truth":
        result.setdefault("rack_truth", {})[step["name"]] = dict(rack_truth(), t=now())
    elif step["do"] == "touch":
        result.setdefault("touches", {})[step["name"]] = touch(step, wait)
    elif step["do"] == "status_lock_lost":
        # A reader of task's status dies holding its lock (NML_BUFFER_KEYS):
        # LinuxCNC stalls until it restarts, so this ends its run; nothing
        # here polls the status. Then the operator presses Load.
        die_holding_nml_lock(1002)
        result["lock_lost_at"] = now()
        hal.set_p(COMPONENT + ".tool-number", str(step["tool"]))
        hal.set_p(COMPONENT + ".load", "1")
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            status = read_json(state_path() + ".status")
            if any(step["words"] in m.get("text", "") for m in status.get("messages", [])):
                break
            time.sleep(0.05)
        hal.set_p(COMPONENT + ".load", "0")
        result["status_file"] = read_json(state_path() + ".status")
        result["answered_at"] = now()
    else:
        raise ValueError("unknown step %s" % step)


RACK = "fatc-sim-rack."  # the simulated rack a touch probe touches (config/sim/sim_rack.hal)


def rack_truth():
    """Where the simulated rack is: its pins as set, and what they make of it
    (each bore's centre and the top face, the shift added), in machine units."""
    pins = {pin: hal.get_value(RACK + pin) for pin in (
        "count", "bore-diameter", "top-z", "bottom-z", "x-min", "x-max", "y-min", "y-max",
        "shift-x", "shift-y", "shift-z", "probe-length", "stylus-radius", "touching", "out")}
    bores = [[hal.get_value(RACK + "pocket-x-%d" % k) + pins["shift-x"],
              hal.get_value(RACK + "pocket-y-%d" % k) + pins["shift-y"]] for k in range(pins["count"])]
    return {"pins": pins, "bores": bores, "top_z": pins["top-z"] + pins["shift-z"]}


def parameters(*numbers):
    """The interpreter's numbered parameters, as LinuxCNC prints them (DEBUG)."""
    said = len(messages)
    command.mode(linuxcnc.MODE_MDI)
    command.wait_complete()
    command.mdi("(DEBUG,fatc-parameters %s)" % " ".join("#%d" % n for n in numbers))
    command.wait_complete(10)
    wait_for(lambda: any(m.startswith("fatc-parameters") for m in messages[said:]), 10,
             "the parameters " + " ".join(map(str, numbers)))
    line = [m for m in messages[said:] if m.startswith("fatc-parameters")][0]
    return dict(zip(numbers, map(float, line.split()[1:])))


def touch(step, wait):
    """A touch as a probing flow makes one, on `axis` toward `to` from where the
    spindle stands, by MDI in the work coordinates in effect: G38.3 at the seek
    feed, back off by the backoff, G38.3 again at the latch feed (config.json's
    probe_seek_feed, probe_latch_feed, probe_backoff unless the step says),
    then back where it started. What LinuxCNC reports after each G38.3:
    #5061-#5063, #5070 and its probed position."""
    config = read_json(config_path())
    seek = step.get("seek", config.get("probe_seek_feed"))
    latch = step.get("latch", config.get("probe_latch_feed"))
    backoff = step.get("backoff", config.get("probe_backoff"))
    axis = "xyz".index(step["axis"].lower())
    letter = step["axis"].upper()
    stat.poll()
    begin = stat.position[axis] - stat.g5x_offset[axis] - stat.g92_offset[axis] - stat.tool_offset[axis]
    toward = 1.0 if step["to"] > begin else -1.0

    def probe(target, feed):
        began, seen = time.monotonic(), []

        def ended():  # task takes the line before the interpreter says it runs
            if stat.interp_state != linuxcnc.INTERP_IDLE:
                seen.append(True)
            return stat.interp_state == linuxcnc.INTERP_IDLE and (seen or time.monotonic() - began > 2.0)
        command.mdi("G38.3 %s%.4f F%.1f" % (letter, target, feed))
        command.wait_complete(120)
        wait(ended, 120, "the G38.3 to end")
        found = parameters(5061, 5062, 5063, 5070)
        stat.poll()
        return {"feed": feed, "to": target, "tripped": found[5070] == 1.0,
                "probed": [found[5061], found[5062], found[5063]],
                "stat_probed": list(stat.probed_position[:3]), "stat_tripped": bool(stat.probe_tripped),
                "probe_input": hal.get_value("motion.probe-input"),
                "rack_touching": hal.get_value(RACK + "touching")}

    command.mode(linuxcnc.MODE_MDI)
    command.wait_complete()
    done = {"axis": letter, "from": begin, "backoff": backoff, "seek": probe(step["to"], seek)}
    if done["seek"]["tripped"]:
        trip = done["seek"]["probed"][axis]
        command.mdi("G1 %s%.4f F%.1f" % (letter, trip - toward * backoff, seek))
        command.wait_complete(60)
        done["latch"] = probe(trip + toward * 2 * backoff, latch)
    command.mdi("G0 %s%.4f" % (letter, begin))
    command.wait_complete(60)
    return done


def run_operator(scenario):
    """An operator at the panel: buttons are HAL pins, waits are on what LinuxCNC
    and the component report, all sampled like a program run."""
    result = {"name": scenario["name"], "samples": [], "messages": []}
    first_message = len(messages)
    start = time.monotonic()

    def sampled_wait(condition, timeout, what):
        sampled_wait_in(result, start, condition, timeout, what)

    background = {}  # operator commands still running, by name

    for step in scenario["operator"]:
        if "do" in step:
            perform(step, result, start)
        elif "set" in step:
            for pin, value in step["set"].items():
                hal.set_p(pin, str(value))
        elif "press" in step:
            # A press is a pulse the component's 20 ms poll cannot miss: 100 ms
            # down, then 100 ms up before anything else may press again.
            hal.set_p(step["press"], "1")
            pressed = time.monotonic()
            sampled_wait(lambda: time.monotonic() - pressed > 0.1, 5, "the press")
            hal.set_p(step["press"], "0")
            released = time.monotonic()
            sampled_wait(lambda: time.monotonic() - released > 0.1, 5, "the release")
        elif "wait" in step:
            pin, value = step["wait"]
            sampled_wait(lambda: hal.get_value(pin) == value, step.get("timeout", 180),
                         "%s == %s" % (pin, value))
        elif "wait_pins" in step:
            # Every pin at its value in the same sample.
            pins = step["wait_pins"]
            sampled_wait(lambda: all(hal.get_value(p) == v for p, v in pins.items()),
                         step.get("timeout", 180), " and ".join("%s == %s" % i for i in pins.items()))
        elif "wait_message" in step:
            sampled_wait(lambda: any(step["wait_message"] in m for m in messages[first_message:]), 60,
                         "a message saying " + step["wait_message"])
        elif "wait_tool_in_spindle" in step:
            sampled_wait(lambda: stat.tool_in_spindle == step["wait_tool_in_spindle"], 60,
                         "LinuxCNC's tool in spindle to be %d" % step["wait_tool_in_spindle"])
        elif "wait_idle" in step:
            sampled_wait(lambda: hal.get_value("fixed_atc_probe.state") == 1 and
                         stat.interp_state == linuxcnc.INTERP_IDLE, 180, "the changer idle")
        elif step.get("machine") == "off":
            command.state(linuxcnc.STATE_OFF)  # task then reports ESTOP_RESET or OFF
            sampled_wait(lambda: stat.task_state != linuxcnc.STATE_ON and
                         hal.get_value("fixed_atc_probe.state") == 0, 30, "the machine off")
        elif step.get("machine") == "on":
            command.state(linuxcnc.STATE_ON)  # homing survives machine off
            sampled_wait(lambda: hal.get_value("fixed_atc_probe.state") == 1, 30, "the changer idle")
        elif "wait_move_held" in step:
            # A move was asked for and the interpreter runs it, yet the machine
            # stands: for this many samples in a row (what LinuxCNC reports).
            stat.poll()
            held_at, held = list(stat.actual_position[:3]), [0]

            def still():
                moving = stat.interp_state == linuxcnc.INTERP_IDLE or \
                    list(stat.actual_position[:3]) != held_at
                held[0] = 0 if moving else held[0] + 1
                return held[0] >= step["wait_move_held"]
            sampled_wait(still, 60, "a move held still for %d samples" % step["wait_move_held"])
            result["held_at"] = held_at
        elif "abort" in step:
            command.abort()
            sampled_wait(lambda: stat.interp_state == linuxcnc.INTERP_IDLE, 30, "the abort")
        elif "wait_interp_idle" in step:
            # A move held by the rack guard: the component aborts it.
            sampled_wait(lambda: stat.interp_state == linuxcnc.INTERP_IDLE and
                         not hal.get_value("fatc-rack-guard.tripped"), step["wait_interp_idle"],
                         "the interpreter idle, the rack guard released")
        elif "jog_cont" in step:
            # The operator holds a jog key until the machine stops or `timeout`,
            # then lets go (JOG_STOP), as a GUI does.
            axis, velocity = step["jog_cont"]
            command.mode(linuxcnc.MODE_MANUAL)
            command.wait_complete()
            command.jog(linuxcnc.JOG_CONTINUOUS, False, axis, velocity)
            sampled_wait(lambda: hal.get_value("motion.jog-is-active"), 10, "the jog to start")
            try:
                sampled_wait(lambda: not hal.get_value("motion.jog-is-active"),
                             step.get("timeout", 30), "the jog to stop")
            except TimeoutError:
                pass  # the checker judges where it went
            command.jog(linuxcnc.JOG_STOP, False, axis)
            result["jogged_to"] = list(stat.actual_position[:3])
        elif "wait_z_below" in step:
            sampled_wait(lambda: stat.actual_position[2] < step["wait_z_below"], 60,
                         "Z below %s" % step["wait_z_below"])
        elif "jog" in step:
            axis, distance = step["jog"]
            command.mode(linuxcnc.MODE_MANUAL)
            command.wait_complete()
            target = stat.actual_position[axis] + distance
            command.jog(linuxcnc.JOG_INCREMENT, False, axis, 20.0, distance)
            sampled_wait(lambda: abs(stat.actual_position[axis] - target) < 1e-3, 60, "the jog")
            result["jogged_to"] = list(stat.actual_position[:3])
        elif "operator_command" in step or "join" in step:
            operator_command.perform(step, result, background)
        elif "mdi" in step:
            command.mode(linuxcnc.MODE_MDI)
            command.wait_complete()
            command.mdi(step["mdi"])
            if step.get("complete", True):  # a move held back would keep it waiting
                command.wait_complete(60)
    finish(result, start, first_message)
    return result


def machine_on():
    """Out of estop, on, and homed where homing was lost: what an operator does
    before looking at the changer after an estop or a start."""
    command.state(linuxcnc.STATE_ESTOP_RESET)
    command.state(linuxcnc.STATE_ON)
    wait_for(lambda: stat.task_state == linuxcnc.STATE_ON, 60, "machine on")
    if not all(stat.homed[i] for i in range(stat.joints)):
        command.mode(linuxcnc.MODE_MANUAL)
        command.wait_complete()
        command.home(-1)
        wait_for(lambda: all(stat.homed[i] for i in range(stat.joints)), 120, "homing")


def finish(result, start, first_message):
    """The last sample and what LinuxCNC says after the scenario."""
    stat.poll()
    drain_errors()
    result["samples"].append(sample(start))
    result["messages"] = messages[first_message:]
    result["start_pos"] = result["samples"][0]["pos"]
    result["duration"] = time.monotonic() - start
    result["usage_after"] = component_usage()
    result["tool_table_file"] = open(os.path.join(os.path.dirname(sys.argv[2]), "sim.tbl")).read()
    # The lengths LinuxCNC holds in memory (stat), beside the file it wrote.
    result["tool_table"] = {str(t.id): t.zoffset for t in stat.tool_table if t.id > 0}
    result["state_file"] = read_json(state_path())
    result["status_file"] = read_json(state_path() + ".status")


def when(action, s, result):
    """An action fires on a condition of the sample: e.g. chuck open, or a pin value."""
    condition = action["when"]
    if "pin" in condition:
        # "nth": the condition's nth start (an operator wait that comes twice).
        key = "seen %s" % json.dumps(condition)
        now = s[condition["pin"]] == condition["value"]
        if now and not result.get(key + " last"):
            result[key] = result.get(key, 0) + 1
        result[key + " last"] = now
        return now and result.get(key, 0) == condition.get("nth", 1)
    if "after_start" in condition:
        return s["t"] > condition["after_start"]
    if "program_paused" in condition:
        return s["paused"]
    if "after_paused" in condition:
        return "paused_at" in result and s["t"] > result["paused_at"] + condition["after_paused"]
    return False


def main():
    # A run that hangs: `kill -USR1` prints where the driver waits.
    faulthandler.register(signal.SIGUSR1)
    driver = hal.component("fatc-driver")  # hal.get_value needs a component of our own
    driver.ready()
    scenarios = json.load(open(os.environ["FATC_SCENARIOS"]))
    results = {"scenarios": [], "error": None}
    try:
        bring_up()
        for scenario in scenarios:
            sample_pins[:] = scenario.get("sample_pins", [])
            run = run_operator if "operator" in scenario else run_scenario
            results["scenarios"].append(run(scenario))
    except Exception as e:  # the checker reports it; LinuxCNC must still shut down
        results["error"] = "%s: %s (last messages: %s)" % (type(e).__name__, e, messages[-4:])
    json.dump(results, open(os.environ["FATC_RESULTS"], "w"))
    write_per_scenario(os.environ["FATC_RESULTS"], results)


def write_per_scenario(path, results):
    """Each scenario also alone beside RESULTS (check.load_results reads it):
    a checker of one scenario then parses its own samples, not every one's."""
    folder = path + ".d"
    os.makedirs(folder, exist_ok=True)
    for scenario in results["scenarios"]:
        json.dump(scenario, open(os.path.join(folder, scenario["name"] + ".json"), "w"))
    json.dump({"error": results["error"], "names": [s["name"] for s in results["scenarios"]]},
              open(os.path.join(folder, "run.json"), "w"))


if __name__ == "__main__":
    main()
