"""The headless operator (`fixed_atc_probe --operator`) against the running
machine, as a user types it with the INI: driver.py's steps
  {"operator_command": [ARGS...], "name": N}                   runs it to its end
  {"operator_command": [...], "name": N, "background": true}   runs on meanwhile
  {"join": N}                                                  waits for it
each run's arguments, output and exit status into result["operator_commands"][N]."""
import os
import subprocess


def perform(step, result, background):
    """`background`: the runs still going, by name (another invocation may
    answer the prompt one of them waits at)."""
    if "join" in step:
        join(result, step["join"], background.pop(step["join"]))
        return
    args = ["fixed_atc_probe", "--operator"] + step["operator_command"] + \
        ["--ini", os.environ["INI_FILE_NAME"]]
    process = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if step.get("background"):
        background[step["name"]] = process
    else:
        join(result, step["name"], process)


def join(result, name, process):
    out, err = process.communicate(timeout=300)
    result.setdefault("operator_commands", {})[name] = {
        "args": process.args, "code": process.returncode, "out": out, "err": err}
