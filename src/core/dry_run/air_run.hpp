#pragma once

// A change in the air: any sequence run a height above the rack, so that the
// whole path can be watched over the forks before the first real change.
// Planned here, from the sequence itself as the Simulator records it; the
// flow that walks it is flows/air_run.hpp.

#include <functional>
#include <optional>
#include <string>

#include "../machine/changer.hpp"

namespace fatc {

/// What the operator gives an air run.
struct AirSettings {
  double height = 0.0;  ///< above the rack's top, config units
  double feed = 0.0;    ///< every move's feed, units per minute; 0: the config's verify feed
};

/// Why `air` cannot be flown with `config`, in one line; nothing if it can.
std::optional<std::string> why_not_air(const Config& config, const AirSettings& air);

/// The moves of a planned sequence `steps` flown in the air: no move that
/// serves a pocket (Step::pocket) ends lower than `air.height` above the top
/// of the rack part the pocket is in (RackPart::box: its forks and the
/// keep-out above them); those higher, and moves elsewhere (loading, the
/// touch-off sensor), keep their target, so the approach heights above that
/// floor are flown as they are.
/// Every move runs at `air.feed`, a blended run as its single moves. Probe
/// moves and the moves below where the probing started (backing off the
/// sensor, the retract), the chuck, dwells, the operator's waits and
/// LinuxCNC's tool commands are left out: nothing is taken, handed or measured.
std::vector<Step> air_route(const Config& config, const std::vector<Step>& steps,
                      const AirSettings& air);

/// The air run of what `request` does to a changer with `tools` standing at
/// `at` (known on `known`), named for the operator; or why not. The spindle
/// really holds `held`, `held_length` long, all the way: refused where its
/// tip would hang below the rack's top (a height less than its length).
struct AirPlan {
  std::optional<AirRunRequest> request;
  std::string refused;  ///< one line, when there is no request
};
AirPlan plan_air_run(const Config& config, const ToolState& tools, const Point& at, unsigned known,
                     const std::function<void(Changer&)>& request, const std::string& name,
                     const AirSettings& air, int held = 0, double held_length = 0.0);

/// What the operator asks to fly, as the `air-run-*` pins and --plan --air say it.
struct AirAsk {
  enum class What { change, load, unload, verify };
  What what = What::change;
  int tool = 0;             ///< change: the tool M6 asks for; load, unload: the tool
  std::optional<int> from;  ///< change: the tool in the spindle as it starts; unset: the real one
  int pocket = 0;           ///< load: into (0: the changer chooses); verify: the pocket
  AirSettings air;
};
/// The air run `ask` names, planned from what `changer` knows (the tool in
/// its spindle as long as its keep-out counts it) and where the spindle
/// stands (`at`, unknown: the sequence starts from nowhere known).
AirPlan plan_air_run(const Changer& changer, const AirAsk& ask, const std::optional<Point>& at);

/// `tools` as if `tool` were in the spindle: the one there back in its pocket,
/// `tool` out of its own (0: the spindle empty). Only for planning.
ToolState as_if_holding(const Config& config, ToolState tools, int tool);

/// "100.000 mm above the rack at F1000": how an air run flies, for its name.
std::string air_words(const Config& config, const AirSettings& air);

}  // namespace fatc
