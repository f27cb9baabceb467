#include "keys.hpp"

#include <sstream>
#include <stdexcept>

namespace fatc {
namespace {

// Same bounds in mm and inch: wide enough for any machine in either, narrow
// enough that nothing overflows (a coordinate plus an offset) or means nothing
// (a side offset of 1e-300, a feed of 5e-324, a timeout whose deadline
// overflows std::chrono).
constexpr Range kCoordinate{-100000.0, 100000.0, "length"};
constexpr Range kOffset{0.001, 1000.0, "length"};
constexpr Range kSideComponent{-1000.0, 1000.0, "length"};
constexpr Range kMargin{1.0, 1000.0, "length"};
constexpr Range kTolerance{0.0001, 100.0, "length"};
constexpr Range kFeed{0.01, 100000.0, "feed"};
constexpr Range kPulse{0.01, 60.0, "seconds"};
constexpr Range kTimeout{0.01, 3600.0, "seconds"};
constexpr Range kSensorTimeout{0.01, 60.0, "seconds"};
constexpr Range kPulses{0.0, 20.0, ""};
constexpr Range kBlend{0.0, 1000.0, "length"};
constexpr Range kChanges{0.0, 1000000.0, ""};
constexpr Range kRpm{1.0, 100000.0, "rpm"};
constexpr Range kPlunges{1.0, 20.0, ""};
constexpr const char* kBoolean = "`true`, `false`";
constexpr const char* kRequired = "required";

// A key left out keeps the value a Config starts with: the defaults the
// reference states are those values, never written twice.
const Config kStart;
const RackCoverConfig kCover;
std::string stated(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}
/// A default with a unit, in both: "500 mm/min, 20 in/min".
std::string stated(const UnitDefault& value, bool feed) {
  return stated(value.mm) + (feed ? " mm/min, " : " mm, ") + stated(value.inch) +
         (feed ? " in/min" : " inch");
}

// A sensor's key only wires it; what the sensor says comes from sensor_list.hpp.
/// "`tool-present`: a tool is clamped in the spindle".
std::string pin_says(const SensorWords& words) {
  return "`" + std::string(words.pin) + "`: " + words.says;
}
/// A sensor of `sensors`.
KeyDeclaration sensor_key(Sensor sensor) {
  const SensorWords& words = declared(sensor).words;
  return {words.key, "`false`", {}, kBoolean, pin_says(words)};
}
/// A sensor of `rack_cover`: "`rack-cover-opened` is wired".
KeyDeclaration cover_sensor_key(Sensor sensor) {
  const SensorWords& words = declared(sensor).words;
  return {words.key, "`false`", {}, kBoolean, "`" + std::string(words.pin) + "` is wired"};
}

// clang-format off
const std::vector<KeyDeclaration> kKeys = {
  {"units", "`\"mm\"`", {}, "`\"mm\"`, `\"inch\"`",
   "the unit of every length and feed in the file; the executor works in G21 or G20 accordingly"},
  {"probe_length_compensation_offset", kRequired, kCoordinate, "",
   "subtracted from the machine Z where the latch touches, to give the tool length: the Z at "
   "which the bare spindle nose would touch the sensor"},
  {"probe_retract_offset_z", kRequired, kOffset, "",
   "how far up the spindle goes after the latch touch"},
  {"pocket_side_offset", kRequired, {}, "an object of the keys below",
   "from a pocket to its *side*, outside the fork, where the slow move in starts and the slow "
   "move out ends. Pockets closer to each other than its length are refused"},
  {"pocket_side_offset.{x,y}", kRequired, kSideComponent,
   "together at least 0.1 long, and longer than `rack_keepout_margin`",
   "the side offset's X and Y"},
  {"pocket_above_chuck_offset_z", kRequired, kOffset, "",
   "above a pocket's Z: the spindle nose clear of the holder; the chuck opens there before a "
   "fetch and closes there after a return"},
  {"pocket_above_clearance_offset_z", kRequired, kOffset, "above `pocket_above_chuck_offset_z`",
   "above a pocket's Z: clear of every holder; a top pocket's approach starts here"},
  {"chuck_seconds", kRequired, kPulse, "",
   "each dwell of the chuck at a pocket: after it opens and after it closes, before the spindle "
   "moves on"},
  {"loading", kRequired, {}, "an object of the keys below",
   "where the operator hands tools in and out; a probe starts from `loading.z`"},
  {"loading.{x,y,z}", kRequired, kCoordinate, "", "the loading position"},
  {"probe_limit", kRequired, {}, "an object of the keys below",
   "over the touch-off sensor, and how low the probe may go"},
  {"probe_limit.{x,y,z}", kRequired, kCoordinate, "z not above `loading.z`",
   "x, y: over the touch-off sensor; z: the lowest the probe may go (no touch by then: the "
   "probe fails)"},
  {"safe", kRequired, {}, "an object of the keys below",
   "near the rack, above everything; sequences start and end there (`\"direct\"`: at safe Z)"},
  {"safe.{x,y,z}", kRequired, kCoordinate, "", "the safe position"},
  {"pockets", kRequired, {}, "1 to 200 pockets",
   "the rack: one entry per pocket, keyed by its number. Which tool sits in a pocket is tool "
   "state, not config"},
  {"pockets.N", "", {}, "N a whole number 1 to 999999999, as a string: `\"7\"`",
   "pocket N, a place in the rack"},
  {"pockets.N.{x,y,z}", "from `pocket_default`; one of the two must say it", kCoordinate, "",
   "where the tool holder sits: the spindle nose with a holder gripped and seated in the fork"},
  {"pockets.N.tool", "N", {}, "0, or a tool 1 to 999999999 in no other pocket",
   "the tool pocket N holds at first start (no state file yet); 0: it starts empty"},
  {"pockets.N.approach", "`pocket_default.approach`, else `\"side\"`", {},
   "`\"side\"`, `\"top\"`",
   "`\"side\"`: in from the side to return, out the side after fetching; `\"top\"`: straight "
   "down into the pocket and straight up out of it"},
  {"pockets.N.side_offset", "`pocket_default.side_offset`, else `pocket_side_offset`", {},
   "an object of x and y, as `pocket_side_offset`; must lead out of the pocket's keep-out",
   "this pocket's own side, for racks with pockets facing different ways"},
  {"pockets.N.side_offset.{x,y}", "", kSideComponent, "", "this pocket's side offset"},
  {"pocket_default", "`{}`", {}, "an object of the keys below",
   "merged under every pocket: a key the pocket gives wins"},
  {"pocket_default.{x,y,z}", "none", kCoordinate, "",
   "the coordinate every pocket shares unless it gives its own"},
  {"pocket_default.approach", "`\"side\"`", {}, "`\"side\"`, `\"top\"`",
   "every pocket's approach unless it gives its own"},
  {"pocket_default.side_offset", "`pocket_side_offset`", {}, "as `pocket_side_offset`",
   "every pocket's side unless it gives its own"},
  {"pocket_default.side_offset.{x,y}", "", kSideComponent, "", "the default side offset"},
  {"path", "`\"prototype\"`", {}, "`\"prototype\"`, `\"direct\"`",
   "`\"prototype\"`: through safe XY before and after each leg; `\"direct\"`: over the rack at "
   "safe Z, safe XY only where the program or the operator comes next, only the keep-out column "
   "crossed slowly (docs/sequences.md, the direct path)"},
  {"pocket_feed", stated(unit_default::pocket_feed, true), kFeed, "", "the slow moves into and out of a pocket"},
  {"verify_feed", "`pocket_feed`", kFeed, "",
   "every move of a dry run through a pocket (verifying a pocket); into and out of the pocket "
   "never faster than `pocket_feed`"},
  {"probe_seek_feed", stated(unit_default::probe_seek_feed, true) + " (sample: 3000 mm/min)", kFeed, "",
   "the first, fast probing stage, and the back-off"},
  {"probe_latch_feed", stated(unit_default::probe_latch_feed, true) + " (sample: 60 mm/min)", kFeed, "not above `probe_seek_feed`",
   "the second, slow probing stage: it sets the accuracy"},
  {"probe_backoff", stated(unit_default::probe_backoff, false) + " (sample: 0.5 mm)", kOffset, "",
   "lift above the first touch before the slow stage"},
  {"probe_after_change", "`\"off\"`", {},
   "`\"off\"`, `\"always\"`, `\"new\"`, `\"never\"`, `\"check\"`; `\"measure\"` is the older "
   "word for `\"always\"`",
   "every tool's measuring rule unless `tools` gives its own. After M6: `\"off\"` measures "
   "nothing; `\"always\"` measures the new tool and writes its length; `\"new\"` only a tool the "
   "changer never measured; `\"check\"` measures it and faults when it differs from the stored "
   "length (a tool never measured is measured). A load and measure all measure every tool but a "
   "`\"never\"` one, which nothing takes to the sensor: its length in LinuxCNC's tool table is "
   "trusted (measuring after M6)"},
  {"probe_check_tolerance", stated(unit_default::probe_check_tolerance, false), kTolerance, "below `probe_window`",
   "how far a checked length may be from the stored one"},
  {"probe_window", stated(unit_default::probe_window, false), kOffset, "above `probe_check_tolerance`",
   "a probe after M6 of a tool with a stored length must first touch within this of where that "
   "length puts the touch"},
  {"manual_tools", "`true`", {}, kBoolean,
   "M6 to a tool with no pocket hands it over at `loading`; `false`: refused"},
  {"flush", "1 pulse of 0.2 s, 0.2 s pause", {}, "an object of the keys below",
   "chuck pulses that drop whatever the spindle holds before it takes a tool"},
  {"flush.pulses", stated(kStart.flush.pulses), kPulses, "a whole number", "how many times the chuck opens; 0: no flush"},
  {"flush.pulse_seconds", stated(kStart.flush.pulse_seconds), kPulse, "", "how long it stays open each time"},
  {"flush.pause_seconds", stated(kStart.flush.pause_seconds), kPulse, "", "how long it stays closed between pulses"},
  {"spindle_stop_timeout_seconds", stated(kStart.spindle_stop_timeout_seconds), kTimeout, "",
   "how long M6 (and a chuck about to open) waits for the spindle to stop"},
  {"move_while_spindle_stops", "`true`", {}, kBoolean,
   "M6 lifts to safe Z and travels at safe Z toward the first pocket while the spindle runs "
   "down, the chuck closed, into no keep-out column; nothing goes lower until the spindle "
   "stands. It needs a spindle that says it runs down: `zero-speed` wired "
   "(`sensors.zero_speed`), or `spindle-stopped` from the drive; netted from "
   "`not spindle.0.on` alone, the spindle reads stopped at M5. `false`: M6 stands until the "
   "spindle stops"},
  {"blend_tolerance", "0", kBlend, "up to how far `safe.z` lies above the highest pocket's "
   "above-clearance",
   "how far below safe Z M6 may round the corners of its rapids at safe Z (G64 P): up to safe Z, "
   "across and down run on without stopping at either corner; 0: every move ends standing. A "
   "corner whose way up or down lies closer than this to a pocket's keep-out column, or in one, is "
   "rounded within that room divided by 3.5 instead, so it stays above every column. Over the work the "
   "machine must be clear this far below safe Z"},
  {"rack_keepout_margin", "half the side offset's length", kMargin,
   "from 0.04 in inch; below the side offset's length",
   "half-width of each pocket's keep-out column: no move may cross it except the pocket's own "
   "approach. A holder is not zero wide: a column of nothing would let every move through the "
   "rack", 0.04},
  {"rack_keepout_all_motion", "`true`", {}, kBoolean,
   "the rack's volume is kept out of every motion, programs, MDI and jogs alike, by the "
   "realtime guard `fatc-rack-guard`; `false` switches that off, and the component and panel "
   "say it is off (the changer's own moves are checked either way)"},
  {"rack_keepout_above", stated(unit_default::rack_keepout_above, false), kMargin, "from 0.04 in inch",
   "how far above the holders' tops (a pocket's Z plus `pocket_above_chuck_offset_z`) the "
   "rack's volume reaches: the lowest the tip of the tool in the spindle may pass over a pocket",
   0.04},
  {"sensors", "all `false`", {}, "an object of the keys below",
   "which optional sensors are wired; one not wired is never read"},
  sensor_key(Sensor::tool_present),
  sensor_key(Sensor::drawbar_open),
  sensor_key(Sensor::drawbar_closed),
  sensor_key(Sensor::air_pressure),
  sensor_key(Sensor::zero_speed),
  sensor_key(Sensor::at_speed),
  {kPocketSensor.key, "`false`", {},
   "`true` (every pocket), `false`, or a list of pockets of `pockets`, each once: `[1, 2, 5]`",
   pin_says(kPocketSensor)},
  {"sensor_timeout_seconds", stated(kStart.sensor_timeout_seconds), kSensorTimeout, "",
   "how long a wired sensor may take to confirm a change"},
  {"rack_cover", "absent: no cover", {},
   "an object of the keys below; `{}` turns the cover on with their defaults",
   "the rack has a dust cover on `rack-cover-open`"},
  cover_sensor_key(Sensor::rack_cover_opened),
  cover_sensor_key(Sensor::rack_cover_closed),
  {"rack_cover.seconds", stated(kCover.seconds), kTimeout, "", "how long the cover takes to open where no sensor says"},
  {"rack_cover.timeout_seconds", stated(kCover.timeout_seconds), kTimeout, "", "how long a wired cover sensor may take"},
  {"air_blast", "`false`", {}, kBoolean,
   "drive `air-blast` while the chuck is open at a pocket with the spindle empty"},
  {"rack_touch", "absent: nothing is found by touch", {}, "an object of the keys below",
   "how a 3D probe (a tool of kind `\"probe\"`) in the spindle finds each pocket by touching its "
   "feature, and the rack datum it touches again to see whether the rack moved "
   "(docs/sequences.md, teach by touch)"},
  {"rack_touch.feature", kRequired, {}, "`\"bore\"`, `\"fork\"`, `\"faces\"`",
   "`\"bore\"`: a hole at the pocket, its walls touched across X, then across Y from the X "
   "found; `\"fork\"`: a bore open toward the pocket's side, its jaws across the side's axis "
   "and its back wall; `\"faces\"`: two outside faces, `x_face` and `y_face`. Pins are not "
   "supported"},
  {"rack_touch.stylus_radius", kRequired, kOffset, "below `depth`; a bore wider than twice it",
   "the radius of the probe's stylus ball: a wall touched lies this far beyond the ball's centre"},
  {"rack_touch.bore_diameter", "required for `\"bore\"` and `\"fork\"`", kOffset,
   "above twice `stylus_radius`", "the bore's diameter; a fork's, at its back wall"},
  {"rack_touch.bore_tolerance", stated(unit_default::bore_tolerance, false), kTolerance, "",
   "how far the diameter measured across X and across Y may be from `bore_diameter`: a chip, "
   "or the wrong feature, is refused"},
  {"rack_touch.top", kRequired, {}, "an object of the keys below",
   "where the top face is touched for Z, from the pocket's X,Y"},
  {"rack_touch.top.{x,y}", kRequired, kSideComponent, "", "the top face's touch point"},
  {"rack_touch.pocket_above_top", kRequired, kSideComponent, "",
   "a pocket's Z is the top face's Z (the nose where it touched, less the probe's tool-table "
   "length) plus this; may be negative"},
  {"rack_touch.depth", kRequired, kOffset, "",
   "how far below the top face the walls and faces are touched"},
  {"rack_touch.x_face", "required for `\"faces\"`", {}, "an object of the keys below",
   "a point on the face touched across X, from the pocket's X,Y; x not 0: its sign says on which "
   "side of the pocket the face lies"},
  {"rack_touch.x_face.{x,y}", kRequired, kSideComponent, "", "the X face's point"},
  {"rack_touch.y_face", "required for `\"faces\"`", {}, "an object of the keys below",
   "a point on the face touched across Y, from the pocket's X,Y; y not 0"},
  {"rack_touch.y_face.{x,y}", kRequired, kSideComponent, "", "the Y face's point"},
  {"rack_touch.search", stated(unit_default::touch_search, false), kOffset, "",
   "how far past where a touch is expected the probe goes before it says it found nothing"},
  {"rack_touch.clear", stated(unit_default::touch_clear, false), kOffset, "",
   "how far short of a face a touch starts, and how far above the top face the Z touch starts"},
  {"rack_touch.drift_tolerance", stated(unit_default::touch_drift_tolerance, false), kTolerance,
   "", "how far the datum may be from where it was taught before M6 is refused"},
  {"rack_touch.datum", "absent: no drift check", {}, "an object of the keys below",
   "the rack datum: one pocket's feature, touched again to see whether the rack moved"},
  {"rack_touch.datum.pocket", kRequired, {}, "a pocket of `pockets`",
   "the pocket whose feature is the datum"},
  {"rack_touch.datum.{x,y,z}", "written by teach-datum", kCoordinate, "all three or none",
   "where the datum was found when it was taught: what the drift check compares against"},
  {"rack_touch.check_every_changes", "0", kChanges, "a whole number; needs `datum`",
   "the drift check falls due after this many changes; 0: never"},
  {"rack_touch.check_at_start", "`false`", {}, kBoolean,
   "the drift check falls due each time the component starts"},
  {"chuck", "`{\"kind\": \"drawbar\"}`", {}, "an object of the keys below",
   "what holds the tool in the spindle (docs/collet_nut.md)"},
  {"chuck.kind", "`\"drawbar\"`", {}, "`\"drawbar\"`, `\"collet_nut\"`",
   "`\"drawbar\"`: the changer releases and clamps a drawbar (`chuck-release`); "
   "`\"collet_nut\"`: an ER nut per tool, gripped by its pocket, screwed off (reverse) and on "
   "(forward) by the spindle, which the changer turns itself (M4, M3) over the served pocket only. "
   "A pocket's `z` is then its engage Z, every pocket is entered from the top, and the keys "
   "below are read"},
  {"chuck.spin_off_offset_z", "required for `\"collet_nut\"`", kOffset,
   "below `chuck.rise_after_unload_offset_z`; below safe Z",
   "above a pocket's `z`: where the spindle starts turning before it plunges, and where the "
   "plunges of a load come back to (RapidChange: the spin-off / load spindle start Z)"},
  {"chuck.rise_after_unload_offset_z", "`chuck.spin_off_offset_z`", kOffset, "",
   "above a pocket's `z`: how high the spindle rises, still reversing, after it unscrewed a nut"},
  {"chuck.engage_feed", "required for `\"collet_nut\"`", kFeed, "",
   "the plunges onto and into a nut: about the thread's pitch times the speed"},
  {"chuck.unload_rpm", "required for `\"collet_nut\"`", kRpm, "",
   "the spindle's speed in reverse (M4) while it screws a nut off"},
  {"chuck.load_rpm", "required for `\"collet_nut\"`", kRpm, "",
   "the spindle's speed forward (M3) while it screws a nut on"},
  {"chuck.tighten_plunges", "1", kPlunges, "a whole number",
   "how many times a load plunges onto the nut: the spindle stalls as the thread seats, and "
   "each plunge tightens it a little more"},
  {"chuck.spindle_ramp_seconds", "2", kPulse, "",
   "how long the spindle takes to reach its speed or to stop, waited where `sensors.at_speed` "
   "(or `sensors.zero_speed`) is not wired"},
  {"chuck.recognition", "absent: no tool-recognition sensor", {}, "an object of the keys below",
   "the infrared tool-recognition sensor on `nut-seen`, read with the spindle stopped over the "
   "pocket: after an unload zone 1 must be clear; after a load zone 1 must be cut (a nut is "
   "there) and zone 2 clear (it is screwed home). A failed reading is tried once more, then "
   "the changer faults naming the zone"},
  {"chuck.recognition.zone_1_z", kRequired, kCoordinate, "not below any pocket's spin-off",
   "the nose's machine Z where a nut on the spindle cuts the beam"},
  {"chuck.recognition.zone_2_z", kRequired, kCoordinate, "above `zone_1_z`, below safe Z",
   "the nose's machine Z where only a nut not screwed home (hanging low) cuts the beam"},
  {"tools", "`{}`", {}, "an object of tool numbers, each an object of the keys below",
   "what a tool is and how it is measured, where it differs from the rest; lengths stay in "
   "LinuxCNC's tool table"},
  {"tools.N.kind", "`\"cutter\"`", {}, "`\"cutter\"`, `\"probe\"`",
   "`\"probe\"`: a touch probe. While it is in the spindle `fatc-spindle-guard` holds the "
   "spindle still (M3, M4 from anywhere; the component aborts them and says why) and routes "
   "the probe's input to `motion.probe-input`"},
  {"tools.N.measure", "`probe_after_change`", {}, "as `probe_after_change`",
   "this tool's measuring rule"},
  {"tools.N.check_tolerance", "`probe_check_tolerance`", kTolerance,
   "below `probe_window`; only with the rule `\"check\"`",
   "how far this tool's checked length may be from its stored one"},
  {"tools.N.probe_feed", "a probe: `probe_latch_feed`; else none", kFeed, "",
   "the most either probing stage moves this tool on the sensor: a probe's stylus or a spring "
   "tool touches slowly. Above `probe_window` over where its length puts the touch it goes down "
   "at `probe_seek_feed`, and a touch there is refused, nothing written"},
};
// clang-format on

/// "loading.{x,y,z}" -> loading.x, loading.y, loading.z.
std::vector<std::string> expand(const std::string& path) {
  const auto open = path.find('{');
  if (open == std::string::npos) return {path};
  std::vector<std::string> paths;
  const std::string head = path.substr(0, open);
  const std::string names = path.substr(open + 1, path.size() - open - 2);
  std::size_t at = 0;
  while (at <= names.size()) {
    const auto comma = names.find(',', at);
    const auto end = comma == std::string::npos ? names.size() : comma;
    paths.push_back(head + names.substr(at, end - at));
    at = end + 1;
  }
  return paths;
}

/// "pockets.7.x" as declared: "pockets.N.x"; "tools.7.kind": "tools.N.kind".
std::string pattern_of(const std::string& path) {
  for (const std::string prefix : {"pockets.", "tools."}) {
    if (path.rfind(prefix, 0) != 0) continue;
    const auto dot = path.find('.', prefix.size());
    return prefix + "N" + (dot == std::string::npos ? "" : path.substr(dot));
  }
  return path;
}

std::string unit_words(const Range& range) {
  const std::string unit = range.unit;
  if (unit == "seconds") return "s";
  return unit;
}

std::string number_words(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

}  // namespace

const std::vector<KeyDeclaration>& config_keys() { return kKeys; }

const KeyDeclaration& key(const std::string& path) {
  const std::string wanted = pattern_of(path);
  for (const KeyDeclaration& declared : kKeys) {
    for (const std::string& one : expand(declared.path)) {
      if (one == wanted) return declared;
    }
  }
  throw std::logic_error("config key " + path + " is not declared in keys.cpp");
}

std::vector<std::string> keys_below(const std::string& path) {
  const std::string parent = pattern_of(path);
  std::vector<std::string> names;
  for (const KeyDeclaration& declared : kKeys) {
    for (const std::string& one : expand(declared.path)) {
      const auto dot = one.rfind('.');
      const std::string above = dot == std::string::npos ? "" : one.substr(0, dot);
      if (above == parent && one.substr(dot + 1) != "N") {
        names.push_back(dot == std::string::npos ? one : one.substr(dot + 1));
      }
    }
  }
  return names;
}

Range bounds_in(const KeyDeclaration& key, Units units) {
  Range range = key.bounds.value();
  if (units == Units::inch && key.inch_min) range.min = *key.inch_min;
  return range;
}

std::string config_markdown() {
  std::string out =
      "| key | unit | default | range | meaning |\n"
      "| --- | --- | --- | --- | --- |\n";
  for (const KeyDeclaration& declared : kKeys) {
    std::string paths;
    for (const std::string& one : expand(declared.path)) {
      paths += (paths.empty() ? "`" : ", `") + one + "`";
    }
    std::string range;
    if (declared.bounds) {
      range = number_words(declared.bounds->min) + " to " + number_words(declared.bounds->max);
    }
    if (*declared.range) range += (range.empty() ? "" : "; ") + std::string(declared.range);
    const std::string unit = declared.bounds ? unit_words(*declared.bounds) : "";
    out += "| " + paths + " | " + unit + " | " + declared.fallback + " | " + range + " | " +
           declared.doc + " |\n";
  }
  return out;
}

}  // namespace fatc
