#!/usr/bin/env python3
"""Writes the hostile corpus: bad_configs/, bad_states/ and bad_inis/ next to
this script. Each file is one way to spoil a valid config.json, state file or
machine INI; hostile_test.cpp says what message each must give. Run it again
after changing a case here (the files are committed, the script is their
recipe). Megabyte-sized cases, FIFOs, /dev/zero and directories are made by
the test itself at run time, not kept here."""
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))

# The unit tests' sample config (sample_config.json) in mm, pocket 6 at the
# others' Z, with the feeds, the flush and the spindle's timeout given.
with open(os.path.join(HERE, "sample_config.json"), encoding="utf-8") as sample:
    CONFIG = {"units": "mm", **json.load(sample)}
del CONFIG["pockets"]["6"]["z"]
CONFIG.update({
    "pocket_feed": 600.0,
    "probe_seek_feed": 3000.0,
    "probe_latch_feed": 60.0,
    "probe_backoff": 0.5,
    "flush": {"pulses": 1, "pulse_seconds": 0.2, "pause_seconds": 0.2},
    "spindle_stop_timeout_seconds": 10.0,
})

STATE = {"version": 1, "spindle": 3, "uncertain": False, "in_pocket": [1, 2, 4, 5, 6],
         "lengths": {"1": 42.125, "3": 17.5}}

INI = """[EMC]
NML_FILE = linuxcnc.nml
[TRAJ]
LINEAR_UNITS = mm
[AXIS_X]
MIN_LIMIT = -10
MAX_LIMIT = 400
[AXIS_Y]
MIN_LIMIT = -10
MAX_LIMIT = 300
[AXIS_Z]
MIN_LIMIT = -120
MAX_LIMIT = 0
"""

EXECUTOR_INI = INI + """[FIXED_ATC_PROBE]
CONFIG = config.json
STATE = config.json.state
RETURN_TO_XY = 1
MACHINE_ON_SIGNAL = machine-on
STEP_READY_IN = 00
STEP_REQUEST_OUT = 00
PROBE_Z_OUT = 00
PROBE_RESULT_OUT = 01
EXECUTOR_CALL_OUT = 02
STEP_TIMEOUT = 30
"""


def text(value):
    return json.dumps(value, indent=2, ensure_ascii=False) + "\n"


def spoil(base, change):
    value = json.loads(json.dumps(base))
    change(value)
    return text(value)


def replace_once(source, old, new):
    assert old in source, old
    return source.replace(old, new, 1)


def write(folder, name, content):
    os.makedirs(os.path.join(HERE, folder), exist_ok=True)
    mode = "wb" if isinstance(content, bytes) else "w"
    with open(os.path.join(HERE, folder, name), mode) as out:
        out.write(content)


