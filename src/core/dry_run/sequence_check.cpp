#include "sequence_check.hpp"

#include <algorithm>
#include <cmath>

#include "../formatted.hpp"
#include "../rack/touch.hpp"

namespace fatc {

std::string describe(const SequenceViolation& violation) {
  return violation.sequence + ", step " + std::to_string(violation.step + 1) + " (" +
         step_kind_name(violation.move.kind) + " to " + violation.move.label +
         "): " + violation.what;
}

std::string describe(const SequenceRoom& room) {
  return room.sequence + ", step " + std::to_string(room.step + 1) + " (" +
         step_kind_name(room.move.kind) + " to " + room.move.label + ") over pocket " +
         std::to_string(room.holder);
}

std::vector<SequenceViolation> check_sequence(const std::string& sequence, const Config& config,
                                              const Simulator& planned,
                                              const std::optional<SoftLimits>& limits,
                                              const StepsFrom& from) {
  const auto steps = planned.steps();
  std::vector<SequenceViolation> found;
  for (auto& v : check_steps(config, steps, limits, from)) {
    found.push_back({sequence, v.step, steps[v.step], std::move(v.what)});
  }
  return found;
}

SequencesChecked check_sequences(const Config& config, const std::optional<SoftLimits>& limits,
                                 const ToolLengths& lengths,
                                 const std::map<int, double>& measured) {
  SequencesChecked checked;
  const StepsFrom from_safe{config.safe, axis_xyz, lengths, measured};
  auto add = [&](int number, const std::string& sequence, const Simulator& planned) {
    auto found = check_sequence(sequence, config, planned, limits, from_safe);
    checked.violations.insert(checked.violations.end(), std::make_move_iterator(found.begin()),
                              std::make_move_iterator(found.end()));
    ++checked.sequences;
    const auto steps = planned.steps();
    const StepRoom least = least_tip_room(config, steps, config.safe);
    if (least.room.pocket == 0) return;
    const auto known = checked.room.find(number);
    if (known == checked.room.end() || least.room.length < known->second.length) {
      checked.room[number] = {least.room.length, sequence, least.step, steps[least.step],
                              least.room.pocket};
    }
  };
  for (const auto& [number, pocket] : config.pockets) {
    // The pocket with a tool in it: its first-start tool, or, when it starts
    // empty, one that neither a pocket nor the tool table knows (its length
    // is the longest the config allows, what these plans find).
    int tool = pocket.first_tool;
    if (tool == 0) {
      tool = 1;
      while (config.first_pocket_of(tool) || lengths.table.count(tool)) ++tool;
    }
    ToolState full = ToolState::fresh(config);
    full.pockets[number] = {tool, true};
    ToolState in_spindle = full;
    in_spindle.put_in_spindle(tool);
    ToolState free = full;
    free.pockets[number] = {};
    const std::string t = "T" + std::to_string(tool);
    const std::string at = " (pocket " + std::to_string(number) + ")";
    auto from_safe = [&](const ToolState& tools, const std::function<void(Changer&)>& request) {
      return plan_from(config, tools, config.safe, axis_xyz, request);
    };
    add(number, "M6 " + t + " from empty" + at,
        from_safe(full, [tool](Changer& c) { c.tool_change(tool); }));
    add(number, "M6 T0 from " + t + at, from_safe(in_spindle, [](Changer& c) { c.tool_change(0); }));
    add(number, "load " + t + " into pocket " + std::to_string(number),
        from_safe(free, [tool, number](Changer& c) { c.load(tool, number); }));
    add(number, "unload " + t + at, from_safe(full, [tool](Changer& c) { c.unload(tool); }));
    add(number, "measure " + t + at, from_safe(full, [tool](Changer& c) { c.measure_all({tool}); }));
    add(number, "verify of pocket " + std::to_string(number) + " with " + t,
        from_safe(in_spindle, [number](Changer& c) { c.verify(number); }));
  }
  // Each pocket found by touch (rack_touch), with each probe of `tools`.
  if (!config.rack_touch) return checked;
  for (const auto& [probe, said] : config.tools) {
    if (said.kind != ToolKind::probe) continue;
    const double length = lengths.of(probe, measured).length;
    for (const auto& [number, pocket] : config.pockets) {
      const ExpectedTouches path =
          expected_touches(config, {FeatureTouch::of_pocket(config, number, pocket.at, length)}, probe);
      const std::string sequence =
          "touch pocket " + std::to_string(number) + " with T" + std::to_string(probe);
      for (const Violation& v : check_steps(config, path.steps, limits, from_safe)) {
        checked.violations.push_back({sequence, v.step, path.steps[v.step], v.what});
      }
      ++checked.sequences;
    }
  }
  return checked;
}

std::optional<std::string> loading_note(const Config& config) {
  const double off = std::hypot(config.loading.x - config.probe_limit.x,
                                config.loading.y - config.probe_limit.y);
  if (off <= (config.units == Units::inch ? 0.04 : 1.0)) return std::nullopt;
  const std::string where =
      formatted("loading X%.3f Y%.3f is not over the touch-off sensor (probe_limit X%.3f Y%.3f)",
                config.loading.x, config.loading.y, config.probe_limit.x, config.probe_limit.y);
  return std::string("note: ") + where + ", " + format_length(config, off) +
         " off: a load measures straight down from loading, so each load needs a jog over the "
         "sensor at its second prompt; set loading's x and y to probe_limit's to spare it";
}

std::vector<std::string> carried_tools(const Config& config, const ToolLengths& lengths,
                                       const std::map<int, double>& measured,
                                       const SequencesChecked& checked) {
  std::vector<std::string> lines;
  int fit = 0;
  for (const auto& [tool, z] : lengths.table) {
    const KeepoutLength counted = lengths.of(tool, measured);
    if (counted.source != LengthSource::table) {
      lines.push_back(keepout_length_words(config, lengths, tool, measured));
    }
    std::vector<int> too_short;
    const SequenceRoom* least = nullptr;
    for (const auto& [pocket, room] : checked.room) {
      if (counted.length <= room.length + 1e-9) continue;
      too_short.push_back(pocket);
      if (!least || room.length < least->length) least = &room;
    }
    if (!least) {
      ++fit;
      continue;
    }
    lines.push_back("T" + std::to_string(tool) + " (length " +
                    format_length(config, counted.length) + ") cannot be carried through " +
                    pocket_list(too_short) + ": " + describe(*least) + " leaves " +
                    format_length(config, least->length) + " below the nose; " + tip_remedy());
  }
  lines.push_back(std::to_string(fit) + (fit == 1 ? " tool" : " tools") +
                  " of the table fit every pocket");
  return lines;
}

double longest_carried(const Config& config, const SequencesChecked& checked) {
  double longest = config.pocket_above_clearance_offset_z - config.pocket_above_chuck_offset_z;
  for (const auto& [pocket, room] : checked.room) longest = std::min(longest, room.length);
  return std::max(longest, 0.0);
}

ToolLengths carried_lengths(const Config& config, const std::optional<SoftLimits>& limits,
                            std::map<int, double> table) {
  ToolLengths lengths;
  lengths.longest = longest_carried(config, check_sequences(config, limits));
  lengths.table = std::move(table);
  return lengths;
}

}  // namespace fatc
