#include "cli.hpp"

#include <cstdio>
#include <ostream>

#include "core/changer.hpp"
#include "core/geometry.hpp"
#include "core/simulator.hpp"
#include "files.hpp"
#include "ini.hpp"

namespace fatc::io {

const char* const kUsage =
    "usage: fixed_atc_probe --config FILE [--state FILE]          run as a HAL component\n"
    "       fixed_atc_probe --check --config FILE [--ini FILE]    check config and rack geometry\n"
    "       fixed_atc_probe --plan --config FILE --from A --to B [--ini FILE]\n"
    "                                                             print the steps of M6 from A to B\n"
    "       fixed_atc_probe --dot                                 the state machine as Graphviz\n";

namespace {

std::optional<int> tool_argument(const std::string& text) {
  if (text.empty() || text.size() > 9) return std::nullopt;
  for (const char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
  }
  return std::stoi(text);
}

std::string format_point(double x, double y, double z) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "%10.3f %10.3f %10.3f", x, y, z);
  return buffer;
}

struct Loaded {
  std::optional<Config> config;
  std::optional<SoftLimits> limits;
};

Loaded load(const Options& options, std::ostream& err) {
  Loaded loaded;
  auto result = load_config_file(options.config_path);
  for (const auto& error : result.errors) err << error << "\n";
  if (!result.config) return loaded;
  if (!options.ini_path.empty()) {
    std::string error;
    const auto ini = IniFile::read(options.ini_path, error);
    if (ini) loaded.limits = soft_limits(*ini, result.config->units, error);
    if (!loaded.limits) {
      err << error << "\n";
      return loaded;
    }
  }
  loaded.config = result.config;
  return loaded;
}

/// Prints each violation of one planned sequence; returns how many.
int report(const std::string& name, const Config& config, const Simulator& sim,
           const std::optional<SoftLimits>& limits, std::ostream& out) {
  const auto steps = sim.steps();
  const auto violations = check_steps(config, steps, limits);
  for (const auto& v : violations) {
    out << "  " << name << ", step " << v.step + 1 << " (" << step_kind_name(steps[v.step].kind)
        << " to " << steps[v.step].label << "): " << v.what << "\n";
  }
  return static_cast<int>(violations.size());
}

int check(const Options& options, std::ostream& out, std::ostream& err) {
  const Loaded loaded = load(options, err);
  if (!loaded.config) return 1;
  const Config& config = *loaded.config;
  out << options.config_path << ": units " << units_name(config.units) << ", "
      << config.pockets.size() << " pockets, keep-out margin " << config.keepout_margin() << "\n\n";
  out << "station                          x          y          z\n";
  out << "safe                  " << format_point(config.safe.x, config.safe.y, config.safe.z) << "\n";
  out << "loading               "
      << format_point(config.loading.x, config.loading.y, config.loading.z) << "\n";
  out << "probe_limit           "
      << format_point(config.probe_limit.x, config.probe_limit.y, config.probe_limit.z) << "\n";
  for (const auto& [tool, pocket] : config.pockets) {
    const auto w = pocket_waypoints(config, tool);
    const std::string name = "pocket " + std::to_string(tool);
    out << name << std::string(22 - name.size(), ' ')
        << format_point(w.pocket.x, w.pocket.y, w.pocket.z) << "\n";
    out << "  side                " << format_point(w.side.x, w.side.y, w.side.z) << "\n";
    out << "  above_chuck         "
        << format_point(w.above_chuck.x, w.above_chuck.y, w.above_chuck.z) << "\n";
    out << "  above_clearance     "
        << format_point(w.above_clearance.x, w.above_clearance.y, w.above_clearance.z) << "\n";
  }
  out << "\nchecking every sequence against the rack keep-out"
      << (loaded.limits ? " and the soft limits" : "") << ":\n";
  int violations = 0;
  int sequences = 0;
  for (const auto& entry : config.pockets) {
    const int tool = entry.first;
    const std::string t = std::to_string(tool);
    violations += report("M6 T" + t + " from empty", config,
                         plan_change(config, 0, tool, config.probe_limit.z), loaded.limits, out);
    violations += report("M6 T0 from T" + t, config,
                         plan_change(config, tool, 0, config.probe_limit.z), loaded.limits, out);
    violations += report("load T" + t, config, plan_load(config, tool, 0, config.probe_limit.z),
                         loaded.limits, out);
    violations += report("unload T" + t, config, plan_unload(config, tool, 0), loaded.limits, out);
    sequences += 4;
  }
  out << sequences << " sequences checked, " << violations << " violation"
      << (violations == 1 ? "" : "s") << "\n";
  return violations == 0 ? 0 : 1;
}

