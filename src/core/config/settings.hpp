#pragma once

// What a validated config.json holds: the Config and its plain types, and
// what the house asks of a Config. It includes nothing of config/ above it,
// so every reader of config.json may include it; the house includes
// config.hpp, which adds the parser.

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "../motion/point.hpp"
#include "sensor_list.hpp"

namespace fatc {

enum class Units { mm, inch };

/// A default with a unit: the same amount in either unit. The inch value is
/// the round number a machinist writes, the mm one over 25 (1.6 % more than
/// the exact amount, as 0.004 inch is of 0.1 mm): a config that leaves the
/// key out moves and measures at the same speeds whichever unit it is in.
struct UnitDefault {
  double mm;
  double inch;
  constexpr double in(Units units) const { return units == Units::inch ? inch : mm; }
};

/// Every default of config.json that has a unit (docs/config.md states both).
namespace unit_default {
constexpr UnitDefault pocket_feed{500.0, 20.0};
constexpr UnitDefault probe_seek_feed{300.0, 12.0};
constexpr UnitDefault probe_latch_feed{25.0, 1.0};
constexpr UnitDefault probe_backoff{2.0, 0.08};
constexpr UnitDefault probe_check_tolerance{0.1, 0.004};
constexpr UnitDefault probe_window{10.0, 0.4};
constexpr UnitDefault rack_keepout_above{5.0, 0.2};
constexpr UnitDefault touch_search{5.0, 0.2};
constexpr UnitDefault touch_clear{3.0, 0.12};
constexpr UnitDefault touch_drift_tolerance{0.1, 0.004};
constexpr UnitDefault bore_tolerance{0.5, 0.02};
}  // namespace unit_default

/// When the changer measures a tool on the touch-off sensor: a tool's own
/// `tools.N.measure`, else `probe_after_change`.
enum class MeasureRule {
  off,       ///< M6 measures nothing; a load and measure all do
  always,    ///< after every change into the spindle, and at a load ("measure" of old)
  when_new,  ///< "new": M6 measures it only when the changer never measured it; a load does
  never,     ///< never touches the sensor: its length in LinuxCNC's tool table is trusted
  check,     ///< M6 re-touches it and faults when it differs from its stored length
};

/// What a tool is (`tools.N.kind`).
enum class ToolKind {
  cutter,  ///< turns in the spindle
  probe,   ///< a touch probe: the spindle is held while it is in it
};

/// `tools.N`: what config.json says of one tool; the tool table stays LinuxCNC's.
struct ToolConfig {
  ToolKind kind = ToolKind::cutter;
  std::optional<MeasureRule> measure;         ///< unset: probe_after_change
  std::optional<double> check_tolerance;      ///< unset: probe_check_tolerance
  std::optional<double> probe_feed;           ///< caps both probing stages; unset: a probe's is probe_latch_feed
};

/// Which way the sequences go between the rack and `safe` (`path`).
enum class Path {
  prototype,  ///< the prototype's literal sequences: through safe XY before and after each leg
  direct,     ///< over the rack at safe Z, no trip to safe XY between a return and a fetch
};

/// How the spindle drops whatever it may hold before it receives a tool.
struct FlushConfig {
  int pulses = 1;              ///< chuck openings; 0 disables the flush
  double pulse_seconds = 0.2;  ///< how long the chuck stays open each pulse
  double pause_seconds = 0.2;  ///< how long it stays closed between pulses
};

/// `rack_cover`: a dust cover over the rack, opened before the first move into
/// the rack and closed once the changer is done with it. Which of its sensors
/// are wired is in SensorConfig.
struct RackCoverConfig {
  double seconds = 1.0;          ///< how long it takes to open, where no sensor says
  double timeout_seconds = 5.0;  ///< how long a wired sensor may take to confirm
};

/// How the spindle enters and leaves a pocket (docs/sequences.md).
enum class Approach {
  side,  ///< in from the side to return, out the side after fetching (the prototype's)
  top,   ///< straight down into the pocket and straight up out of it, both ways
};

/// A place in the rack. Which tool sits in it is tool state (ToolState), not config.
struct Pocket {
  Point at;            ///< where the tool holder sits
  int first_tool = 0;  ///< the tool it holds at first start (`tool`), 0: starts empty
  Approach approach = Approach::side;
  PlanarOffset
      side_offset;  ///< from the pocket to its side (`side_offset`, else pocket_side_offset)
};

/// Which feature of a pocket a 3D probe touches to find it (`rack_touch.feature`).
enum class TouchFeature {
  bore,   ///< a round hole at the pocket: two walls across X, then two across Y
  fork,   ///< a bore open toward the pocket's side: its jaws and its back wall
  faces,  ///< two outside faces, one across X and one across Y
};

/// `rack_touch`: how a 3D probe finds a pocket, and the rack datum it watches
/// (docs/sequences.md, teach by touch). Lengths in the config's units.
struct RackTouch {
  TouchFeature feature = TouchFeature::bore;
  double stylus_radius = 0.0;
  std::optional<double> bore_diameter;  ///< bore and fork
  double bore_tolerance = unit_default::bore_tolerance.mm;
  PlanarOffset top;              ///< where the top face is touched, from the pocket's X,Y
  double pocket_above_top = 0.0;  ///< pocket Z = the top face's Z + this
  double depth = 0.0;            ///< how far below the top face walls and faces are touched
  PlanarOffset x_face;           ///< faces: a point on the face across X, from the pocket's X,Y
  PlanarOffset y_face;           ///< faces: a point on the face across Y
  double search = unit_default::touch_search.mm;
  double clear = unit_default::touch_clear.mm;
  double drift_tolerance = unit_default::touch_drift_tolerance.mm;
  int datum_pocket = 0;             ///< the pocket whose feature is the rack datum, 0: none
  std::optional<Point> datum;       ///< where teach-datum found it
  int check_every_changes = 0;      ///< 0: never
  bool check_at_start = false;
};

/// What holds the tool in the spindle (`chuck.kind`).
enum class ChuckKind {
  drawbar,     ///< a drawbar the changer releases and clamps (`chuck-release`)
  collet_nut,  ///< an ER nut per tool, gripped by its pocket and screwed off and on by the spindle
};

/// Where the tool-recognition sensor's beam is read (`chuck.recognition`):
/// the nose's machine Z at zone 1 (a nut on the spindle cuts the beam) and at
/// zone 2 (only a nut hanging low, not screwed home, still cuts it).
struct Recognition {
  double zone_1_z = 0.0;
  double zone_2_z = 0.0;
};

/// `chuck`: a drawbar (the default), or a collet-nut magazine and how the
/// spindle screws its nuts (docs/collet_nut.md). A pocket's z is then its
/// engage Z: the nose with the nut fully engaged.
struct ChuckConfig {
  ChuckKind kind = ChuckKind::drawbar;
  double spin_off_offset_z = 0.0;           ///< above a pocket's z: the spindle starts and stops turning
  double rise_after_unload_offset_z = 0.0;  ///< above a pocket's z: the rise, still reversing
  double engage_feed = 0.0;                 ///< the plunges onto and into the nut
  double unload_rpm = 0.0;                  ///< reverse (M4)
  double load_rpm = 0.0;                    ///< forward (M3)
  int tighten_plunges = 1;                  ///< plunges while loading: the thread seats
  double spindle_ramp_seconds = 2.0;        ///< a start or stop where no sensor says
  std::optional<Recognition> recognition;   ///< unset: no tool-recognition sensor
};

/// The validated contents of config.json. Lengths are in `units`, feeds in
/// `units` per minute, positions are machine coordinates (G53).
struct Config {
  Units units = Units::mm;

