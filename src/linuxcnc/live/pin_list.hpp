#pragma once

// The component's HAL pins, declared once. create_pins makes them from this
// list; the pin references (the man page's PINS, docs/pins.md) and
// tests/integration/pins/pins.golden are generated from it (fatc_docs), and a
// test fails when a generated file is stale.

#include <initializer_list>
#include <string>
#include <vector>

#include "hal_pins_detail.hpp"

namespace fatc::linuxcnc {

/// The pocket sensor: one pin for each pocket of config.json.
struct PerPocket {};
/// `rack-keepout-N-...`: one pin for each box the rack guard holds.
struct PerBox {
  hal_float_t* (HalPins::*member)[kGuardBoxes];
};

/// A sensor's line in the reference: "sensor (`sensors.zero_speed`): the spindle's ...".
inline std::string sensor_doc(const SensorWords& words) {
  return "sensor (`" + std::string(words.key) + "`): " + words.says + words.pin_note;
}

struct PinDeclaration {
  enum class Type { bit, s32, real, sensor, bit_per_pocket, real_per_box };
  PinDeclaration(const char* name, hal_bit_t* HalPins::*member, hal_pin_dir_t dir, const char* doc,
                 int start = 0)
      : name(name), type(Type::bit), dir(dir), doc(doc), start(start), bit(member) {}
  PinDeclaration(const char* name, hal_s32_t* HalPins::*member, hal_pin_dir_t dir, const char* doc,
                 int start = 0)
      : name(name), type(Type::s32), dir(dir), doc(doc), start(start), s32(member) {}
  PinDeclaration(const char* name, hal_float_t* HalPins::*member, hal_pin_dir_t dir,
                 const char* doc, int start = 0)
      : name(name), type(Type::real), dir(dir), doc(doc), start(start), real(member) {}
  explicit PinDeclaration(const SensorDeclaration& declared)
      : name(declared.words.pin),
        type(Type::sensor),
        dir(HAL_IN),
        doc(sensor_doc(declared.words)),
        sensor(declared.sensor) {}
  explicit PinDeclaration(PerPocket)
      : name(kPocketSensor.pin),
        type(Type::bit_per_pocket),
        dir(HAL_IN),
        doc(sensor_doc(kPocketSensor)) {}
  PinDeclaration(const char* name, PerBox boxes, hal_pin_dir_t dir, const char* doc)
      : name(name), type(Type::real_per_box), dir(dir), doc(doc), per_box(boxes.member) {}

