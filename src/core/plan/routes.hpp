#pragma once

// Where the changer goes: the waypoints of every leg, from the config alone.
// The tables decide what happens next; these functions say where, so the
// path (`path`) and the approach of a pocket (`approach`) are plain code in
// one place. A route is a run of moves with no decision between them.
// docs/sequences.md is the contract they follow.

#include <optional>
#include <type_traits>
#include <vector>

#include "../config/config.hpp"
#include "../motion/step.hpp"

namespace fatc::plan {

using Route = std::vector<Step>;

// ---------------------------------------------------------------- single waypoints
Step safe_z(const Config& c);
Step safe_xy(const Config& c);
Step loading_z(const Config& c);
Step loading_xy(const Config& c);
/// Over the touch-off sensor, at the current Z.
Step sensor_xy(const Config& c);
/// Where a probe of `tool` first goes down fast (probe_seek_feed, still a
/// probing move that stops at a touch) when its own seek is slower: to
/// probe_window above where a tool `length` long touches, the rest at its own
/// feed. None where that saves nothing: its seek is as fast, no length is
/// known, or the spindle (at `start_z`, where known) is not higher than that
/// by more than a back-off.
std::optional<double> probe_approach_z(const Config& c, int tool, double length,
                                       std::optional<double> start_z);
Step probe_approach(const Config& c, double z);
Step probe_seek(const Config& c, int tool);
/// Up from where the seek touched, to latch slowly from there.
Step probe_back_off(const Config& c, int tool, double first_touch_z);
Step probe_latch(const Config& c, int tool);
Step retract_from_sensor(const Config& c, double latched_z);
/// Tells LinuxCNC (M61) what the spindle holds.
Step spindle_tool(int tool);
/// Writes a measured length to LinuxCNC's tool table (G10 L1).
Step tool_length(int tool, double length);

// ---------------------------------------------------------------- return a tool
/// To the pocket's approach, where its sensor is read before anything goes
/// in: up to safe Z, (safe XY on the prototype path), over the side and down
/// to it, or over the pocket and down to above-clearance (prototype) or
/// above-chuck (direct).
Route return_to_approach(const Config& c, int pocket);
/// Into the holder: slowly in from the side (on the direct path at rapid to
/// the column's edge first), or slowly down from above.
Route return_into_pocket(const Config& c, int pocket);
/// Up to above-chuck with the chuck open: the tool stays behind.
Route return_up_from_tool(const Config& c, int pocket);
/// Away from the pocket once the chuck closed: up to safe Z (through
/// above-clearance on the prototype path) and back to safe XY, unless a fetch
/// follows on the direct path, which starts over this pocket.
Route return_away(const Config& c, int pocket, bool fetch_follows);

// ---------------------------------------------------------------- fetch a tool
/// To above-chuck over the pocket, where the chuck flushes and opens: from
/// safe Z (through safe XY and above-clearance on the prototype path).
Route fetch_to_above_chuck(const Config& c, int pocket);
/// Slowly down around the tool, the chuck open.
Route fetch_down_to_tool(const Config& c, int pocket);
/// Out of the holder with the tool (slowly while engaged) and back to safe.
Route fetch_out_and_away(const Config& c, int pocket);

// ---------------------------------------------------------------- screw a collet nut (`chuck`)
// A pocket's z is its engage Z; every move below safe Z stays in its column.
/// Over the pocket at safe Z (through safe XY on the prototype path) and down
/// to spin-off, where the spindle starts turning.
Route nut_to_spin_off(const Config& c, int pocket);
/// Back down (or up) to spin-off from a recognition zone, to screw once more.
Route nut_back_to_spin_off(const Config& c, int pocket);
/// Unloading, the spindle reversing: the plunge to the engage Z at the engage
/// feed, and the rise to rise-after-unload.
Route nut_screw_off(const Config& c, int pocket);
/// Loading, the spindle forward: down to the engage Z and back up to
/// spin-off at the engage feed, `tighten_plunges` times.
Route nut_screw_on(const Config& c, int pocket);
/// To where the tool-recognition beam is read, the spindle stopped over the pocket.
Route nut_to_zone_1(const Config& c, int pocket);
Route nut_to_zone_2(const Config& c, int pocket);
/// Up from the pocket with its nut on the spindle, and back to safe: as a return's way away.
Route nut_away(const Config& c, int pocket);

// ---------------------------------------------------------------- while the spindle runs down
/// What M6 may do before the spindle stands, of `first`, the route its first
/// leg walks: the leading moves that stay at safe Z (up to it, and across
/// toward the pocket above every keep-out column); with a rack cover, whose
/// shape the config does not give, only up to safe Z. Nothing lower, the
/// chuck closed. None where `move_while_spindle_stops` is false.
Route while_spindle_stops(const Config& c, const Route& first);
/// M6's first leg: the return of the spindle's tool into `pocket`, or the
/// fetch of the tool in it.
struct FirstLeg {
  bool returns = false;
  int pocket = 0;
};
/// while_spindle_stops of the route `first` walks first.
Route while_spindle_stops_before(const Config& c, const FirstLeg& first);

/// `route` from where the spindle stands (`at`, known on the axes of
/// `known_axes`): a leading run of moves at safe Z that ends there is left
/// out, so that a leg does not walk again the way to where it already is (after
/// the moves made while the spindle ran down, a fetch after a return). The
/// last waypoint is always kept.
Route from_where_it_stands(const Config& c, Route route, const Point& at, unsigned known_axes);

/// `route` as the executor runs it with `blend_tolerance`: up to safe Z and
/// across at it, each followed by a rapid, go into the step of that rapid
/// (Step::before), so that their corners at safe Z are rounded; from `at`
/// (known on `known_axes`). Unchanged with a tolerance of 0.
Route blended(const Config& c, const Route& route, const Point& at, unsigned known_axes);

// ---------------------------------------------------------------- a phase
/// Where the spindle stands as a phase starts: `at`, known on the axes of `known_axes`.
struct Standing {
  Point at;
  unsigned known_axes = 0;
};

/// `route` as a phase walks it from where the spindle stands: from there
/// (from_where_it_stands), blended.
Route walked(const Config& c, Route route, const Standing& from);

/// The whole route a phase walks, the one call it makes into plan/: the
/// route (or the single step) `make` makes of the config and `args`, walked
/// from where the spindle stands.
template <class Make, class... Args>
Route phase(const Config& c, const Standing& from, Make make, const Args&... args) {
  if constexpr (std::is_same_v<std::invoke_result_t<Make, const Config&, const Args&...>, Step>) {
    return walked(c, Route{make(c, args...)}, from);
  } else {
    return walked(c, make(c, args...), from);
  }
}

// ---------------------------------------------------------------- the operator and the sensor
/// Up to safe Z where the spindle stands.
Route to_safe_z(const Config& c);
/// To `loading`, Z first: where the operator reaches the spindle.
Route to_loading(const Config& c);
/// To `loading` Z, then over the touch-off sensor.
Route to_sensor(const Config& c);

// ---------------------------------------------------------------- verify
/// A dry run through a pocket's approach: in the way a return goes in and out
/// the way a fetch comes out, or down from above and back up; every move at
/// the dry run's feed, or slower where the leg itself is.
Route verify_pocket(const Config& c, int pocket);

}  // namespace fatc::plan
