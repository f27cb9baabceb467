#!/usr/bin/python3
"""Unit tests of scripts/rehearse.py (issue 44), no LinuxCNC started: the
user's INI into the simulated copy's, and the bad input refused with one line.

    rehearse_unit.py FIXED_ATC_PROBE_BINARY"""
import contextlib
import io
import json
import os
import shutil
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..", "..")
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import linuxcnc  # noqa: E402
import rehearse  # noqa: E402

SAMPLES = "/usr/share/doc/linuxcnc/examples/sample-configs/sim"
# Setup step 4's section with behaviour keys other than its own, to be seen in the copy.
SECTION = rehearse.text_of(os.path.join(HERE, "fixed_atc_probe_section.ini")).replace(
    "STEP_TIMEOUT = 30", "STEP_TIMEOUT = 45").replace("RETURN_TO_XY = 0", "RETURN_TO_XY = 1")


def config_of(name):
    return json.loads(rehearse.text_of(os.path.join(HERE, name)))


def without_m6_moves(text):
    return "".join(line for line in text.splitlines(True) if not line.startswith("TOOL_CHANGE_"))


class Machine(unittest.TestCase):
    """A copy of a sample machine in a folder of its own."""

    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="rehearse-unit-")
        self.addCleanup(shutil.rmtree, self.folder)

    def machine(self, sample, config, section=SECTION, edit=lambda text: text):
        ini = os.path.join(self.folder, "machine.ini")
        text = without_m6_moves(rehearse.text_of(os.path.join(SAMPLES, sample)))
        rehearse.write(ini, edit(text) + section)
        table = linuxcnc.ini(os.path.join(SAMPLES, sample)).find("EMCIO", "TOOL_TABLE")
        shutil.copy(os.path.join(SAMPLES, os.path.dirname(sample), table), self.folder)
        shutil.copy(os.path.join(HERE, config), os.path.join(self.folder, "fixed_atc_probe.json"))
        return ini

    def refused(self, *args):
        """main()'s exit and what it printed; nothing may be written to the workdir."""
        work = os.path.join(self.folder, "work")
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            status = rehearse.main(list(args) + ["--workdir", work, "--binary", sys.argv[1]])
        self.assertEqual(status, 2)
        self.assertEqual(out.getvalue(), "")
        lines = err.getvalue().splitlines()
        self.assertEqual(len(lines), 1, lines)
        self.assertTrue(lines[0].endswith("; nothing started"), lines[0])
        self.assertFalse(os.path.exists(os.path.join(work, "rehearsal.ini")))
        return lines[0]