  // Keys of the Python prototype, same meaning.
  double probe_length_compensation_offset = 0.0;
  double probe_retract_offset_z = 0.0;
  PlanarOffset pocket_side_offset;
  double pocket_above_chuck_offset_z = 0.0;
  double pocket_above_clearance_offset_z = 0.0;
  double chuck_seconds = 0.5;
  Point loading;
  Point probe_limit;
  Point safe;
  std::map<int, Pocket> pockets;  ///< pocket number -> pocket, pocket_default merged

  // Keys new in the C++ version, all optional.
  // Unset: unit_default's, in `units` (parse_config sets them once it knows).
  double pocket_feed = unit_default::pocket_feed.mm;  ///< slow moves into and out of a pocket
  double probe_seek_feed = unit_default::probe_seek_feed.mm;    ///< first, fast probing stage
  double probe_latch_feed = unit_default::probe_latch_feed.mm;  ///< second, slow probing stage
  double probe_backoff = unit_default::probe_backoff.mm;        ///< lift between the two stages
  FlushConfig flush;
  double spindle_stop_timeout_seconds = 10.0;
  bool move_while_spindle_stops = true;  ///< M6 moves toward the rack while the spindle runs down
  /// How far below safe Z the corners of a run of rapids at safe Z may be
  /// rounded (G64 P); 0: every move ends standing.
  double blend_tolerance = 0.0;
  std::optional<double> rack_keepout_margin;  ///< unset: half the side offset
  bool rack_keepout_all_motion = true;        ///< the realtime guard keeps all motion out
  std::optional<double> rack_keepout_above;   ///< unset: 5 mm or 0.2 inch
  MeasureRule probe_after_change = MeasureRule::off;  ///< every tool's rule but its own
  std::optional<double> probe_check_tolerance;  ///< unset: 0.1 mm or 0.004 inch
  bool manual_tools = true;             ///< M6 to a tool without pocket hands it over at `loading`
  SensorConfig sensors;                 ///< all off unless config.json says they are wired
  double sensor_timeout_seconds = 1.0;  ///< how long a wired sensor may take to confirm a change
  std::optional<double> probe_window;   ///< unset: 10 mm or 0.4 inch
  std::optional<RackCoverConfig> rack_cover;  ///< unset: no cover
  bool air_blast = false;  ///< `air-blast` cleans the taper while the chuck is open at a pocket
  std::optional<double> verify_feed;  ///< unset: pocket_feed
  Path path = Path::prototype;
  std::map<int, ToolConfig> tools;  ///< tool number -> what `tools` says of it
  std::optional<RackTouch> rack_touch;  ///< unset: nothing is found by touch
  ChuckConfig chuck;
  /// The keys with a unit that config.json left out, as --check lists them.
  std::vector<std::string> defaulted;

