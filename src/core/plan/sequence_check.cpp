#include "sequence_check.hpp"

#include <algorithm>

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
                                              const ToolLengths& lengths) {
  const auto steps = planned.steps();
  std::vector<SequenceViolation> found;
  StepsFrom from;
  from.lengths = lengths;
  for (auto& v : check_steps(config, steps, limits, from)) {
    found.push_back({sequence, v.step, steps[v.step], std::move(v.what)});
  }
  return found;
}

SequencesChecked check_sequences(const Config& config, const std::optional<SoftLimits>& limits,
                                 const ToolLengths& lengths) {
  SequencesChecked checked;
  auto add = [&](int number, const std::string& sequence, const Simulator& planned) {
    auto found = check_sequence(sequence, config, planned, limits, lengths);
    checked.violations.insert(checked.violations.end(), std::make_move_iterator(found.begin()),
                              std::make_move_iterator(found.end()));
    ++checked.sequences;
    const auto steps = planned.steps();
    const StepRoom least = least_tip_room(config, steps);
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
    const double z = config.probe_limit.z;
    add(number, "M6 " + t + " from empty" + at, plan_change(config, full, tool, z));
    add(number, "M6 T0 from " + t + at, plan_change(config, in_spindle, 0, z));
    add(number, "load " + t + " into pocket " + std::to_string(number),
        plan_load(config, free, tool, number, z));
    add(number, "unload " + t + at, plan_unload(config, full, tool));
    add(number, "measure " + t + at,
        plan_from(config, full, {}, 0, [tool](Changer& c) { c.measure_all({tool}); }));
    add(number, "verify of pocket " + std::to_string(number) + " with " + t,
        plan_from(config, in_spindle, {}, 0, [number](Changer& c) { c.verify(number); }));
  }
  return checked;
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
