#include "measuring.hpp"

namespace fatc {

Measuring measuring_of(const Config& config, int tool, bool known) {
  Measuring measuring;
  measuring.rule = config.rule_of(tool);
  switch (measuring.rule) {
    case MeasureRule::always:
      measuring.after_change = true;
      break;
    case MeasureRule::check:
      measuring.after_change = true;
      // A check of a tool the changer has no length of measures it.
      measuring.checks = known;
      break;
    case MeasureRule::when_new:
      measuring.after_change = !known;
      break;
    case MeasureRule::off:
      break;
    case MeasureRule::never:
      measuring.never = true;
      break;
  }
  return measuring;
}

CheckTolerance check_tolerance_for(const Config& config, int tool) {
  const auto own = config.tools.find(tool);
  if (own != config.tools.end() && own->second.check_tolerance) {
    return {*own->second.check_tolerance, "tools." + std::to_string(tool) + ".check_tolerance"};
  }
  return {config.check_tolerance(), "probe_check_tolerance"};
}

double Config::check_tolerance_of(int tool) const {
  return check_tolerance_for(*this, tool).length;
}

}  // namespace fatc