class Translation(Machine):
    def test_the_copy_keeps_the_machine_and_its_behaviour_keys(self):
        ini_path = self.machine("gmoccapy/gmoccapy.ini", "rehearse_mm.json")
        ini = linuxcnc.ini(ini_path)
        config = config_of("rehearse_mm.json")
        text, length = rehearse.sim_ini(ini, ini_path, config, "c.json", self.folder)
        copy = os.path.join(self.folder, "copy.ini")
        rehearse.write(copy, text)
        sim = linuxcnc.ini(copy)
        for section in ("AXIS_X", "AXIS_Z", "JOINT_0", "JOINT_2"):
            for key in ("MIN_LIMIT", "MAX_LIMIT", "MAX_VELOCITY", "MAX_ACCELERATION"):
                self.assertEqual(sim.find(section, key), ini.find(section, key), section + key)
        self.assertEqual(sim.find("TRAJ", "LINEAR_UNITS"), "mm")
        self.assertEqual(sim.find("KINS", "KINEMATICS"), "trivkins coordinates=xyz")
        self.assertEqual(sim.find("JOINT_2", "HOME"), "-10")
        self.assertEqual(sim.find("JOINT_2", "HOME_SEARCH_VEL"), "0")
        self.assertEqual(sim.find("EMCIO", "CYCLE_TIME"), "0.100")
        self.assertEqual(sim.find("FIXED_ATC_PROBE", "STEP_TIMEOUT"), "45")
        self.assertEqual(sim.find("FIXED_ATC_PROBE", "RETURN_TO_XY"), "1")
        # The user's wiring is not the simulated mill's.
        self.assertEqual(sim.find("FIXED_ATC_PROBE", "MACHINE_ON_SIGNAL"), "sample:enable")
        self.assertNotIn("gmoccapy", " ".join(sim.findall("HAL", "HALFILE")))
        self.assertIn(os.path.join(self.folder, "rack_sim.hal"), sim.findall("HAL", "HALFILE"))
        # config/sim's plate for a touch probe sits where the sample rack is, not theirs.
        self.assertNotIn("sim_rack.hal", " ".join(sim.findall("HAL", "HALFILE")))
        # The setter under probe_limit (X 60 +- 5), a quarter of the way up to loading.
        self.assertEqual(float(sim.find("FIXED_ATC_PROBE", "SIM_SENSOR_Z")), -70.0)
        self.assertEqual(float(sim.find("FIXED_ATC_PROBE", "SIM_SENSOR_XMIN")), 55.0)
        self.assertEqual(length, 25.0)

    def test_inches_stay_inches(self):
        ini_path = self.machine("axis/axis.ini", "rehearse_inch.json")
        config = config_of("rehearse_inch.json")
        sensor, length = rehearse.setter(config, "c.json")
        self.assertEqual(length, 1.0)
        self.assertAlmostEqual(sensor["SIM_SENSOR_XMAX"] - sensor["SIM_SENSOR_XMIN"], 10 / 25.4)
        text, _ = rehearse.sim_ini(linuxcnc.ini(ini_path), ini_path, config, "c.json", self.folder)
        self.assertIn("LINEAR_UNITS = inch", text)

    def test_a_gantry_reads_z_on_its_fourth_joint(self):
        ini = os.path.join(SAMPLES, "gmoccapy/non_trivial_kinematics/Gantry/gantry_mm.ini")
        self.assertEqual(rehearse.joints_of(linuxcnc.ini(ini), ini), {"X": 0, "Y": 1, "Z": 3})

    def test_the_rack_has_a_sensor_for_each_of_the_users_pockets(self):
        hal = rehearse.rack_hal(config_of("rehearse_inch.json"))
        self.assertEqual([line.split()[1] for line in hal.splitlines() if "pocket-occupied" in line],
                         ["fatc-sim-pocket-1", "fatc-sim-pocket-2", "fatc-sim-pocket-3"])

    def test_the_whole_preparation_writes_the_copy(self):
        ini = self.machine("axis/axis.ini", "rehearse_inch.json")
        work = os.path.join(self.folder, "work")
        args = type("Args", (), {"ini": ini, "config": None, "tool_table": None, "workdir": work,
                                 "binary": sys.argv[1]})
        env, soak, filled = rehearse.prepare(args)
        self.assertEqual(filled, [])
        self.assertEqual(json.loads(env["FATC_CONFIG_SET"])["pockets"],
                         {"1": {"x": 0.5}, "2": {"x": 1.5}, "3": {"x": 2.5}})
        self.assertEqual(env["FATC_SOAK_TRUE_LENGTH"], "1.0")
        self.assertEqual(float(env["FATC_SOAK_LENGTH_TOLERANCE"]), 0.1 / 25.4)  # the inch default
        self.assertEqual(env["FATC_TOOL_TABLE"], os.path.join(self.folder, "sim.tbl"))
        self.assertEqual(soak, os.path.join(work, "soak"))
        self.assertTrue(os.path.exists(os.path.join(work, "rehearsal.ini")))


    def test_an_empty_rack_is_filled_from_the_table(self):
        config = {"pockets": {"2": {"x": 1, "tool": 0}, "1": {"x": 0, "tool": 0}}}
        pockets, filled = rehearse.rack_of(config, "c.json", [5, 3, 9], "t.tbl")
        self.assertEqual(pockets, {"1": {"x": 0, "tool": 3}, "2": {"x": 1, "tool": 5}})
        self.assertEqual(filled, ["pocket 1 T3", "pocket 2 T5"])
        self.assertEqual(config["pockets"]["1"]["tool"], 0)  # the user's config as it was

    def test_a_rack_partly_empty_stays_so(self):
        config = {"pockets": {"1": {"x": 0, "tool": 0}, "2": {"x": 1}}}
        self.assertEqual(rehearse.rack_of(config, "c.json", [2], "t.tbl"),
                         ({"1": {"x": 0, "tool": 0}, "2": {"x": 1}}, []))


