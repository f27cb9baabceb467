#include "sequence_check.hpp"

namespace fatc {

std::string describe(const SequenceViolation& violation) {
  return violation.sequence + ", step " + std::to_string(violation.step + 1) + " (" +
         step_kind_name(violation.move.kind) + " to " + violation.move.label +
         "): " + violation.what;
}

std::vector<SequenceViolation> check_sequence(const std::string& sequence, const Config& config,
                                              const Simulator& planned,
                                              const std::optional<SoftLimits>& limits) {
  const auto steps = planned.steps();
  std::vector<SequenceViolation> found;
  for (auto& v : check_steps(config, steps, limits)) {
    found.push_back({sequence, v.step, steps[v.step], std::move(v.what)});
  }
  return found;
}

SequencesChecked check_sequences(const Config& config, const std::optional<SoftLimits>& limits) {
  SequencesChecked checked;
  auto add = [&](const std::string& sequence, const Simulator& planned) {
    auto found = check_sequence(sequence, config, planned, limits);
    checked.violations.insert(checked.violations.end(), std::make_move_iterator(found.begin()),
                              std::make_move_iterator(found.end()));
    ++checked.sequences;
  };
  for (const auto& [number, pocket] : config.pockets) {
    // The pocket with a tool in it: its first-start tool, or one no pocket
    // starts with when it starts empty.
    int tool = pocket.first_tool;
    if (tool == 0) {
      tool = 1;
      while (config.first_pocket_of(tool)) ++tool;
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
    add("M6 " + t + " from empty" + at, plan_change(config, full, tool, z));
    add("M6 T0 from " + t + at, plan_change(config, in_spindle, 0, z));
    add("load " + t + " into pocket " + std::to_string(number),
        plan_load(config, free, tool, number, z));
    add("unload " + t + at, plan_unload(config, full, tool));
  }
  return checked;
}

}  // namespace fatc
