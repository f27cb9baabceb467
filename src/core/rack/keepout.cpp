#include "keepout.hpp"

#include <algorithm>
#include <cmath>

#include "../formatted.hpp"

namespace fatc {
std::optional<RackEntry> rack_entry(const std::vector<RackPart>& volume, const Point& from,
                                    const Point& to, double tool_length) {
  std::optional<double> first;
  const RackPart* entered = nullptr;
  for (const RackPart& part : volume) {
    Box raised = part.box;
    raised.high.z += std::max(tool_length, 0.0);
    const auto along = entry_along(from, to, raised);
    // A move that starts inside entered before (a spindle left in a pocket):
    // it is on its way out, or the entry was named already.
    const bool starts_inside = entry_along(from, from, raised).has_value();
    if (along && !starts_inside && (!first || *along < *first)) {
      first = along;
      entered = &part;
    }
  }
  if (!entered) return std::nullopt;
  const Point nose{from.x + (to.x - from.x) * *first, from.y + (to.y - from.y) * *first,
                   from.z + (to.z - from.z) * *first};
  return RackEntry{nearest_pocket(*entered, nose), nose};
}

KeepoutState keepout_state(const Config& config, const KeepoutInputs& in) {
  if (!config.rack_keepout_all_motion) return KeepoutState::off;
  if (!in.machine_ready || !in.status_read) return KeepoutState::not_armed;
  if (in.changer_busy) return KeepoutState::lifted_for_changer;
  if (in.operator_lifts) return KeepoutState::lifted_by_operator;
  return KeepoutState::armed;
}

const char* keepout_words(KeepoutState state) {
  switch (state) {
    case KeepoutState::off:
      return "rack keep-out OFF (rack_keepout_all_motion is false)";
    case KeepoutState::armed:
      return "rack keep-out armed";
    case KeepoutState::lifted_for_changer:
      return "rack keep-out lifted for the changer's own moves";
    case KeepoutState::lifted_by_operator:
      return "rack keep-out LIFTED for teaching";
    case KeepoutState::not_armed:
      break;
  }
  return "rack keep-out not armed: the machine is not on and homed";
}

KeepoutLength ToolLengths::of(int tool, const std::map<int, double>& measured) const {
  if (tool == 0) return {};
  const auto z = table.find(tool);
  const auto own = measured.find(tool);
  const bool in_table = z != table.end() && z->second > 0.0;
  const bool measured_here = own != measured.end() && own->second > 0.0;
  // A table written relative to a master tool gives a longer tool a small Z:
  // the changer's own measurement, where longer, is the tool's. LinuxCNC
  // writes the table with six decimals: a measurement it rounded is no longer.
  constexpr double kTableDecimals = 5e-7;
  if (measured_here && (!in_table || own->second > z->second + kTableDecimals)) {
    return {own->second, LengthSource::measured};
  }
  if (in_table) return {z->second, LengthSource::table};
  return {longest, LengthSource::longest};
}

std::string keepout_length_words(const Config& config, const ToolLengths& lengths, int tool,
                                 const std::map<int, double>& measured) {
  const KeepoutLength counted = lengths.of(tool, measured);
  if (counted.source == LengthSource::table || counted.source == LengthSource::none) return {};
  const auto z = lengths.table.find(tool);
  const std::string given =
      z == lengths.table.end()
          ? "LinuxCNC's tool table gives no length"
          : "LinuxCNC's tool table gives Z" + format_length(config, z->second) +
                (z->second > 0.0 ? ", shorter than the changer measured it"
                                 : ", no length below the spindle nose");
  return "T" + std::to_string(tool) + ": " + given + "; the rack keep-out counts it as " +
         format_length(config, counted.length) +
         (counted.source == LengthSource::measured ? " (its length as the changer measured it)"
                                                   : " (the longest tool the config allows)");
}

std::string held_words(const Config& config, int tool, double tool_length) {
  if (tool == 0) return "with an empty spindle";
  return "with T" + std::to_string(tool) + " (length " + format_length(config, tool_length) + ")";
}

std::string keepout_refusal(const Config& config, const std::string& what, int pocket, int tool,
                            double tool_length, const Point& at) {
  const std::string where = formatted("X%.3f Y%.3f Z%.3f", at.x, at.y, at.z);
  return what + " would have entered the rack at pocket " + std::to_string(pocket) + " " +
         held_words(config, tool, tool_length) + ": stopped near " + where +
         " and aborted; move clear above or beside the rack";
}

}  // namespace fatc