class BadInput(Machine):
    def test_a_usage_mistake(self):
        err = io.StringIO()
        with contextlib.redirect_stderr(err), self.assertRaises(SystemExit) as end:
            rehearse.main(["--ini", "m.ini", "--changes", "many"])
        self.assertEqual(end.exception.code, 2)
        self.assertEqual(err.getvalue(), "fixed_atc_probe-rehearse: argument --changes: invalid int "
                                         "value: 'many'\n")

    def test_no_ini(self):
        line = self.refused("--ini", os.path.join(self.folder, "nowhere.ini"))
        self.assertIn("nowhere.ini: no such file", line)

    def test_no_section(self):
        ini = self.machine("axis/axis.ini", "rehearse_inch.json", section="")
        self.assertIn("machine.ini: no [FIXED_ATC_PROBE] section", self.refused("--ini", ini))

    def test_an_include(self):
        ini = self.machine("axis/axis.ini", "rehearse_inch.json",
                           edit=lambda text: "#INCLUDE more.inc\n" + text)
        self.assertIn("machine.ini line 1: #INCLUDE", self.refused("--ini", ini))

    def test_no_config(self):
        ini = self.machine("axis/axis.ini", "rehearse_inch.json")
        os.remove(os.path.join(self.folder, "fixed_atc_probe.json"))
        self.assertIn("fixed_atc_probe.json: no such file ([FIXED_ATC_PROBE]CONFIG of",
                      self.refused("--ini", ini))

    def test_units_that_differ(self):
        ini = self.machine("axis/axis.ini", "rehearse_mm.json")
        self.assertIn("units mm, but", self.refused("--ini", ini))

    def test_a_config_the_limits_cannot_hold(self):
        # The inch machine's Z ends at 0.12 inch; its config moved 10 inches down the table.
        config = config_of("rehearse_inch.json")
        config["pocket_default"]["y"] = -18.0
        ini = self.machine("axis/axis.ini", "rehearse_inch.json")
        rehearse.write(os.path.join(self.folder, "fixed_atc_probe.json"), json.dumps(config))
        line = self.refused("--ini", ini)
        self.assertIn("fixed_atc_probe.json does not fit", line)
        self.assertIn("machine.ini: M6 T1 from empty (pocket 1), step 2 (rapid to over pocket 1): "
                      "Y=-18.000 is outside the soft limits -10.000 .. 10.000 (the first problem `%s --check "
                      "--config " % sys.argv[1], line)

    def test_a_rack_tool_the_table_does_not_list(self):
        config = config_of("rehearse_inch.json")
        config["pockets"]["3"]["tool"] = 77
        ini = self.machine("axis/axis.ini", "rehearse_inch.json")
        rehearse.write(os.path.join(self.folder, "fixed_atc_probe.json"), json.dumps(config))
        self.assertIn("fixed_atc_probe.json: pocket 3 holds tool 77 at the first start, which "
                      "%s does not list" % os.path.join(self.folder, "sim.tbl"), self.refused("--ini", ini))

    def test_an_m6_that_moves(self):
        ini = self.machine("axis/axis.ini", "rehearse_inch.json",
                           edit=lambda text: text.replace("[EMCIO]", "[EMCIO]\nTOOL_CHANGE_QUILL_UP = 1"))
        self.assertIn("TOOL_CHANGE_QUILL_UP", self.refused("--ini", ini))

    def test_a_machine_of_other_kinematics(self):
        ini = self.machine("axis/axis.ini", "rehearse_inch.json",
                           edit=lambda text: text.replace("KINEMATICS = trivkins", "KINEMATICS = pumakins"))
        self.assertIn("[KINS]KINEMATICS pumakins: the rehearsal simulates trivkins machines only",
                      self.refused("--ini", ini))


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
