#include "check.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <ostream>
#include <set>
#include <sstream>

#include "core/config/quote.hpp"
#include "core/formatted.hpp"
#include "core/program/preflight.hpp"
#include "core/rack/geometry.hpp"
#include "inputs.hpp"
#include "io/capped_lines.hpp"
#include "io/files.hpp"
#include "linuxcnc/offline/ini.hpp"
#include "linuxcnc/offline/machine_ini.hpp"

namespace fatc::io {
namespace {

std::string format_point(double x, double y, double z) {
  return formatted("%10.3f %10.3f %10.3f", x, y, z);
}

/// How many tools sit in their pockets.
std::size_t tools_in_rack(const ToolState& tools) {
  std::size_t count = 0;
  for (const auto& [number, pocket] : tools.pockets) count += tools.holds(number) ? 1 : 0;
  return count;
}

/// --check of the state file: what the component would read at start.
int check_state(const Options& options, Loaded& loaded, std::ostream& out, std::ostream& err) {
  const std::optional<Config>& config = loaded.config;
  const std::string& path = options.state_path;
  struct stat st;
  if (::stat(path.c_str(), &st) != 0 && errno == ENOENT) {
    out << shown_path(path)
        << ": no state saved yet: the component starts with each pocket holding its first-start "
           "tool\n";
    return 0;
  }
  const ToolStateResult state = config ? load_state_file(path, *config) : load_state_file(path);
  if (!state.state) {
    err << state.error << "\n";
    loaded.not_checked.push_back(fault_of("state file", path) +
                                 ": where the tools are not checked");
    return 1;
  }
  const ToolState& tools = *state.state;
  out << shown_path(path) << ": spindle "
      << (tools.spindle == 0 ? std::string("empty") : "T" + std::to_string(tools.spindle)) << ", "
      << tools_in_rack(tools) << " tools in their pockets, " << tools.lengths.size() << " lengths"
      << (tools.uncertain ? ", uncertain (an interrupted sequence)" : "") << "\n";
  return 0;
}

}  // namespace

int report(const std::vector<SequenceViolation>& violations, std::ostream& out) {
  std::vector<std::string> lines;
  for (const auto& v : violations) lines.push_back(describe(v));
  print_capped(out, lines);
  return static_cast<int>(violations.size());
}

namespace {

/// The wired sensors of `sensors` by their pins, the pocket sensors' numbers
/// after the first, and the timeout they share (the rack cover's have their
/// own): "…, pocket-…-1 2 5 (sensor_timeout_seconds 1)", or "none".
std::string sensors_wired(const Config& config) {
  const SensorConfig& wired = config.sensors;
  std::vector<std::string> pins;
  for (const SensorDeclaration& sensor : kSensors) {
    if (keyed_in(sensor, "sensors") && wired.wired(sensor.sensor)) pins.push_back(sensor.words.pin);
  }
  if (!wired.pocket_occupancy.empty()) {
    std::vector<std::string> pockets;
    for (const int pocket : wired.pocket_occupancy) pockets.push_back(std::to_string(pocket));
    pins.push_back(pocket_pin(listed(pockets, " ")));
  }
  if (pins.empty()) return "none";
  std::ostringstream timeout;
  timeout << config.sensor_timeout_seconds;
  return listed(pins, ", ") + " (sensor_timeout_seconds " + timeout.str() + ")";
}

/// --check's verdict when an input could not be read or is not valid: the
/// sequences it could still check, and last what it could not.
int partial_verdict(const Loaded& loaded, std::ostream& out) {
  if (loaded.config) {
    const SequencesChecked checked = check_sequences(*loaded.config, loaded.limits);
    const std::size_t violations = checked.violations.size();
    out << checked.sequences << " sequences checked against the rack keep-out"
        << (loaded.limits ? " and the soft limits" : "") << ", " << violations << " violation"
        << (violations == 1 ? "" : "s") << "\n";
  }
  std::string last;
  for (const std::string& part : loaded.not_checked) last += (last.empty() ? "" : "; ") + part;
  out << last << "\n";
  return 1;
}

/// The tools of the table the rack cannot carry across (carried_tools),
/// after what the table's lines say of themselves (skipped, read in pieces, a tool twice).
void report_carried(const Config& config, const Loaded& loaded, const SequencesChecked& checked,
                    std::ostream& out) {
  out << "\ntools of " << shown_path(*loaded.table_path)
      << " carried across the rack (a tool of no known length counts as "
      << format_length(config, loaded.lengths.longest) << ", the longest the config allows):\n";
  print_capped(out, loaded.table_skipped);
  // The tools it cannot carry, then how many fit.
  std::vector<std::string> lines = carried_tools(config, loaded.lengths, loaded.measured, checked);
  const std::string fit = lines.back();
  lines.pop_back();
  print_capped(out, lines);
  out << "  " << fit << "\n";
}

}  // namespace

int check(const Options& options, std::ostream& out, std::ostream& err) {
  Loaded loaded = load(options, err);
  int problems = loaded.problems + check_state(options, loaded, out, err);
  if (options.ini_path) {
    std::string error;
    if (const auto ini = IniFile::read(*options.ini_path, error)) {
      const Config* config = loaded.config ? &*loaded.config : nullptr;
      const auto section = executor_problems(*ini, config);
      for (const auto& problem : section) err << problem << "\n";
      problems += static_cast<int>(section.size());
      for (const auto& move : builtin_m6_moves(*ini)) {
        err << ini->path() << ": " << move << "\n";
        ++problems;
      }
      if (!section.empty()) {
        loaded.not_checked.push_back("INI [FIXED_ATC_PROBE] not valid (" +
                                     std::to_string(section.size()) +
                                     (section.size() == 1 ? " problem" : " problems") +
                                     "): M6, the panel's flows and the chuck M-codes would not run as set up");
      }
    }
  }
  if (!loaded.not_checked.empty()) return partial_verdict(loaded, out);
  const Config& config = *loaded.config;
  out << shown_path(options.config_path) << ": units " << units_name(config.units) << ", "
      << config.pockets.size() << " pockets, keep-out margin " << config.keepout_margin() << "\n";
  const auto defaults = defaulted_words(config);
  if (!defaults.empty()) {
    out << "defaults taken (the keys left out, in " << units_name(config.units) << "):\n";
    for (const std::string& line : defaults) out << "  " << line << "\n";
  }
  out << "sensors wired: " << sensors_wired(config) << "\nmeasuring:\n";
  for (const std::string& line : measuring_words(config)) out << "  " << line << "\n";
  out << "\n";
  out << "station                          x          y          z\n";
  out << "safe                  " << format_point(config.safe.x, config.safe.y, config.safe.z)
      << "\n";
  out << "loading               "
      << format_point(config.loading.x, config.loading.y, config.loading.z) << "\n";
  out << "probe_limit           "
      << format_point(config.probe_limit.x, config.probe_limit.y, config.probe_limit.z) << "\n";
  if (const auto note = loading_note(config)) out << *note << "\n";
  for (const auto& [number, pocket] : config.pockets) {
    const auto w = pocket_waypoints(config, number);
    const std::string name = "pocket " + std::to_string(number);
    out << name << std::string(22 - name.size(), ' ')
        << format_point(w.pocket.x, w.pocket.y, w.pocket.z) << "  (approach "
        << approach_name(pocket.approach) << ", first tool "
        << (pocket.first_tool == 0 ? std::string("none") : "T" + std::to_string(pocket.first_tool))
        << ")\n";
    out << "  side                " << format_point(w.side.x, w.side.y, w.side.z) << "\n";
    out << "  above_chuck         "
        << format_point(w.above_chuck.x, w.above_chuck.y, w.above_chuck.z) << "\n";
    out << "  above_clearance     "
        << format_point(w.above_clearance.x, w.above_clearance.y, w.above_clearance.z) << "\n";
  }
  out << "\nchecking every sequence against the rack keep-out"
      << (loaded.limits ? " and the soft limits" : "") << ":\n";
  if (const auto saved = load_state_file(options.state_path, config); saved.state) {
    loaded.measured = saved.state->lengths;
  }
  const SequencesChecked checked =
      check_sequences(config, loaded.limits, loaded.lengths, loaded.measured);
  const int violations = report(checked.violations, out);
  out << checked.sequences << " sequences checked, " << violations << " violation"
      << (violations == 1 ? "" : "s") << "\n";
  if (loaded.table_path) report_carried(config, loaded, checked, out);
  if (loaded.table_unread) out << "\n" << *loaded.table_unread << "\n";
  return violations == 0 && problems == 0 ? 0 : 1;
}

}  // namespace fatc::io