int plan(const Options& options, std::ostream& out, std::ostream& err) {
  const Loaded loaded = load(options, err);
  if (!loaded.config) return 1;
  const Config& config = *loaded.config;
  const int from = *options.from_tool;
  const int to = *options.to_tool;
  if (from != 0 && !config.has_pocket(from)) {
    err << "--from " << from << ": tool " << from << " has no pocket in " << options.config_path
        << "\n";
    return 1;
  }
  const Simulator sim = plan_change(config, from, to, config.probe_limit.z);
  out << "M6 T" << to << " with " << (from == 0 ? std::string("an empty spindle") : "T" + std::to_string(from) + " in the spindle") << "\n";
  int number = 0;
  bool refused = false;
  for (const auto& record : sim.records) {
    if (record.kind == Record::Kind::save) continue;
    if (record.kind == Record::Kind::step && record.step.kind == StepKind::fail) refused = true;
    char prefix[16];
    std::snprintf(prefix, sizeof prefix, "%3d  ", ++number);
    out << prefix << describe(record) << "\n";
  }
  const int violations = report("M6", config, sim, loaded.limits, out);
  return refused || violations != 0 ? 1 : 0;
}

}  // namespace

std::optional<Options> parse_options(const std::vector<std::string>& args, std::string& error) {
  Options options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&](const char* name) -> std::optional<std::string> {
      if (i + 1 >= args.size()) {
        error = std::string(name) + " needs a value";
        return std::nullopt;
      }
      return args[++i];
    };
    if (arg == "--check") {
      options.mode = Options::Mode::check;
    } else if (arg == "--plan") {
      options.mode = Options::Mode::plan;
    } else if (arg == "--dot") {
      options.mode = Options::Mode::dot;
    } else if (arg == "--help" || arg == "-h") {
      options.mode = Options::Mode::help;
    } else if (arg == "--config" || arg == "--state" || arg == "--ini") {
      const auto text = value(arg.c_str());
      if (!text) return std::nullopt;
      (arg == "--config" ? options.config_path : arg == "--state" ? options.state_path : options.ini_path) = *text;
    } else if (arg == "--from" || arg == "--to") {
      const auto text = value(arg.c_str());
      if (!text) return std::nullopt;
      const auto tool = tool_argument(*text);
      if (!tool) {
        error = arg + ": expected a tool number (0 for none), got \"" + *text + "\"";
        return std::nullopt;
      }
      (arg == "--from" ? options.from_tool : options.to_tool) = *tool;
    } else {
      error = "unknown argument \"" + arg + "\"";
      return std::nullopt;
    }
  }
  const bool needs_config = options.mode == Options::Mode::component ||
                            options.mode == Options::Mode::check || options.mode == Options::Mode::plan;
  if (needs_config && options.config_path.empty()) {
    error = "--config FILE is required";
    return std::nullopt;
  }
  if (options.mode == Options::Mode::plan && (!options.from_tool || !options.to_tool)) {
    error = "--plan needs --from A and --to B";
    return std::nullopt;
  }
  return options;
}

int run_tool_mode(const Options& options, std::ostream& out, std::ostream& err) {
  switch (options.mode) {
    case Options::Mode::check: return check(options, out, err);
    case Options::Mode::plan: return plan(options, out, err);
    case Options::Mode::dot: out << Changer::dot(); return 0;
    case Options::Mode::help: out << kUsage; return 0;
    case Options::Mode::component: break;
  }
  return 2;
}

}  // namespace fatc::io
