#include "cli.hpp"

#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <map>
#include <ostream>
#include <set>
#include <sstream>

#include "capped_lines.hpp"
#include "command_line.hpp"
#include "confirm.hpp"
#include "core/config/quote.hpp"
#include "core/dry_run/sequence_check.hpp"
#include "core/dry_run/simulator.hpp"
#include "core/formatted.hpp"
#include "core/machine/changer.hpp"
#include "core/program/preflight.hpp"
#include "core/program/tool_table.hpp"
#include "core/rack/geometry.hpp"
#include "file_writer.hpp"
#include "files.hpp"
#include "ini.hpp"
#include "lint.hpp"
#include "plot.hpp"

namespace fatc::io {
namespace {

std::string format_point(double x, double y, double z) {
  return formatted("%10.3f %10.3f %10.3f", x, y, z);
}

/// The INI's soft limits in `units`; nullopt and one line on `err` when it
/// cannot be read. Its #INCLUDE problems go first on `err`, one line each,
/// counted in `problems`: they say why a key is missing.
std::optional<SoftLimits> read_limits(const std::string& ini_path, Units units, std::ostream& err,
                                      int& problems) {
  std::string error;
  const auto ini = IniFile::read(ini_path, error);
  std::optional<SoftLimits> limits;
  if (ini) {
    for (const program::Finding& problem : ini->include_problems()) {
      err << problem.where.file << ": line " << problem.where.line << ": " << problem.text << "\n";
    }
    problems += static_cast<int>(ini->include_problems().size());
    limits = soft_limits(*ini, units, error);
  }
  if (!limits) err << error << "\n";
  return limits;
}

/// "config unreadable" or "config not valid": what kept an input from being checked.
std::string fault_of(const char* input, const std::string& path) {
  std::string ignored;
  return std::string(input) + (read_small_file(path, ignored) ? " not valid" : " unreadable");
}

struct Loaded {
  std::optional<Config> config;
  std::optional<SoftLimits> limits;
  /// LinuxCNC's tool table (--tool-table, else the INI's) in the config's
  /// units: the lengths the sequences are checked with.
  ToolLengths lengths;
  std::optional<std::string> table_path;  ///< the table read, if any
  std::vector<std::string> table_skipped;  ///< what its lines say of themselves, "line N: why"
  std::map<int, double> measured;          ///< the state file's measured lengths
  /// Why the INI's tool table was not read (LinuxCNC starts without one).
  std::optional<std::string> table_unread;
  int problems = 0;  ///< lines written to `err`
  /// What an input kept from being checked, "INI unreadable: soft limits not checked".
  std::vector<std::string> not_checked;
};

/// LinuxCNC's tool table as the keep-out reads it: --tool-table, else the
/// INI's [EMCIO]TOOL_TABLE; each Z in `units` (the table is in the INI's).
struct TableRead {
  std::optional<std::string> path;  ///< none: no table named
  std::map<int, double> lengths;
  std::string error;  ///< why it could not be read, empty when it was
  std::vector<std::string> skipped;  ///< ToolTable::problems, as "line N: why"
};
TableRead read_table(const Options& options, Units units) {
  TableRead read;
  std::string error;
  const auto ini = options.ini_path ? IniFile::read(*options.ini_path, error) : std::nullopt;
  read.path = options.tool_table_path;
  if (!read.path && ini) {
    if (const auto named = ini->get("EMCIO", "TOOL_TABLE")) {
      read.path = beside(*options.ini_path, *named);
    }
  }
  if (!read.path) return read;
  const auto text = read_small_file(*read.path, read.error);
  if (!text) return read;
  // Without an INI the table is taken in the config's units.
  const double per_mm = (ini ? ini->linear_units() : std::nullopt)
                            .value_or(units == Units::inch ? 1.0 / 25.4 : 1.0);
  const ToolTable table = parse_tool_table(*text);
  read.lengths = tool_lengths(table, units, per_mm);
  for (const LineNote& note : table.problems) {
    read.skipped.push_back("line " + std::to_string(note.line) + ": " + note.text);
  }
  return read;
}

/// The tool table's lengths into `loaded`. A --tool-table that cannot be
/// read is a problem; the INI's is only said (LinuxCNC starts without it).
void read_tool_lengths(const Options& options, Loaded& loaded, std::ostream& err) {
  const Config& config = *loaded.config;
  TableRead table = read_table(options, config.units);
  if (!table.path) return;
  if (table.error.empty()) {
    loaded.lengths = carried_lengths(config, loaded.limits, std::move(table.lengths));
    loaded.table_path = table.path;
    loaded.table_skipped = std::move(table.skipped);
  } else if (!options.tool_table_path) {
    loaded.table_unread = table.error + ": the tools' lengths not checked";
  } else {
    err << table.error << "\n";
    ++loaded.problems;
    loaded.not_checked.push_back(fault_of("tool table", *table.path) +
                                 ": the tools' lengths not checked");
  }
}

/// Reads the config and, if given, the INI; every problem one line on `err`.
Loaded load(const Options& options, std::ostream& err) {
  Loaded loaded;
  const auto result = load_config_file(options.config_path);
  for (const auto& error : result.errors) err << error << "\n";
  loaded.problems += static_cast<int>(result.errors.size());
  loaded.config = result.config;
  if (!loaded.config) {
    loaded.not_checked.push_back(fault_of("config", options.config_path) +
                                 ": the rack and its sequences not checked");
  }
  if (options.ini_path) {
    // Without a valid config the INI is still checked, its numbers as in mm.
    loaded.limits = read_limits(*options.ini_path,
                                loaded.config ? loaded.config->units : Units::mm, err,
                                loaded.problems);
    if (!loaded.limits) {
      ++loaded.problems;
      loaded.not_checked.push_back(fault_of("INI", *options.ini_path) +
                                   ": soft limits not checked");
    }
  }
  if (loaded.config) read_tool_lengths(options, loaded, err);
  return loaded;
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

/// Prints the violations, one indented line each, capped; returns how many.
int report(const std::vector<SequenceViolation>& violations, std::ostream& out) {
  std::vector<std::string> lines;
  for (const auto& v : violations) lines.push_back(describe(v));
  print_capped(out, lines);
  return static_cast<int>(violations.size());
}

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

/// Whose rack --plan and --plot show: "the rack as at first start", "the rack as PATH has it".
std::string rack_words(const Options& options) {
  if (options.state_path.empty()) return "the rack as at first start";
  struct stat st;
  // A --state that is not there (a typo, a component not started yet) is said, not taken silently.
  if (::stat(options.state_path.c_str(), &st) != 0 && errno == ENOENT) {
    return "the rack as at first start: no state saved in " + shown_path(options.state_path) +
           " yet";
  }
  return "the rack as " + shown_path(options.state_path) + " has it";
}

/// The rack at first start, or as --state has it (nothing uncertain, nothing
/// under way); nullopt and the line on `err` when the state file is bad.
std::optional<ToolState> rack_of(const Options& options, const Config& config, std::ostream& err) {
  if (options.state_path.empty()) return ToolState::fresh(config);
  auto saved = load_state_file(options.state_path, config);
  if (!saved.state) {
    err << saved.error << "\n";
    return std::nullopt;
  }
  saved.state->uncertain = false;
  saved.state->in_progress.reset();
  return saved.state;
}

/// "an empty spindle", "T3 in the spindle": the spindle a planned change starts from.
std::string spindle_words(int tool) {
  return tool == 0 ? "an empty spindle" : "T" + std::to_string(tool) + " in the spindle";
}

/// Why the changer refuses the planned change, if it does: its fail step's words.
std::optional<std::string> refusal(const Simulator& plan) {
  for (const Step& step : plan.steps()) {
    if (step.kind == StepKind::fail) return step.label;
  }
  return std::nullopt;
}

/// --plot: the rack from above into an SVG file, with the path of one change if asked.
int plot(const Options& options, std::ostream& out, std::ostream& err) {
  const Loaded loaded = load(options, err);
  if (!loaded.config || loaded.problems > 0) return 1;
  const Config& config = *loaded.config;
  auto rack = rack_of(options, config, err);
  if (!rack) return 1;
  std::string title = shown_path(options.config_path);
  std::optional<Simulator> change;
  if (options.from_tool) {
    rack->put_in_spindle(*options.from_tool);
    change = plan_change(config, *rack, *options.to_tool, config.probe_limit.z);
    if (const auto why = refusal(*change)) {
      err << *why << "\n";
      return 1;
    }
    title += ": M6 T" + std::to_string(*options.to_tool) + " with " +
             spindle_words(*options.from_tool) + ", the " +
             (config.path == Path::direct ? "direct" : "prototype") + " path";
  }
  try {
    const std::string drawing = rack_svg(config, *rack, change ? &*change : nullptr,
                                         loaded.limits ? &*loaded.limits : nullptr, title);
    write_file(options.plot_path, drawing, kCommandLineWait);
  } catch (const std::exception& e) {
    err << e.what() << "\n";
    return 2;
  }
  out << "wrote " << shown_path(options.plot_path) << ": " << config.pockets.size()
      << (config.pockets.size() == 1 ? " pocket" : " pockets")
      << (change ? ", and the path of the change" : "") << ", " << rack_words(options) << "\n";
  return 0;
}

/// The planned change's time on its path and on the other one, as --lint
/// estimates it (change_time), and the bound.
void print_estimate(const Options& options, const Config& config, const ToolState& tools, int to,
                    const Simulator& sim, std::ostream& out) {
  std::string error;
  const auto motion = machine_motion(options.ini_path, config, error);
  if (!motion) return;  // the INI was read already: this cannot fail now
  Config other = config;
  other.path = config.path == Path::direct ? Path::prototype : Path::direct;
  const Simulator other_sim = plan_change(other, tools, to, config.probe_limit.z);
  const ChangeTime time = change_time(sim, config.safe, motion->timing);
  const ChangeTime other_time = change_time(other_sim, config.safe, motion->timing);
  const char* name = config.path == Path::direct ? "direct" : "prototype";
  const char* other_name = config.path == Path::direct ? "prototype" : "direct";
  const std::string parts = formatted("(moves %.2f s, dwells %.2f s, %d step%s)", time.moves,
                                      time.dwells, time.steps, time.steps == 1 ? "" : "s");
  // Two lines: the figures, then how they were worked out (a line stays under 400 characters).
  out << "estimated " << seconds_text(time.seconds()) << " on the " << name << " path ("
      << seconds_text(other_time.seconds()) << " on the " << other_name << " path) " << parts
      << ", the operator not counted\n"
      << "  from safe: " << motion->source << ", " << estimate_costs_text(motion->timing) << "\n";
  if (config.blend_tolerance > 0.0) {
    out << "  blend_tolerance: a blended run counted as one step, its moves as exact stops; its "
           "rounded corners save more\n";
  }
  if (!options.ini_path) {
    out << "bound: --ini gives it (the machine's velocities and accelerations)\n";
    return;
  }
  const auto ini = IniFile::read(*options.ini_path, error);
  const auto limits = ini ? motion_limits(*ini, config.units, error) : std::nullopt;
  if (!limits) {
    out << "bound: not known: " << error << "\n";
    return;
  }
  const Simulator& direct = config.path == Path::direct ? sim : other_sim;
  const Simulator& prototype = config.path == Path::direct ? other_sim : sim;
  out << "bound " << seconds_text(limits_seconds(direct, config.safe, *limits))
      << ": the direct path's moves at the velocities and accelerations of "
      << shown_path(*options.ini_path) << ", each an exact stop, plus the dwells (the prototype "
      << "path's: " << seconds_text(limits_seconds(prototype, config.safe, *limits))
      << "; with each run of rapids as one move, more than blending could save: "
      << seconds_text(blended_seconds(direct, config.safe, *limits)) << ")\n";
  if (!config.move_while_spindle_stops) return;
  Config direct_config = config;
  direct_config.path = Path::direct;
  const Simulator running = plan_change_running_down(direct_config, tools, to, config.probe_limit.z);
  const double meanwhile = limits_seconds_while_running_down(running, config.safe, *limits);
  out << "while the spindle runs down: " << seconds_text(meanwhile)
      << " of the bound's moves (" << (config.rack_cover ? "up to safe Z" : "up to safe Z and across at it")
      << "), the rest "
      << seconds_text(limits_seconds(running, config.safe, *limits) - meanwhile)
      << " once it stands\n";
}

int plan(const Options& options, std::ostream& out, std::ostream& err) {
  const Loaded loaded = load(options, err);
  if (!loaded.config || loaded.problems > 0) return 1;
  const Config& config = *loaded.config;
  const int from = *options.from_tool;
  const int to = *options.to_tool;
  auto rack = rack_of(options, config, err);
  if (!rack) return 1;
  ToolState& tools = *rack;
  tools.put_in_spindle(from);
  const Simulator sim = plan_change(config, tools, to, config.probe_limit.z);
  out << "M6 T" << to << " with " << spindle_words(from) << ", " << rack_words(options) << "\n";
  int number = 0;
  for (const auto& record : sim.records) {
    if (record.kind == Record::Kind::save) continue;
    out << formatted("%3d  ", ++number) << describe(record) << "\n";
  }
  const int violations =
      report(check_sequence("M6", config, sim, loaded.limits, {{}, 0, loaded.lengths, tools.lengths}),
             out);
  const bool refused = refusal(sim).has_value();
  if (!refused) print_estimate(options, config, tools, to, sim, out);
  return refused || violations != 0 ? 1 : 0;
}

}  // namespace


namespace {

/// --teach: the machine position into config.json, the file as it was kept as PATH.bak.
/// The config is taken before it is read: a teach at the same time (here or
/// in the component) waits its turn and then reads what this one wrote.
int teach_position(const Options& options, std::ostream& out, std::ostream& err) {
  try {
    const FileWriter config(options.config_path, kCommandLineWait);
    std::string error;
    const auto text = read_small_file(options.config_path, error);
    if (!text) {
      err << error << "\n";
      return 2;
    }
    std::optional<SoftLimits> limits;
    if (options.ini_path) {
      int problems = 0;  // said; a teach needs only the limits
      limits = read_limits(*options.ini_path, declared_units(*text), err, problems);
      if (!limits) return 2;
    }
    TableRead table = read_table(options, declared_units(*text));
    if (!table.error.empty() && options.tool_table_path) {
      err << table.error << "\n";
      return 2;
    }
    ToolLengths lengths;
    lengths.table = std::move(table.lengths);
    const TeachResult taught =
        teach(*text, *options.teach_target, *options.teach_at, limits, lengths);
    if (!taught.text) {
      err << shown_path(options.config_path) << ": " << taught.error << "\n";
      return 1;
    }
    save_config_file(config, *text, *taught.text, kCommandLineWait);
    out << taught.change << "\n"
        << "written (previous file kept as " << shown_path(options.config_path + ".bak") << ")\n";
    return 0;
  } catch (const std::exception& e) {
    err << e.what() << "\n";
    return 2;
  }
}

/// A file given on the command line, as a message names it.
struct GivenFile {
  std::string name;  ///< "--plot \"rack.svg\"", "the backup \"config.json.bak\""
  std::string path;
};

}  // namespace

std::string written_onto_input(const Options& options) {
  std::vector<GivenFile> written;
  std::vector<GivenFile> inputs;
  switch (options.mode) {
    case Options::Mode::plot:
      written = {{"--plot " + quote(options.plot_path, 200), options.plot_path}};
      inputs = {{"--config", options.config_path}, {"--state", options.state_path}};
      break;
    case Options::Mode::teach: {
      const std::string backup = options.config_path + ".bak";
      written = {{"the backup " + quote(backup, 200), backup}};
      inputs = {{"--ini", options.ini_path.value_or("")}};
      break;
    }
    case Options::Mode::confirm:
    case Options::Mode::component:
      written = {{"--state " + quote(options.state_path, 200), options.state_path}};
      inputs = {{"--config", options.config_path}};
      break;
    default:
      break;
  }
  for (const GivenFile& output : written) {
    for (const GivenFile& input : inputs) {
      if (input.path.empty() || !same_file(output.path, input.path)) continue;
      return output.name + " is the file given as " + input.name + ": nothing written";
    }
  }
  return "";
}

Options with_state_of_ini(Options options) {
  const bool reads_it = options.mode == Options::Mode::check ||
                        options.mode == Options::Mode::lint ||
                        options.mode == Options::Mode::operator_request;
  if (!reads_it || options.state_given || !options.ini_path) return options;
  std::string error;
  const auto ini = IniFile::read(*options.ini_path, error);
  if (!ini) return options;  // the INI's own check says why
  if (const auto state = ini->get("FIXED_ATC_PROBE", "STATE"); state && !state->empty()) {
    options.state_path =
        (*state)[0] == '/' ? *state : folder_of(*options.ini_path) + "/" + *state;
  }
  return options;
}

namespace {

int run_mode(const Options& given, std::ostream& out, std::ostream& err) {
  const Options options = with_state_of_ini(given);
  if (const std::string refused = written_onto_input(options); !refused.empty()) {
    err << refused << "\n";
    return 2;
  }
  switch (options.mode) {
    case Options::Mode::check:
      return check(options, out, err);
    case Options::Mode::plan:
      return plan(options, out, err);
    case Options::Mode::dot:
      out << Changer::dot();
      return 0;
    case Options::Mode::confirm:
      return confirm(options, out, err);
    case Options::Mode::lint:
      return lint(options, out, err);
    case Options::Mode::teach:
      return teach_position(options, out, err);
    case Options::Mode::plot:
      return plot(options, out, err);
    case Options::Mode::help:
      out << usage();
      return 0;
    case Options::Mode::component:
    case Options::Mode::version:  // main's: the version is linked into the program alone
    case Options::Mode::operator_request:  // HAL's: src/linuxcnc/operator_command.cpp
      break;
  }
  return 2;
}

}  // namespace

int run_tool_mode(const Options& options, std::ostream& out, std::ostream& err) {
  // Graphviz and the usage are ours alone; every other line may hold a file's text.
  if (options.mode == Options::Mode::dot || options.mode == Options::Mode::help) {
    return run_mode(options, out, err);
  }
  CappedLines out_lines(out), err_lines(err);
  std::ostream capped_out(&out_lines), capped_err(&err_lines);
  const int code = run_mode(options, capped_out, capped_err);
  capped_out.flush();
  capped_err.flush();
  return code;
}

}  // namespace fatc::io
