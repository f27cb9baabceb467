// Any bytes as config.json: either a config whose every number is finite and
// in its declared range, or one printable line per problem. Never a crash,
// an exception, a leak or undefined behaviour.
#include <cmath>
#include <cstdint>
#include <string>

#include "core/config/config.hpp"
#include "invariants.hpp"

namespace {

void check_finite(double value, const char* what) {
  if (!std::isfinite(value)) fatc::fuzz::broken("a valid config is finite", what);
}

void check_point(const fatc::Point& point, const char* what) {
  check_finite(point.x, what);
  check_finite(point.y, what);
  check_finite(point.z, what);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const fatc::ConfigResult result = fatc::parse_config(text);
  if (result.config.has_value() == !result.errors.empty()) {
    fatc::fuzz::broken("a config or its errors, never both or neither", text.substr(0, 200));
  }
  fatc::fuzz::check_messages(result.errors);
  if (!result.config) return 0;
  const fatc::Config& c = *result.config;
  check_point(c.loading, "loading");
  check_point(c.probe_limit, "probe_limit");
  check_point(c.safe, "safe");
  for (const auto& [number, pocket] : c.pockets) {
    check_point(pocket.at, "pocket");
    // The waypoints the changer moves through: a coordinate plus an offset.
    check_finite(pocket.at.z + c.pocket_above_clearance_offset_z, "above_clearance");
    check_finite(pocket.at.x + pocket.side_offset.x, "side x");
    check_finite(pocket.at.y + pocket.side_offset.y, "side y");
    if (pocket.first_tool < 0) fatc::fuzz::broken("a first-start tool is 0 or a tool", "tool");
  }
  if (!(c.probe_latch_feed > 0 && c.probe_latch_feed <= c.probe_seek_feed)) {
    fatc::fuzz::broken("latch feed above 0 and not above the seek feed", text.substr(0, 200));
  }
  for (double seconds : {c.chuck_seconds, c.spindle_stop_timeout_seconds, c.flush.pulse_seconds,
                         c.flush.pause_seconds}) {
    if (!(seconds > 0 && seconds <= 3600)) fatc::fuzz::broken("durations up to an hour", text.substr(0, 200));
  }
  return 0;
}
