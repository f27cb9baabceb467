#include "plan_touch.hpp"

#include <ostream>

#include "check.hpp"
#include "core/dry_run/sequence_check.hpp"
#include "core/formatted.hpp"
#include "core/rack/touch.hpp"

namespace fatc::io {
namespace {

/// The probe the touches take: --from, else the config's first tool of kind
/// probe; nullopt and the line in `why` when there is none.
std::optional<int> probe_of(const Options& options, const Config& config, std::string& why) {
  if (options.from_tool) {
    if (config.is_probe(*options.from_tool)) return *options.from_tool;
    why = "--plan --touch: T" + std::to_string(*options.from_tool) +
          " is not a probe (tools." + std::to_string(*options.from_tool) +
          ".kind): the touches need a 3D probe in the spindle";
    return std::nullopt;
  }
  for (const auto& [tool, said] : config.tools) {
    if (said.kind == ToolKind::probe) return tool;
  }
  why = "--plan --touch: config.json's tools has no tool of kind \"probe\": the touches need a "
        "3D probe in the spindle";
  return std::nullopt;
}

/// The features --touch names; nullopt and the line in `why` for one the config has not.
std::optional<std::vector<FeatureTouch>> features_of(const Options::Touched& touched,
                                                      const Config& config, double length,
                                                      std::string& why) {
  std::vector<FeatureTouch> features;
  if (touched.datum) {
    if (config.rack_touch->datum_pocket == 0) {
      why = "--touch datum: config.json's rack_touch names no datum (rack_touch.datum.pocket)";
      return std::nullopt;
    }
    features.push_back(FeatureTouch::of_datum(config, length));
    return features;
  }
  std::vector<int> pockets = touched.pockets;
  if (touched.all) {
    for (const auto& entry : config.pockets) pockets.push_back(entry.first);
  }
  for (const int pocket : pockets) {
    if (!config.has_pocket(pocket)) {
      why = "--touch: there is no pocket " + std::to_string(pocket) + " in config.json";
      return std::nullopt;
    }
    features.push_back(
        FeatureTouch::of_pocket(config, pocket, config.pockets.at(pocket).at, length));
  }
  return features;
}

}  // namespace

int plan_touch(const Options& options, const Loaded& loaded, std::ostream& out) {
  const Config& config = *loaded.config;
  if (!config.rack_touch) {
    out << "--plan --touch: config.json has no rack_touch: nothing is found by touch\n";
    return 1;
  }
  std::string why;
  const auto probe = probe_of(options, config, why);
  if (!probe) {
    out << why << "\n";
    return 1;
  }
  const double length = loaded.lengths.of(*probe, loaded.measured).length;
  const auto features = features_of(*options.touch, config, length, why);
  if (!features) {
    out << why << "\n";
    return 1;
  }
  const ExpectedTouches path = expected_touches(config, *features, *probe);
  std::string names;
  for (const FeatureTouch& feature : *features) names += (names.empty() ? "" : ", ") + feature.name();
  out << "touch " << names << " with T" << *probe << " in the spindle, "
      << format_length(config, length) << " long, rack_touch.feature \""
      << feature_name(config.rack_touch->feature) << "\"\n";
  int number = 0;
  for (const Step& step : path.steps) out << formatted("%3d  ", ++number) << describe(step) << "\n";
  out << "as touched where expected, found where config.json has them:\n";
  for (const std::string& line : found_lines(config, path.found)) out << "  " << line << "\n";
  std::vector<SequenceViolation> violations;
  const StepsFrom from{{}, 0, loaded.lengths, loaded.measured};
  for (const Violation& v : check_steps(config, path.steps, loaded.limits, from)) {
    violations.push_back({"touch", v.step, path.steps[v.step], v.what});
  }
  return report(violations, out) != 0 ? 1 : 0;
}

}  // namespace fatc::io