def configs():
    c = text(CONFIG)
    cases = {
        # numbers beyond a double, anywhere
        "overflow_chuck_seconds.json": replace_once(c, '"chuck_seconds": 0.5', '"chuck_seconds": 1e309'),
        "overflow_negative_pocket.json": replace_once(c, '"x": 150.0', '"x": -1e400'),
        "overflow_integer_digits.json": replace_once(c, '"pocket_feed": 600.0', '"pocket_feed": 1' + "0" * 400),
        # deep nesting
        "deep_arrays.json": '{"pockets": ' + "[" * 20000 + "]" * 20000 + "}",
        "deep_objects.json": '{"flush": ' + '{"a": ' * 5000 + "1" + "}" * 5000 + "}",
        "deep_unclosed.json": "[" * 30000,
        # duplicate keys
        "duplicate_top_key.json": replace_once(c, '"chuck_seconds": 0.5', '"chuck_seconds": 0.5,\n  "chuck_seconds": 5'),
        "duplicate_pocket.json": replace_once(c, '"2": {', '"2": {"x": 350.0},\n    "2": {'),
        "duplicate_axis.json": replace_once(c, '"x": 120.0', '"x": 120.0, "x": 9000'),
        # NUL byte
        "nul_byte.json": replace_once(c, '"units": "mm"', '"units": "mm\u0000"').encode(),
        "nul_after_object.json": (c + "\u0000garbage").encode(),
        # positive but meaningless, or overflowing
        "side_offset_tiny.json": spoil(CONFIG, lambda j: j.update(pocket_side_offset={"x": 0.0, "y": 1e-300})),
        "feed_denormal.json": spoil(CONFIG, lambda j: j.update(probe_latch_feed=5e-324)),
        "latch_above_seek.json": spoil(CONFIG, lambda j: j.update(probe_latch_feed=4000.0)),
        "timeout_overflows.json": spoil(CONFIG, lambda j: j.update(spindle_stop_timeout_seconds=1e10)),
        "chuck_seconds_huge.json": spoil(CONFIG, lambda j: j.update(chuck_seconds=1e300)),
        "flush_pulse_huge.json": spoil(CONFIG, lambda j: j["flush"].update(pulse_seconds=1e20)),
        "flush_pulses_huge.json": spoil(CONFIG, lambda j: j["flush"].update(pulses=1e9)),
        "coordinate_huge.json": spoil(CONFIG, lambda j: j["safe"].update(z=1e308)),
        "pocket_plus_offset_overflows.json": spoil(CONFIG, lambda j: (j["pockets"]["6"].update(z=1.7e308),
                                                                    j.update(pocket_above_clearance_offset_z=1.7e308))),
        "clearance_offset_huge.json": spoil(CONFIG, lambda j: j.update(pocket_above_clearance_offset_z=1e308)),
        "tolerance_tiny.json": spoil(CONFIG, lambda j: j.update(probe_check_tolerance=1e-300)),
        "margin_huge.json": spoil(CONFIG, lambda j: j.update(rack_keepout_margin=1e300)),
        # a keep-out too narrow to catch a move through a holder
        "margin_zero.json": spoil(CONFIG, lambda j: j.update(rack_keepout_margin=0)),
        "margin_tiny.json": spoil(CONFIG, lambda j: j.update(rack_keepout_margin=1e-9)),
        "margin_default_below_floor.json": spoil(CONFIG, lambda j: j.update(
            pocket_side_offset={"x": 0.0, "y": 1.5})),
        "retract_denormal.json": spoil(CONFIG, lambda j: j.update(probe_retract_offset_z=5e-324)),
        "backoff_huge.json": spoil(CONFIG, lambda j: j.update(probe_backoff=1e6)),
        "length_offset_huge.json": spoil(CONFIG, lambda j: j.update(probe_length_compensation_offset=-1e200)),
        "side_component_huge.json": spoil(CONFIG, lambda j: j["pocket_side_offset"].update(x=1e300)),
        "integer_beyond_64_bits.json": replace_once(c, '"chuck_seconds": 0.5', '"chuck_seconds": 123456789012345678901234567890'),
        "too_many_pockets.json": spoil(CONFIG, lambda j: j.update(
            pockets={str(t): {"x": 50.0 * t} for t in range(1, 202)})),
        # control characters, escape sequences, direction overrides echoed back
        "escape_sequence_key.json": spoil(CONFIG, lambda j: j.update({"\u001b[31mred\u001b[0m": 1})),
        "escape_sequence_value.json": spoil(CONFIG, lambda j: j.update(units="\u001b]0;pwned\u0007mm")),
        "c1_control_value.json": spoil(CONFIG, lambda j: j.update(units="\u009b31mmm")),
        "bidi_override_value.json": spoil(CONFIG, lambda j: j.update(units="\u202emm")),
        "bidi_isolate_key.json": spoil(CONFIG, lambda j: j.update({"\u2067safe\u2069": 1})),
        "tag_characters_value.json": spoil(CONFIG, lambda j: j.update(units="mm\U000e0041\U000e007f")),
        "soft_hyphen_value.json": spoil(CONFIG, lambda j: j.update(probe_after_change="mea\u00adsure")),
        "zero_width_key.json": spoil(CONFIG, lambda j: j.update({"chuck_seconds\u200b": 0.5})),
        "deep_duplicate_long_keys.json": "".join('{"%s%02d": ' % ("k" * 58, n) for n in range(60))
                                         + '{"x": 1, "x": 2}' + "}" * 60,
        "newline_in_pocket_key.json": spoil(CONFIG, lambda j: j["pockets"].update({"1\n2": {"x": 400.0}})),
        "long_string_value.json": spoil(CONFIG, lambda j: j.update(probe_after_change="x" * 20000)),
        "long_unterminated_string.json": '{"units": "' + "m" * 20000,
        "many_unknown_keys.json": spoil(CONFIG, lambda j: j.update({"key%d" % i: i for i in range(500)})),
        # plain syntax and type problems
        "empty.json": "",
        "top_level_array.json": "[1, 2]\n",
        "top_level_string.json": '"config"\n',
        "truncated.json": c[: len(c) // 2],
        "trailing_garbage.json": c + "x\n",
        "comment.json": "// my mill\n" + c,
        "invalid_utf8.json": replace_once(c, '"units": "mm"', '"units": "m\udcffm"').encode("utf-8", "surrogateescape"),
        "lone_surrogate.json": replace_once(c, '"units": "mm"', '"units": "\\ud800"'),
        "nan_literal.json": replace_once(c, '"chuck_seconds": 0.5', '"chuck_seconds": NaN'),
        "infinity_literal.json": replace_once(c, '"chuck_seconds": 0.5', '"chuck_seconds": -Infinity'),
        "tool_number_too_big.json": spoil(CONFIG, lambda j: j["pockets"].update({"99999999999": {"x": 400.0}})),
        "units_number.json": spoil(CONFIG, lambda j: j.update(units=25.4)),
        "pockets_string.json": spoil(CONFIG, lambda j: j.update(pockets="1,2,3")),
        "pocket_default_array.json": spoil(CONFIG, lambda j: j.update(pocket_default=[])),
        # the optional sensors and their timeout, the probe window
        "sensors_not_object.json": spoil(CONFIG, lambda j: j.update(sensors="all")),
        "sensors_unknown_key.json": spoil(CONFIG, lambda j: j.update(sensors={"toolpresent": True})),
        "sensors_not_bool.json": spoil(CONFIG, lambda j: j.update(sensors={"air_pressure": "yes"})),
        "sensors_null.json": spoil(CONFIG, lambda j: j.update(sensors={"tool_present": None})),
        "sensors_pocket_missing.json": spoil(CONFIG, lambda j: j.update(sensors={"pocket_occupancy": [1, 9]})),
        "sensors_pocket_twice.json": spoil(CONFIG, lambda j: j.update(sensors={"pocket_occupancy": [2, 2]})),
        "sensors_pocket_negative.json": spoil(CONFIG, lambda j: j.update(sensors={"pocket_occupancy": [-3]})),
        "sensors_pocket_string.json": spoil(CONFIG, lambda j: j.update(sensors={"pocket_occupancy": "all"})),
        "sensor_timeout_negative.json": spoil(CONFIG, lambda j: j.update(sensor_timeout_seconds=-1)),
        "sensor_timeout_huge.json": spoil(CONFIG, lambda j: j.update(sensor_timeout_seconds=1e10)),
        "sensor_timeout_string.json": spoil(CONFIG, lambda j: j.update(sensor_timeout_seconds="1s")),
        "probe_window_zero.json": spoil(CONFIG, lambda j: j.update(probe_window=0)),
        "probe_window_below_tolerance.json": spoil(CONFIG, lambda j: j.update(probe_window=0.05, probe_after_change="check")),
        # the touch-off sensor in a pocket's column, with no probing after a change
        "sensor_in_rack.json": spoil(CONFIG, lambda j: j.update(
            probe_after_change="off", probe_limit={"x": 152.0, "y": 24.0, "z": -90.0})),
    }
    for name, content in cases.items():
        write("bad_configs", name, content)


def states():
    s = text(STATE)
    cases = {
        "overflow_length.json": replace_once(s, '"1": 42.125', '"1": 1e309'),
        "overflow_spindle.json": replace_once(s, '"spindle": 3', '"spindle": -1e400'),
        "deep_nesting.json": '{"version": 1, "lengths": ' + "[" * 20000 + "]" * 20000 + "}",
        "duplicate_spindle.json": replace_once(s, '"spindle": 3', '"spindle": 3,\n  "spindle": 0'),
        "duplicate_length.json": replace_once(s, '"3": 17.5', '"3": 17.5, "3": 99.0'),
        "nul_byte.json": replace_once(s, '"uncertain": false', '"uncertain": false\u0000').encode(),
        "length_huge.json": spoil(STATE, lambda j: j["lengths"].update({"1": 1e200})),
        "spindle_fraction.json": spoil(STATE, lambda j: j.update(spindle=2.5)),
        "spindle_beyond_64_bits.json": replace_once(s, '"spindle": 3', '"spindle": 18446744073709551615'),
        "in_pocket_object.json": spoil(STATE, lambda j: j.update(in_pocket={})),
        "in_progress_escape.json": spoil(STATE, lambda j: j.update(
            in_progress={"sequence": "M6 T4", "step": "\u001b[2Jreturning", "pocket": 3})),
        "in_progress_c1.json": spoil(STATE, lambda j: j.update(
            in_progress={"sequence": "M6 T4", "step": "\u009b2Jreturning", "pocket": 3})),
        "in_progress_long.json": spoil(STATE, lambda j: j.update(
            in_progress={"sequence": "M6 " * 3000, "step": "returning", "pocket": 3})),
        "in_progress_text.json": spoil(STATE, lambda j: j.update(in_progress="M6 T4")),
        "in_progress_unknown_key.json": spoil(STATE, lambda j: j.update(
            in_progress={"sequence": "M6 T4", "step": "returning", "pocket": 3, "tool": 4})),
        "in_progress_bad_pocket.json": spoil(STATE, lambda j: j.update(
            in_progress={"sequence": "M6 T4", "step": "returning", "pocket": -1})),
        "in_progress_no_step.json": spoil(STATE, lambda j: j.update(
            in_progress={"sequence": "M6 T4", "pocket": 3})),
        "escape_sequence_key.json": spoil(STATE, lambda j: j.update({"\u001b]0;x\u0007": 1})),
        "version_text.json": spoil(STATE, lambda j: j.update(version="1")),
        "pocket_not_in_config.json": spoil(STATE, lambda j: j.update(in_pocket=[1, 2, 99])),
        "in_progress_pocket_not_in_config.json": spoil(STATE, lambda j: j.update(
            uncertain=True, in_progress={"sequence": "M6 T4", "step": "returning tool 3 to pocket 99",
                                         "pocket": 99})),
        "in_progress_bidi.json": spoil(STATE, lambda j: j.update(
            in_progress={"sequence": "M6 T4", "step": "returning tool 3 \u202eto pocket 3", "pocket": 3})),
        "in_progress_tag.json": spoil(STATE, lambda j: j.update(
            in_progress={"sequence": "M6 T4\U000e0001", "step": "returning", "pocket": 3})),
        "length_key_padded.json": spoil(STATE, lambda j: j["lengths"].update({"01": 3.0})),
        "empty.json": "",
        "torn_write.json": s[: len(s) * 2 // 3],
        "top_level_array.json": "[3]\n",
    }
    for name, content in cases.items():
        write("bad_states", name, content)


def inis():
    i = INI
    cases = {
        "min_nan.ini": replace_once(i, "MIN_LIMIT = -10\nMAX_LIMIT = 400", "MIN_LIMIT = nan\nMAX_LIMIT = 400"),
        "max_inf.ini": replace_once(i, "MAX_LIMIT = 300", "MAX_LIMIT = inf"),
        "comma_decimal.ini": replace_once(i, "MAX_LIMIT = 400", "MAX_LIMIT = 0,5"),
        "unit_suffix.ini": replace_once(i, "MAX_LIMIT = 400", "MAX_LIMIT = 400 mm"),
        "trailing_junk.ini": replace_once(i, "MAX_LIMIT = 400", "MAX_LIMIT = 0abc"),
        "inline_comment.ini": replace_once(i, "MAX_LIMIT = 0\n", "MAX_LIMIT = 0 # top of travel\n"),
        "furlong.ini": replace_once(i, "LINEAR_UNITS = mm", "LINEAR_UNITS = furlong"),
        "min_above_max.ini": replace_once(i, "MIN_LIMIT = -120\nMAX_LIMIT = 0", "MIN_LIMIT = 0\nMAX_LIMIT = -50"),
        "no_linear_units.ini": replace_once(i, "LINEAR_UNITS = mm\n", ""),
        "no_axis_z.ini": i[: i.index("[AXIS_Z]")],
        "nul_byte.ini": replace_once(i, "MAX_LIMIT = 300", "MAX_LIMIT = 3\u000000").encode(),
        "lone_carriage_return.ini": replace_once(i, "MAX_LIMIT = 300\n", "MAX_LIMIT = 300\rMAX_LIMIT = 9\n"),
        "overflow.ini": replace_once(i, "MIN_LIMIT = -120", "MIN_LIMIT = -1e999"),
        "beyond_no_limit.ini": replace_once(i, "MIN_LIMIT = -120", "MIN_LIMIT = -1e200"),
        "escape_sequence_value.ini": replace_once(i, "MAX_LIMIT = 400", "MAX_LIMIT = \u001b[31m400"),
        "c1_control_value.ini": replace_once(i, "MAX_LIMIT = 400", "MAX_LIMIT = \u009b31m400"),
        "empty.ini": "",
        "linear_units_zero.ini": replace_once(i, "LINEAR_UNITS = mm", "LINEAR_UNITS = 0"),
        "linear_units_nan.ini": replace_once(i, "LINEAR_UNITS = mm", "LINEAR_UNITS = nan"),
        "linear_units_with_junk.ini": replace_once(i, "LINEAR_UNITS = mm", "LINEAR_UNITS = 1.0 mm"),
        "empty_value.ini": replace_once(i, "MAX_LIMIT = 300", "MAX_LIMIT ="),
        # [FIXED_ATC_PROBE] values echoed back
        "return_to_xy_bidi.ini": replace_once(EXECUTOR_INI, "RETURN_TO_XY = 1", "RETURN_TO_XY = \u202e1"),
        "step_timeout_soft_hyphen.ini": replace_once(EXECUTOR_INI, "STEP_TIMEOUT = 30", "STEP_TIMEOUT = 3\u00ad0"),
        "analog_out_twice_escape.ini": replace_once(
            replace_once(EXECUTOR_INI, "PROBE_Z_OUT = 00", "PROBE_Z_OUT = \u001b[8m"),
            "PROBE_RESULT_OUT = 01", "PROBE_RESULT_OUT = \u001b[8m"),
        # the INI as the linuxcnc script expands its #INCLUDE lines
        "include_missing.ini": i[: i.index("[AXIS_X]")] + "#INCLUDE gone_axes.inc\n",
        "include_nested.ini": i[: i.index("[AXIS_X]")] + "#INCLUDE nested_axes.inc\n",
        "include_shell.ini": i[: i.index("[AXIS_X]")] + "#INCLUDE $(cat axes.inc)\n",
        "include_no_line_end.ini": i[: i.index("[AXIS_X]")] + "#INCLUDE axes_no_line_end.inc\n",
        "include_itself.ini": "#INCLUDE include_itself.ini\n" + i,
        "include_indented.ini": i[: i.index("[AXIS_X]")] + "  #INCLUDE axes.inc\n",
        "include_dev_zero.ini": i[: i.index("[AXIS_X]")] + "#INCLUDE /dev/zero\n",
        # LinuxCNC's own M6 moving after the changer's change
        "tool_change_position.ini": i + "[EMCIO]\nTOOL_CHANGE_POSITION = 0 0 0\n",
    }
    for name, content in cases.items():
        write("bad_inis", name, content)
    # the files those #INCLUDE lines name
    axes = i[i.index("[AXIS_X]"):]
    write("bad_inis", "axes.inc", axes)
    write("bad_inis", "nested_axes.inc", "#INCLUDE axes.inc\n")
    write("bad_inis", "axes_no_line_end.inc", axes.rstrip("\n"))


if __name__ == "__main__":
    configs()
    states()
    inis()
