#include "pocket_reading.hpp"

#include <cstdint>
#include <map>

namespace fatc::reading {
namespace {

/// A fixed rack with more pockets than this is a mistake, and checking every
/// pair of pockets and every planned move against every pocket is quadratic.
constexpr std::size_t kMaxPockets = 200;

/// What a pocket entry and pocket_default may say besides x, y and z.
struct PocketExtras {
  std::optional<Approach> approach;
  std::optional<PlanarOffset> side_offset;
  bool failed = false;  ///< one of them was given but refused (reported)
};

PocketExtras pocket_extras(Reader& reader, const Json& entry, const std::string& here) {
  PocketExtras extras;
  // Both x and y, each within pocket_side_offset's bounds.
  const Range side_bounds = bounds_in(key("pocket_side_offset.x"), reader.units);
  if (const auto approach = entry.find("approach"); approach != entry.end()) {
    if (*approach == "side") {
      extras.approach = Approach::side;
    } else if (*approach == "top") {
      extras.approach = Approach::top;
    } else {
      reader.error(join_path(here, "approach"),
                   "expected \"side\" or \"top\", got " + describe(*approach));
      extras.failed = true;
    }
  }
  if (entry.contains("side_offset")) {
    const Json* side = reader.object(entry, here, "side_offset", true);
    const std::string at = join_path(here, "side_offset");
    if (side) reader.reject_unknown_keys(*side, at);
    const auto x = side ? reader.ranged(*side, at, "x", side_bounds, true) : std::nullopt;
    const auto y = side ? reader.ranged(*side, at, "y", side_bounds, true) : std::nullopt;
    if (x && y) {
      extras.side_offset = PlanarOffset{*x, *y};
    } else {
      extras.failed = true;
    }
  }
  return extras;
}

/// `tool` of a pocket entry: the tool it holds at first start, 0 for none.
std::optional<int> first_tool(Reader& reader, const Json& entry, const std::string& here,
                              int pocket) {
  const auto tool = entry.find("tool");
  if (tool == entry.end()) return pocket;
  if (tool->is_number_integer() && tool->get<std::int64_t>() == 0) return 0;
  if (!is_tool_number(*tool)) {
    reader.error(
        join_path(here, "tool"),
        "expected a tool number (1 to 999999999) or 0 (starts empty), got " + describe(*tool));
    return std::nullopt;
  }
  return tool->get<int>();
}

}  // namespace

void read_pockets(Reader& reader, const Json& root, Config& config) {
  Reader::PartialPoint fallback;
  PocketExtras common;
  if (const Json* defaults = reader.object(root, "", "pocket_default", false)) {
    reader.reject_unknown_keys(*defaults, "pocket_default");
    fallback = reader.partial_point(*defaults, "pocket_default");
    common = pocket_extras(reader, *defaults, "pocket_default");
  }
  const auto defaults = root.find("pocket_default");
  auto default_given = [&](const char* axis) {
    return defaults != root.end() && (!defaults->is_object() || defaults->contains(axis));
  };
  const Json* pockets = reader.object(root, "", "pockets", true);
  if (!pockets) return;
  if (pockets->empty()) {
    reader.error("pockets", "no pockets defined; add at least one, e.g. \"1\": {\"x\": 10}");
    return;
  }
  if (pockets->size() > kMaxPockets) {
    reader.error("pockets", "must hold at most " + std::to_string(kMaxPockets) + " pockets, got " +
                                std::to_string(pockets->size()));
    return;
  }
  std::map<int, int> pocket_of_tool;  // first-start tool -> its pocket, for duplicates
  for (const auto& item : pockets->items()) {
    const std::string here = join_path("pockets", item.key());
    const auto number = tool_number_key(item.key());
    if (!number) {
      reader.error(here, "the key must be a pocket number, a positive integer like \"7\"");
      continue;
    }
    if (!item.value().is_object()) {
      reader.error(here, "expected an object, got " + describe(item.value()));
      continue;
    }
    reader.reject_unknown_keys(item.value(), here);
    const auto own = reader.partial_point(item.value(), here);
    const PocketExtras extras = pocket_extras(reader, item.value(), here);
    const auto tool = first_tool(reader, item.value(), here, *number);
    bool complete = tool.has_value() && !extras.failed && !common.failed;
    auto merge = [&](const std::optional<double>& mine, const std::optional<double>& shared,
                     const char* axis) {
      if (mine) return *mine;
      if (shared) return *shared;
      // A pocket_default that has the axis but failed was reported once already.
      if (!default_given(axis)) {
        reader.error(join_path(here, axis),
                     std::string("missing, and pocket_default has no ") + axis);
      }
      complete = false;
      return 0.0;
    };
    Pocket pocket;
    pocket.at = {merge(own.x, fallback.x, "x"), merge(own.y, fallback.y, "y"),
                 merge(own.z, fallback.z, "z")};
    if (tool && *tool != 0) {
      if (const auto [other, fresh] = pocket_of_tool.emplace(*tool, *number); !fresh) {
        reader.error(join_path(here, "tool"), "tool " + std::to_string(*tool) +
                                                  " already starts in pocket " +
                                                  std::to_string(other->second));
        complete = false;
      }
    }
    if (!complete) continue;
    pocket.first_tool = *tool;
    pocket.approach = extras.approach.value_or(common.approach.value_or(Approach::side));
    pocket.side_offset =
        extras.side_offset.value_or(common.side_offset.value_or(config.pocket_side_offset));
    config.pockets[*number] = pocket;
  }
}

}  // namespace fatc::reading
