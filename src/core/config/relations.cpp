#include "relations.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "rack_volume.hpp"

namespace fatc::reading {
namespace {

/// The side offset's length (x and y combined).
constexpr double kMinSideOffset = 0.1;

/// A side offset says where the spindle slows down before entering a pocket:
/// it must lead out of the pocket's keep-out.
/// (pocket_side_offset itself is held against rack_keepout_margin below.)
void check_side_offset(Reader& reader, const Config& config, const PlanarOffset& offset,
                       const std::string& path, bool pockets_own) {
  const double length = std::hypot(offset.x, offset.y);
  if (length == 0.0) {
    reader.error(path,
                 "must not be zero in both x and y: the side is where the "
                 "spindle slows down before entering a pocket");
  } else if (length < kMinSideOffset) {
    reader.error(path, "must be at least " + format_number(kMinSideOffset) + " " +
                           units_name(config.units) + " long (x and y combined), got " +
                           format_number(length));
  } else if (pockets_own && length <= config.keepout_margin()) {
    reader.error(path, "must lead out of the pocket's keep-out (rack_keepout_margin " +
                           format_number(config.keepout_margin()) + "), got " +
                           format_number(length) + " long");
  }
}

/// A value in a relation between keys, as the user knows it: what they wrote,
/// or the default of a key they left out, which they never typed: "1: its
/// default, left out".
std::string said(const Config& config, const char* key, double value) {
  const bool left_out = std::find(config.defaulted.begin(), config.defaulted.end(), key) !=
                        config.defaulted.end();
  return format_number(value) + (left_out ? ": its default, left out" : "");
}

}  // namespace

void check_relations(Reader& reader, const Config& config) {
  if (config.pocket_above_clearance_offset_z <= config.pocket_above_chuck_offset_z) {
    reader.error("pocket_above_clearance_offset_z",
                 "must be above pocket_above_chuck_offset_z (" +
                     format_number(config.pocket_above_chuck_offset_z) + "), got " +
                     format_number(config.pocket_above_clearance_offset_z));
  }
  const double side = std::hypot(config.pocket_side_offset.x, config.pocket_side_offset.y);
  check_side_offset(reader, config, config.pocket_side_offset, "pocket_side_offset", false);
  for (const auto& [number, pocket] : config.pockets) {
    if (pocket.approach != Approach::side) continue;
    const PlanarOffset& own = pocket.side_offset;
    if (own.x != config.pocket_side_offset.x || own.y != config.pocket_side_offset.y) {
      check_side_offset(reader, config, own, "pockets." + std::to_string(number) + ".side_offset",
                        true);
    }
  }
  for (auto a = config.pockets.begin(); a != config.pockets.end(); ++a) {
    for (auto b = std::next(a); b != config.pockets.end(); ++b) {
      const double distance =
          std::hypot(a->second.at.x - b->second.at.x, a->second.at.y - b->second.at.y);
      if (distance < side) {
        reader.error("pockets." + std::to_string(b->first),
                     "only " + format_number(distance) + " from pocket " +
                         std::to_string(a->first) + ", closer than the side offset (" +
                         format_number(side) + ")");
      }
    }
  }
  if (config.probe_limit.z > config.loading.z) {
    reader.error("probe_limit.z", "must not be above loading.z (" +
                                      format_number(config.loading.z) + "), got " +
                                      format_number(config.probe_limit.z));
  }
  // Load and measure-all probe there whatever probe_after_change says: a
  // sensor in the rack would take the tool down between the holders.
  const Point sensor = config.probe_limit;
  for (const RackPart& part : rack_volume(config)) {
    const Box& box = part.box;
    if (sensor.x > box.low.x && sensor.x < box.high.x && sensor.y > box.low.y &&
        sensor.y < box.high.y) {
      reader.error("probe_limit", "the touch-off sensor at X" + format_number(sensor.x) + " Y" +
                                      format_number(sensor.y) + " lies in the rack's keep-out at pocket " +
                                      std::to_string(nearest_pocket(part, sensor)) +
                                      " (rack_keepout_margin " +
                                      format_number(config.keepout_margin()) +
                                      "): place it clear of the rack");
      break;
    }
  }
  if (const double floor = bounds_in(key("rack_keepout_margin"), config.units).min;
      !config.rack_keepout_margin && config.keepout_margin() < floor) {
    reader.error("rack_keepout_margin", "missing, and its default, half the side offset (" +
                                            format_number(config.keepout_margin()) +
                                            "), is below " + format_number(floor) + " " +
                                            units_name(config.units) +
                                            ": give the tool holder's half-width");
  }
  if (config.rack_keepout_margin && *config.rack_keepout_margin >= side && side > 0.0) {
    reader.error("rack_keepout_margin", "must be smaller than the side offset (" +
                                            format_number(side) + "), got " +
                                            format_number(*config.rack_keepout_margin));
  }
  if (const auto parts = rack_volume(config).size();
      config.rack_keepout_all_motion && parts > kGuardBoxes) {
    reader.error("rack_keepout_all_motion",
                 "the pockets lie in " + std::to_string(parts) +
                     " groups apart from each other, and the realtime guard holds " +
                     std::to_string(kGuardBoxes) + ": move pockets together or set it false");
  }
  if (std::string why; config.blend_tolerance > config.blend_room(&why)) {
    reader.error("blend_tolerance", "must not be more than " +
                                        format_number(config.blend_room()) + ", " + why +
                                        ": a rounded corner would cut into the rack; got " +
                                        format_number(config.blend_tolerance));
  }
  if (uses_default_tolerance(config) && config.window() <= config.check_tolerance()) {
    reader.error("probe_window", "must be larger than probe_check_tolerance (" +
                                     said(config, "probe_check_tolerance", config.check_tolerance()) +
                                     "), got " + said(config, "probe_window", config.window()));
  }
  if (config.probe_latch_feed > config.probe_seek_feed) {
    reader.error("probe_latch_feed",
                 "must not be above probe_seek_feed (" +
                     said(config, "probe_seek_feed", config.probe_seek_feed) + "), got " +
                     said(config, "probe_latch_feed", config.probe_latch_feed));
  }
}

}  // namespace fatc::reading