  bool has_pocket(int number) const { return pockets.count(number) != 0; }
  /// The spindle screws collet nuts off and on (`chuck.kind` "collet_nut").
  bool screws_nuts() const { return chuck.kind == ChuckKind::collet_nut; }
  /// The pocket that holds `tool` at first start, if any.
  std::optional<int> first_pocket_of(int tool) const;
  double keepout_margin() const;
  /// The largest blend_tolerance the rack allows, and in `why` what limits
  /// it: how far safe Z lies above every pocket's above-clearance, since a
  /// rounded corner stays within the tolerance of the crossing at safe Z
  /// (G64 P). Where the way up or down beside it lies closer than that to a
  /// keep-out column, the corner is rounded within blend_over_columns().
  double blend_room(std::string* why = nullptr) const;
  /// The tolerance of a corner whose way up or down is in or beside a
  /// keep-out column: LinuxCNC's arc leaves a right angle 2.41 P down the
  /// vertical (blendmath.c: P cos 45° / (1 - sin 45°)), its parabolic blend
  /// 2.83 P and a trajectory cycle at the blend's speed (tp.c), so within the
  /// room divided by 3.5 the whole corner stays above every column's top.
  double blend_over_columns() const;
  /// How far above the holders' tops the rack's volume reaches.
  double keepout_above() const;
  double check_tolerance() const;
  /// `tool`'s measuring rule, its kind, its check tolerance and its feeds on
  /// the sensor: its own where `tools` gives them, else the config's.
  MeasureRule rule_of(int tool) const;
  bool is_probe(int tool) const;
  double check_tolerance_of(int tool) const;
  double seek_feed_of(int tool) const;
  double latch_feed_of(int tool) const;
  /// How far from its stored length a tool may first touch the sensor in a
  /// probe after M6: a touch outside stops the probe.
  double window() const;
  /// The feed of every move of a dry run through a pocket (verify).
  double dry_run_feed() const { return verify_feed.value_or(pocket_feed); }
};

const char* units_name(Units units);
/// Machine units to one unit of `units`, on a machine of `machine_per_mm`
/// units to the mm (LinuxCNC's linear units: 1 mm, 1/25.4 inch).
double machine_per_unit(Units units, double machine_per_mm);
const char* approach_name(Approach approach);
/// "bore", "fork", "faces".
const char* feature_name(TouchFeature feature);
/// The word config.json uses: "always", "new", ...
const char* rule_name(MeasureRule rule);
/// Where `tool`'s rule comes from, for a message: `tools.7.measure is "never"`,
/// `probe_after_change is "off"`.
std::string rule_said(const Config& config, int tool);
/// Every tool's rule, one line each, for --check: "T2 probe, spindle held,
/// measured if new", ..., "every other tool not measured at M6 (probe_after_change)".
std::vector<std::string> measuring_words(const Config& config);
/// What the operator reads when M3 or M4 meets probe `tool` in the spindle.
std::string spindle_held_refusal(int tool);
/// Some tool is checked against `probe_check_tolerance` (its rule "check", no
/// tolerance of its own): only then must probe_window exceed it.
bool uses_default_tolerance(const Config& config);
/// What the changer does with `tool` at a change, in a few words for --lint
/// and the panel: "measured", "checked ±0.05", "probe, spindle held, measured if new".
std::string rule_words(const Config& config, int tool);
/// A length for a message, with the config's unit: "25.0012 mm".
std::string format_length(const Config& config, double length);
/// Each key with a unit that the config left out, with the value it takes
/// in the config's units, for --check: "pocket_feed 20 in/min (default)".
std::vector<std::string> defaulted_words(const Config& config);

}  // namespace fatc