  const char* name;  ///< after `fixed_atc_probe.`
  Type type;
  hal_pin_dir_t dir;
  /// One line for the reference; `backticks` name a pin, a key or a signal.
  std::string doc;
  int start = 0;  ///< its value from the start, before anything writes it
  Sensor sensor = Sensor{};  ///< a sensor's: which (HalPins::sensors)
  hal_bit_t* HalPins::*bit = nullptr;
  hal_s32_t* HalPins::*s32 = nullptr;
  hal_float_t* HalPins::*real = nullptr;
  hal_float_t* (HalPins::*per_box)[kGuardBoxes] = nullptr;
};

/// HAL's word for a pin's type: bit, s32 or float.
const char* type_name(const PinDeclaration& pin);
/// in or out.
const char* dir_name(const PinDeclaration& pin);
/// A per-box pin's name for box `box`: rack-keepout-N-x-min -> rack-keepout-2-x-min.
std::string box_pin_name(const PinDeclaration& pin, std::size_t box);

/// The pins of the sensors whose keys lie in the config object `object`, in
/// the order of kSensors.
inline std::vector<PinDeclaration> sensor_pins(const char* object) {
  std::vector<PinDeclaration> pins;
  for (const SensorDeclaration& sensor : kSensors) {
    if (keyed_in(sensor, object)) pins.emplace_back(sensor);
  }
  return pins;
}

/// `parts` one after another.
inline std::vector<PinDeclaration> joined(
    std::initializer_list<std::vector<PinDeclaration>> parts) {
  std::vector<PinDeclaration> all;
  for (const auto& part : parts) all.insert(all.end(), part.begin(), part.end());
  return all;
}

// clang-format off
/// Every pin, in the order of the references.
inline const std::vector<PinDeclaration> kPins = joined({{
  // iocontrol's tool handshake, mirrored.
  {"number", &HalPins::number, HAL_IN, "tool being prepared (`iocontrol.0.tool-prep-number`)"},
  {"tool-prepare", &HalPins::tool_prepare, HAL_IN, "`iocontrol.0.tool-prepare`"},
  {"prepared", &HalPins::prepared, HAL_OUT, "`iocontrol.0.tool-prepared`; follows `tool-prepare`"},
  {"tool-change", &HalPins::tool_change, HAL_IN, "`iocontrol.0.tool-change`"},
  {"changed", &HalPins::changed, HAL_OUT,
   "`iocontrol.0.tool-changed`; high until `tool-change` drops, only when idle"},
  {"linuxcnc-tool", &HalPins::linuxcnc_tool, HAL_IN,
   "`iocontrol.0.tool-number`: LinuxCNC's tool in the spindle; brought in line with the "
   "changer's (M61) once idle after a start or a cleared fault"},
  // The rack.
  {"chuck", &HalPins::chuck, HAL_OUT,
   "true opens the chuck; the HAL snippet passes it through `fatc-chuck-guard` to the signal "
   "`fatc-chuck`, which the drawbar valve takes"},
  {"chuck-held", &HalPins::chuck_held, HAL_OUT,
   "a G-code release (or the I/O check) holds the chuck open until its clamp; the snippet nets it through "
   "`fatc-rack-guard` to `motion.feed-inhibit` and through `fatc-spindle-guard` to "
   "`spindle.0.inhibit` (the chuck atoms)"},
  {"heartbeat", &HalPins::heartbeat, HAL_OUT,
   "toggles every poll; `fatc-chuck-guard` closes the chuck when it stops for 0.5 s"},
  {"probe-in-spindle", &HalPins::probe_in_spindle, HAL_OUT,
   "a touch probe (config.json's `tools`) is in the spindle, or may be after a cut-off "
   "sequence; the snippet nets it to `fatc-spindle-guard`, which holds the spindle still and "
   "gives `motion.probe-input` the probe's input"},
  {"changer-spindle", &HalPins::changer_spindle, HAL_OUT,
   "the changer turns the spindle for the step under way (`chuck.kind` \"collet_nut\": a nut "
   "screwed off or on over the served pocket): to `fatc-spindle-guard.changer-spindle`, which "
   "otherwise holds the spindle still while the changer is busy"},
  {"spindle-refused", &HalPins::spindle_refused, HAL_IN,
   "`fatc-spindle-guard.refused`: M3 or M4 met the held spindle; a rising edge aborts what "
   "task runs and says why"},
  {"probe", &HalPins::probe, HAL_IN,
   "the touch-off sensor, netted together with `motion.probe-input` (G38.3 reads that one), "
   "or with `fatc-spindle-guard.sensor` where a touch probe shares it; the executor does not "
   "probe when it is already on"},
  {"spindle-stopped", &HalPins::spindle_stopped, HAL_IN,
   "LinuxCNC has the spindle off (the snippet nets `not spindle.0.on`; a drive's own stopped "
   "signal says when it stands); M6 moves only at safe Z until it (and `zero-speed` where "
   "wired) says so, then waits for it up to `spindle_stop_timeout_seconds`"},
  // The optional sensors (core/config/sensor_list.hpp): read only where
  // config.json's `sensors` says they are wired.
}, sensor_pins("sensors"), {
  PinDeclaration{PerPocket{}},
  // What the rack may need around it: each driven only where config.json names it.
  {"rack-cover-open", &HalPins::rack_cover_open, HAL_OUT,
   "`rack_cover`: true opens the rack's dust cover (before the first move into the rack; "
   "closed when the changer is done with it; left as it is at a fault)"},
}, sensor_pins("rack_cover"), {
  {"air-blast", &HalPins::air_blast, HAL_OUT,
   "`air_blast`: on while the chuck is open at a pocket with the spindle empty (never at "
   "`loading`); off at a fault"},
}, sensor_pins("chuck"), {
  // The machine, and the operator's word after a fault.
  {"machine-on", &HalPins::machine_on, HAL_IN,
   "machine on and out of estop (`motion.motion-enabled`)"},
  {"all-homed", &HalPins::all_homed, HAL_IN, "every joint homed (`motion.is-all-homed`)"},
  {"clear-fault", &HalPins::clear_fault, HAL_IN,
   "rising edge: the operator checked the spindle and the rack; clears a fault with "
   "`confirm-tool` and `confirm-pocket`; nothing moves"},
  {"confirm-tool", &HalPins::confirm_tool, HAL_IN,
   "what the spindle holds, as the operator found it (0 empty); -1 (the default): LinuxCNC's "
   "tool", -1},
  {"confirm-pocket", &HalPins::confirm_pocket, HAL_IN,
   "the pocket of `cut-off-pocket` holds its tool: 1 yes, 0 no, -1 (the default) not said", -1},
  {"cut-off-pocket", &HalPins::cut_off_pocket, HAL_OUT,
   "in fault after a sequence was cut off: the pocket it involved (0 none)"},
  // What the changer is doing.
  {"state", &HalPins::state, HAL_OUT,
   "0 not ready, 1 idle, 2 changing, 3 loading, 4 unloading, 5 fault, 6 measuring (measure "
   "all), 7 verifying (a dry run through a pocket), 8 chuck (a chuck atom), 9 air run (a "
   "sequence flown above the rack), 10 touching (the probe touches the rack)"},
  {"ready", &HalPins::ready, HAL_OUT,
   "idle, able to change tools (not while a release holds the chuck open)"},
  {"busy", &HalPins::busy, HAL_OUT, "a sequence runs"},
  {"touching", &HalPins::touching, HAL_OUT,
   "the probe touches the rack (`state` 10): to fatc-spindle-guard.touching, which gives motion "
   "the probe's input then, not the touch-off sensor's"},
  {"fault", &HalPins::fault, HAL_OUT, "in fault: M6 is refused until `clear-fault`"},
  {"tool-in-spindle", &HalPins::tool_in_spindle, HAL_OUT,
   "what the changer knows is in the spindle"},
  // The step executor's handshake.
  {"step-request", &HalPins::step_request, HAL_IN,
   "executor: asks for its next step (`motion.digital-out-NN`)"},
  {"executor-call", &HalPins::executor_call, HAL_IN,
   "executor: how it was called, 1 M6, 2 an operator flow over MDI, 3 a chuck release, 4 a "
   "chuck clamp; read at its first request (`motion.analog-out-NN`)"},
  {"abort", &HalPins::abort, HAL_IN,
   "rising edge aborts a running sequence (aborts of the program are seen without it)"},
  {"step-ready", &HalPins::step_ready, HAL_OUT,
   "executor: a step is on the step pins (`motion.digital-in-NN`)"},
  {"step-kind", &HalPins::step_kind, HAL_OUT,
   "0 none, 1 rapid, 2 feed, 3 probe, 4 set length, 5 set tool, 6 wait, 7 done, 8 fail"},
  {"step-axes", &HalPins::step_axes, HAL_OUT, "3 XY, 4 Z, 7 XYZ"},
  {"step-x", &HalPins::step_x, HAL_OUT, "machine X of the move"},
  {"step-y", &HalPins::step_y, HAL_OUT, "machine Y of the move"},
  {"step-z", &HalPins::step_z, HAL_OUT, "machine Z of the move"},
  {"step-feed", &HalPins::step_feed, HAL_OUT, "units per minute"},
  {"step-tool", &HalPins::step_tool, HAL_OUT, "tool of set-length, set-tool and done"},
  {"step-value", &HalPins::step_value, HAL_OUT, "length of set-length"},
  {"step-via", &HalPins::step_via, HAL_OUT,
   "before a rapid's own move (`blend_tolerance`): 0 nothing, 1 up to `step-via-z`, 2 across "
   "at it to `step-via-x` `step-via-y`, 3 both; their corners rounded within `step-blend`"},
  {"step-via-x", &HalPins::step_via_x, HAL_OUT, "machine X the run crosses to"},
  {"step-via-y", &HalPins::step_via_y, HAL_OUT, "machine Y the run crosses to"},
  {"step-via-z", &HalPins::step_via_z, HAL_OUT, "machine Z the run goes up to (`step-via` 1, 3): safe Z"},
  {"step-blend", &HalPins::step_blend, HAL_OUT,
   "how far the run's corners may be cut (G64 P), the config's units: `blend_tolerance`, or safe Z's "
   "room over the columns divided by 3.5 where a way up or down is in or beside one"},
  {"units-inch", &HalPins::units_inch, HAL_OUT,
   "the config is in inches (the executor uses G20)"},
  {"return-to-xy", &HalPins::return_to_xy, HAL_IN,
   "after M6, go back over the XY where it was called"},
  {"probe-z", &HalPins::probe_z, HAL_IN,
   "executor: the machine coordinate where the probe move stopped, on the step's axis (Z on "
   "the sensor; X, Y or Z touching a rack feature) (`motion.analog-out-NN`)"},
  {"probe-result", &HalPins::probe_result, HAL_IN,
   "executor: 1 touched, 0 missed, -1 the probe input already tripped (`motion.analog-out-NN`)"},
  // The operator's buttons, from the GUI panel or any HAL source.
  {"tool-number", &HalPins::tool_number, HAL_IN, "the tool the operator buttons are about"},
  {"load", &HalPins::load, HAL_IN,
   "rising edge: load `tool-number` by hand, measure it, put it in its pocket"},
  {"unload", &HalPins::unload, HAL_IN,
   "rising edge: fetch `tool-number` and hand it to the operator at `loading`"},
  {"pocket-number", &HalPins::pocket_number, HAL_IN,
   "the pocket `load` puts `tool-number` in; 0: the changer chooses (the tool's own pocket, its "
   "first-start pocket, else the nearest free one). Also the pocket `teach-pocket` teaches and "
   "`verify-pocket` drives through"},
  {"teach-pocket", &HalPins::teach_pocket, HAL_IN,
   "rising edge: the machine position becomes pocket `pocket-number`'s in config.json, only "
   "while idle"},
  {"teach-loading", &HalPins::teach_loading, HAL_IN,
   "rising edge: the machine position becomes `loading` in config.json, only while idle"},
  {"teach-safe", &HalPins::teach_safe, HAL_IN,
   "rising edge: the machine position becomes `safe` in config.json, only while idle"},
  {"teach-sensor", &HalPins::teach_sensor, HAL_IN,
   "rising edge: the machine XY becomes the touch-off sensor's in config.json, only while idle"},
  {"verify-pocket", &HalPins::verify_pocket, HAL_IN,
   "rising edge: a dry run through the approach of the empty pocket `pocket-number`, held at "
   "each waypoint until `continue`; accepted when `load` would be"},
  // A change in the air: the sequence flown above the rack, nothing taken or recorded.
  {"air-run-change", &HalPins::air_run_change, HAL_IN,
   "rising edge: M6 T`tool-number` flown in the air, as if the spindle held `air-from-tool`; "
   "every move over the rack no lower than `air-height` above its top, at `air-feed`, the chuck "
   "closed, nothing measured or recorded (`state` 9); accepted when `load` would be"},
  {"air-run-load", &HalPins::air_run_load, HAL_IN,
   "rising edge: the load of `tool-number` into `pocket-number` flown in the air"},
  {"air-run-unload", &HalPins::air_run_unload, HAL_IN,
   "rising edge: the unload of `tool-number` flown in the air"},
  {"air-run-verify", &HalPins::air_run_verify, HAL_IN,
   "rising edge: the verify of pocket `pocket-number` flown in the air, without its stops"},
  {"air-from-tool", &HalPins::air_from_tool, HAL_IN,
   "the tool an air-run M6 starts from (0 an empty spindle); -1 (the default): the one the "
   "spindle holds", -1},
  {"air-height", &HalPins::air_height, HAL_IN,
   "how far above the rack's top (its forks and the keep-out above them) an air run flies, "
   "the config's units"},
  {"air-feed", &HalPins::air_feed, HAL_IN,
   "the feed of every move of an air run, units per minute; 0 (the default): the config's "
   "`verify_feed`, else `pocket_feed`"},
  // The rack found by touch, with the probe in the spindle (rack_touch).
  {"touch-pockets", &HalPins::touch_pockets, HAL_IN,
   "rising edge: the probe touches pocket `pocket-number`'s feature (0: every pocket it can), "
   "shows what it found beside config.json and writes it on `continue` (`state` 10)"},
  {"teach-datum", &HalPins::teach_datum, HAL_IN,
   "rising edge: the probe touches the rack datum; on `continue` its position becomes the taught "
   "one in config.json"},
  {"check-datum", &HalPins::check_datum, HAL_IN,
   "rising edge: the drift check: the probe touches the rack datum and compares; beyond "
   "`rack_touch.drift_tolerance` M6 is refused until `teach-datum` or `clear-datum-drift`"},
  {"clear-datum-drift", &HalPins::clear_datum_drift, HAL_IN,
   "rising edge: the operator checked the rack: M6 is allowed again, the changes are counted "
   "from 0; the pockets keep their positions"},
  {"pocket-served", &HalPins::pocket_served, HAL_OUT,
   "the pocket the sequence under way serves (0 none)"},
  {"measure-all", &HalPins::measure_all, HAL_IN,
   "rising edge: fetch, measure and put back each tool `measure-which` names, one after "
   "another; accepted when `load` would be"},
  {"measure-which", &HalPins::measure_which, HAL_IN,
   "the tools `measure-all` measures: 0 every tool in the rack, 1 those never measured, 2 those "
   "of the program loaded in LinuxCNC (the others are skipped with a message)"},
  {"batch-done", &HalPins::batch_done, HAL_OUT,
   "measure all's progress: tools measured so far; `state` is 6 meanwhile"},
  {"batch-total", &HalPins::batch_total, HAL_OUT,
   "measure all's progress: of how many tools (0 when no batch runs)"},
  {"continue", &HalPins::continue_, HAL_IN,
   "rising edge: the operator has done what the prompt asked"},
  {"cancel", &HalPins::cancel, HAL_IN,
   "rising edge: stop at this prompt; the message says where the tools are. During measure "
   "all: stop once the tool under way is back in its pocket (during its probe the probe stops "
   "too)"},
  {"waiting-for-operator", &HalPins::waiting_for_operator, HAL_OUT,
   "a prompt waits for Continue or Cancel: in the load and unload flows once the executor has "
   "ended its run (jogging and the GUI are free); inside M6 (manual tools) while the program "
   "holds"},
  {"step-by-step", &HalPins::step_by_step, HAL_IN,
   "level, taken at the start of each sequence: each move and each chuck action of it waits "
   "for `continue` before it goes out (`waiting-for-operator` high, the prompt naming the step, "
   "its target and feed); `cancel` there aborts the sequence"},
  {"last-length", &HalPins::last_length, HAL_OUT, "the last tool length measured"},
  // What a panel needs to show and to enable only the buttons that can act.
  {"awaiting", &HalPins::awaiting, HAL_OUT,
   "what the changer waits for: 0 nothing, 1 motion, 2 probe, 3 timer, 4 spindle, 5 operator, "
   "6 a sensor"},
  {"step-number", &HalPins::step_number, HAL_OUT,
   "the step of the sequence under way, numbered as `--plan` prints it (0 between sequences)"},
  {"accepting", &HalPins::accepting, HAL_OUT,
   "`load` and `unload` would be accepted now (idle, no program or MDI running)"},
  {"can-cancel", &HalPins::can_cancel, HAL_OUT,
   "`cancel` would act now: a prompt, a probe of the load flow, or measure all"},
  // The rack kept out of every motion by the realtime guard `fatc-rack-guard`.
  {"rack-keepout", &HalPins::rack_keepout, HAL_OUT,
   "the keep-out of every motion: 0 off (`rack_keepout_all_motion` false), 1 armed, 2 lifted "
   "for the changer's own moves, 3 lifted by `rack-keepout-lift`, 4 not armed: the machine is "
   "not on and homed, or LinuxCNC's status is not read", 4},
  {"rack-keepout-lift", &HalPins::rack_keepout_lift, HAL_IN,
   "true lifts the keep-out while the operator jogs into the rack to teach a pocket"},
  {"rack-keepout-enable", &HalPins::rack_keepout_enable, HAL_OUT,
   "to `fatc-rack-guard.enable`: the keep-out is armed"},
  {"rack-keepout-tool-length", &HalPins::rack_keepout_tool_length, HAL_OUT,
   "to `fatc-rack-guard.tool-length`: the length of LinuxCNC's tool in the spindle in its tool "
   "table, machine units, whatever offset is in force"},
  {"rack-keepout-boxes", &HalPins::rack_keepout_boxes, HAL_OUT,
   "to `fatc-rack-guard.boxes`: how many boxes the rack's volume has"},
  {"rack-keepout-N-x-min", PerBox{&HalPins::keepout_x_min}, HAL_OUT,
   "to `fatc-rack-guard.box.N.x-min`, N 0 to 3: box N of the rack's volume, machine units"},
  {"rack-keepout-N-x-max", PerBox{&HalPins::keepout_x_max}, HAL_OUT,
   "to `fatc-rack-guard.box.N.x-max`"},
  {"rack-keepout-N-y-min", PerBox{&HalPins::keepout_y_min}, HAL_OUT,
   "to `fatc-rack-guard.box.N.y-min`"},
  {"rack-keepout-N-y-max", PerBox{&HalPins::keepout_y_max}, HAL_OUT,
   "to `fatc-rack-guard.box.N.y-max`"},
  {"rack-keepout-N-z-max", PerBox{&HalPins::keepout_z_max}, HAL_OUT,
   "to `fatc-rack-guard.box.N.z-max`: its top for an empty spindle (the guard adds the tool's "
   "length)"},
  {"rack-keepout-trips", &HalPins::rack_keepout_trips, HAL_IN,
   "from `fatc-rack-guard.trips`: it counts the motions held before they entered the rack; at "
   "each, the component aborts what task runs and says what, where and with which tool"},
  {"rack-keepout-box", &HalPins::rack_keepout_box, HAL_IN,
   "from `fatc-rack-guard.box`: the box the last trip was about to enter"},
  {"rack-keepout-at-x", &HalPins::rack_keepout_at_x, HAL_IN, "from `fatc-rack-guard.at-x`"},
  {"rack-keepout-at-y", &HalPins::rack_keepout_at_y, HAL_IN, "from `fatc-rack-guard.at-y`"},
  {"rack-keepout-at-z", &HalPins::rack_keepout_at_z, HAL_IN, "from `fatc-rack-guard.at-z`"},
  // The I/O check (core/rack/io_check.hpp): each output driven once, its
  // sensor's answer timed; the words (each sensor, each refusal, the time)
  // are in the status file's `io_check`. Nothing changes the changer's belief.
  {"io-check-chuck-release", &HalPins::io_check_chuck_release, HAL_IN,
   "rising edge: open the chuck, the spindle still and with air; with a tool in the spindle "
   "only with `io-check-holding-tool`"},
  {"io-check-chuck-clamp", &HalPins::io_check_chuck_clamp, HAL_IN, "rising edge: close the chuck"},
  {"io-check-cover-open", &HalPins::io_check_cover_open, HAL_IN,
   "rising edge: open the rack cover (`rack_cover`)"},
  {"io-check-cover-close", &HalPins::io_check_cover_close, HAL_IN,
   "rising edge: close the rack cover; refused while the spindle (with its tool) is in the "
   "rack or not homed"},
  {"io-check-air-blast", &HalPins::io_check_air_blast, HAL_IN,
   "rising edge: `air-blast` on for 1 s (`air_blast`)"},
  {"io-check-holding-tool", &HalPins::io_check_holding_tool, HAL_IN,
   "the operator holds the tool in the spindle: `io-check-chuck-release` may open the chuck on it"},
  {"io-check-held", &HalPins::io_check_held, HAL_OUT,
   "the I/O check holds an output otherwise than the changer commanded it; a sequence, a program "
   "or MDI, or the machine off gives it back"},
}});
// clang-format on

}  // namespace fatc::linuxcnc
