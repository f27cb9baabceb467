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
  for (const auto& entry : config.pockets) {
    const int tool = entry.first;
    const std::string t = std::to_string(tool);
    add("M6 T" + t + " from empty", plan_change(config, 0, tool, config.probe_limit.z));
    add("M6 T0 from T" + t, plan_change(config, tool, 0, config.probe_limit.z));
    add("load T" + t, plan_load(config, tool, 0, config.probe_limit.z));
    add("unload T" + t, plan_unload(config, tool, 0));
  }
  return checked;
}

}  // namespace fatc
