#include "cli.hpp"

#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <ostream>
#include <set>
#include <sstream>

#include "core/machine/changer.hpp"
#include "core/rack/geometry.hpp"
#include "core/program/preflight.hpp"
#include "core/config/quote.hpp"
#include "core/plan/sequence_check.hpp"
#include "core/plan/simulator.hpp"
#include "files.hpp"
#include "ini.hpp"
#include "confirm.hpp"
#include "lint.hpp"
#include "plot.hpp"

namespace fatc::io {

const char* const kUsage =
    "usage: fixed_atc_probe --config FILE [--state FILE]          run as a HAL component\n"
    "       fixed_atc_probe --check --config FILE [--ini FILE] [--state FILE]\n"
    "                                     check config, state, INI and rack geometry\n"
    "       fixed_atc_probe --plan --config FILE --from A --to B [--ini FILE]\n"
    "                                     print the steps of M6 from A to B\n"
    "       fixed_atc_probe --confirm --config FILE [--state FILE] --spindle N [--pocket yes|no]\n"
    "                                     after a fault, with LinuxCNC stopped: the spindle\n"
    "                                     holds tool N (0 empty), the cut-off pocket holds its\n"
    "                                     tool or not; clears the fault in the state file\n"
    "       fixed_atc_probe --lint PROGRAM.ngc --config FILE [--state FILE] [--tool-table FILE]\n"
    "                       [--ini FILE] [--subroutine-path DIR:DIR]\n"
    "                                     read a G-code program without running it: its tool\n"
    "                                     changes, the rack, lengths, problems, change time\n"
    "       fixed_atc_probe --teach pocket:N|loading|safe|sensor --at X,Y,Z --config FILE\n"
    "                       [--ini FILE]\n"
    "                                     write a machine position (G53) into config.json,\n"
    "                                     checked as --check checks; the old file kept as\n"
    "                                     FILE.bak (sensor: X and Y only)\n"
    "       fixed_atc_probe --plot FILE.svg --config FILE [--state FILE] [--from A --to B]\n"
    "                                     draw the rack from above, and the path of M6 A to B\n"
    "       fixed_atc_probe --dot         the state machine as Graphviz\n";

namespace {

std::optional<int> tool_argument(const std::string& text) {
  if (text.empty() || text.size() > 9) return std::nullopt;
  for (const char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
  }
  return std::stoi(text);
}

/// "X,Y,Z": three numbers, nothing else.
std::optional<Point> position_argument(const std::string& text) {
  double values[3];
  std::size_t at = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const std::size_t end = axis < 2 ? text.find(',', at) : text.size();
    if (end == std::string::npos) return std::nullopt;
    const std::string part = text.substr(at, end - at);
    if (part.empty() || std::isspace(static_cast<unsigned char>(part[0]))) return std::nullopt;
    char* stop = nullptr;
    values[axis] = std::strtod(part.c_str(), &stop);
    if (stop != part.c_str() + part.size()) return std::nullopt;
    at = end + 1;
  }
  return Point{values[0], values[1], values[2]};
}

std::string format_point(double x, double y, double z) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "%10.3f %10.3f %10.3f", x, y, z);
  return buffer;
}

/// The INI's soft limits in `units`; nullopt and one line on `err` when it cannot be read.
std::optional<SoftLimits> read_limits(const std::string& ini_path, Units units, std::ostream& err) {
  std::string error;
  const auto ini = IniFile::read(ini_path, error);
  std::optional<SoftLimits> limits;
  if (ini) limits = soft_limits(*ini, units, error);
  if (!limits) err << error << "\n";
  return limits;
}

struct Loaded {
  std::optional<Config> config;
  std::optional<SoftLimits> limits;
  int problems = 0;  ///< lines written to `err`
};

/// Reads the config and, if given, the INI; every problem one line on `err`.
Loaded load(const Options& options, std::ostream& err) {
  Loaded loaded;
  const auto result = load_config_file(options.config_path);
  for (const auto& error : result.errors) err << error << "\n";
  loaded.problems += static_cast<int>(result.errors.size());
  loaded.config = result.config;
  if (options.ini_path) {
    // Without a valid config the INI is still checked, its numbers as in mm.
    loaded.limits =
        read_limits(*options.ini_path, loaded.config ? loaded.config->units : Units::mm, err);
    if (!loaded.limits) ++loaded.problems;
  }
  return loaded;
}

/// How many tools sit in their pockets.
std::size_t tools_in_rack(const ToolState& tools) {
  std::size_t count = 0;
  for (const auto& [number, pocket] : tools.pockets) count += tools.holds(number) ? 1 : 0;
  return count;
}

/// --check of the state file: what the component would read at start.
int check_state(const Options& options, const std::optional<Config>& config, std::ostream& out,
                std::ostream& err) {
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
    return 1;
  }
  const ToolState& tools = *state.state;
  out << shown_path(path) << ": spindle "
      << (tools.spindle == 0 ? std::string("empty") : "T" + std::to_string(tools.spindle)) << ", "
      << tools_in_rack(tools) << " tools in their pockets, " << tools.lengths.size() << " lengths"
      << (tools.uncertain ? ", uncertain (an interrupted sequence)" : "") << "\n";
  return 0;
}

/// Prints each violation, one indented line each; returns how many.
int report(const std::vector<SequenceViolation>& violations, std::ostream& out) {
  for (const auto& v : violations) out << "  " << describe(v) << "\n";
  return static_cast<int>(violations.size());
}

/// "tool-present, air-pressure-ok, pocket-occupied-1 2 5 (sensor_timeout_seconds 1)", or "none".
std::string sensors_wired(const Config& config) {
  const SensorConfig& wired = config.sensors;
  std::string pins;
  auto add = [&](bool on, const char* pin) {
    if (on) pins += std::string(pins.empty() ? "" : ", ") + pin;
  };
  add(wired.zero_speed, "zero-speed");
  add(wired.tool_present, "tool-present");
  add(wired.drawbar_open, "drawbar-open");
  add(wired.drawbar_closed, "drawbar-closed");
  add(wired.air_pressure, "air-pressure-ok");
  if (!wired.pocket_occupancy.empty()) {
    pins += std::string(pins.empty() ? "" : ", ") + "pocket-occupied-";
    bool first = true;
    for (const int pocket : wired.pocket_occupancy) {
      pins += (first ? "" : " ") + std::to_string(pocket);
      first = false;
    }
  }
  if (pins.empty()) return "none";
  std::ostringstream timeout;
  timeout << config.sensor_timeout_seconds;
  return pins + " (sensor_timeout_seconds " + timeout.str() + ")";
}

int check(const Options& options, std::ostream& out, std::ostream& err) {
  const Loaded loaded = load(options, err);
  int problems = loaded.problems + check_state(options, loaded.config, out, err);
  if (options.ini_path) {
    std::string error;
    if (const auto ini = IniFile::read(*options.ini_path, error)) {
      const Config* config = loaded.config ? &*loaded.config : nullptr;
      for (const auto& problem : executor_problems(*ini, config)) {
        err << problem << "\n";
        ++problems;
      }
    }
  }
  if (!loaded.config) return 1;
  const Config& config = *loaded.config;
  out << shown_path(options.config_path) << ": units " << units_name(config.units) << ", "
      << config.pockets.size() << " pockets, keep-out margin " << config.keepout_margin() << "\n";
  out << "sensors wired: " << sensors_wired(config) << "\n\n";
  out << "station                          x          y          z\n";
  out << "safe                  " << format_point(config.safe.x, config.safe.y, config.safe.z)
      << "\n";
  out << "loading               "
      << format_point(config.loading.x, config.loading.y, config.loading.z) << "\n";
  out << "probe_limit           "
      << format_point(config.probe_limit.x, config.probe_limit.y, config.probe_limit.z) << "\n";
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
  const SequencesChecked checked = check_sequences(config, loaded.limits);
  const int violations = report(checked.violations, out);
  out << checked.sequences << " sequences checked, " << violations << " violation"
      << (violations == 1 ? "" : "s") << "\n";
  return violations == 0 && problems == 0 ? 0 : 1;
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
  // Written beside the drawing and renamed over it: a failed write leaves the old one.
  const std::string written = options.plot_path + ".tmp";
  std::ofstream file(written, std::ios::trunc);
  file << rack_svg(config, *rack, change ? &*change : nullptr, title);
  file.close();
  if (!file || std::rename(written.c_str(), options.plot_path.c_str()) != 0) {
    err << shown_path(options.plot_path) << ": cannot write the drawing: " << std::strerror(errno)
        << "\n";
    std::remove(written.c_str());
    return 2;
  }
  out << "wrote " << shown_path(options.plot_path) << ": " << config.pockets.size()
      << (config.pockets.size() == 1 ? " pocket" : " pockets")
      << (change ? ", and the path of the change" : "") << "\n";
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
  char parts[96];
  std::snprintf(parts, sizeof parts, "(moves %.2f s, dwells %.2f s, %d step%s)", time.moves,
                time.dwells, time.steps, time.steps == 1 ? "" : "s");
  out << "estimated " << seconds_text(time.seconds()) << " on the " << name << " path ("
      << seconds_text(other_time.seconds()) << " on the " << other_name << " path): from safe, "
      << motion->source << ", " << estimate_costs_text(motion->timing)
      << "; the operator not counted " << parts << "\n";
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
  out << "M6 T" << to << " with " << spindle_words(from)
      << (options.state_path.empty()
              ? ", the rack as at first start"
              : ", the rack as " + shown_path(options.state_path) + " has it")
      << "\n";
  int number = 0;
  for (const auto& record : sim.records) {
    if (record.kind == Record::Kind::save) continue;
    char prefix[16];
    std::snprintf(prefix, sizeof prefix, "%3d  ", ++number);
    out << prefix << describe(record) << "\n";
  }
  const int violations = report(check_sequence("M6", config, sim, loaded.limits), out);
  const bool refused = refusal(sim).has_value();
  if (!refused) print_estimate(options, config, tools, to, sim, out);
  return refused || violations != 0 ? 1 : 0;
}

}  // namespace

std::optional<Options> parse_options(const std::vector<std::string>& args, std::string& error) {
  using Mode = Options::Mode;
  Options options;
  std::optional<std::string> mode_flag;      ///< the one of --check, --plan, --dot, --help given
  std::map<std::string, std::string> given;  ///< option -> its value, each at most once
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    static const std::map<std::string, Mode> modes = {
        {"--check", Mode::check},     {"--plan", Mode::plan},   {"--dot", Mode::dot},
        {"--confirm", Mode::confirm}, {"--help", Mode::help},   {"-h", Mode::help},
        {"--lint", Mode::lint},       {"--teach", Mode::teach}, {"--plot", Mode::plot}};
    if (const auto mode = modes.find(arg); mode != modes.end()) {
      if (mode_flag) {
        error = *mode_flag == arg ? arg + " given twice"
                                  : *mode_flag + " and " + arg + " cannot be combined";
        return std::nullopt;
      }
      mode_flag = arg;
      options.mode = mode->second;
      // --lint takes the program as its value, --teach the target, --plot the drawing.
      if (arg != "--lint" && arg != "--teach" && arg != "--plot") continue;
    } else if (arg != "--config" && arg != "--state" && arg != "--ini" && arg != "--from" &&
               arg != "--to" && arg != "--spindle" && arg != "--pocket" && arg != "--tool-table" &&
               arg != "--subroutine-path" && arg != "--at") {
      error = "unknown argument " + quote(arg);
      return std::nullopt;
    }
    if (i + 1 >= args.size()) {
      error = arg + " needs a value";
      return std::nullopt;
    }
    const std::string& text = args[++i];
    if (const auto before = given.find(arg); before != given.end()) {
      error = arg + " given twice (" + quote(before->second) + " and " + quote(text) + ")";
      return std::nullopt;
    }
    given[arg] = text;
    const bool tool = arg == "--from" || arg == "--to" || arg == "--spindle";
    // --teach and --at say what they expect themselves.
    if (text.empty() && arg != "--teach" && arg != "--at") {
      error = arg + ": expected " + (tool ? "a tool number" : "a file path") + ", got nothing";
      return std::nullopt;
    }
    if (text.rfind("--", 0) == 0) {
      error = arg + " needs a value, got the option " + quote(text);
      return std::nullopt;
    }
    if (tool) {
      const auto number = tool_argument(text);
      if (!number) {
        error = arg + ": expected a tool number (0 for none), got " + quote(text);
        return std::nullopt;
      }
      (arg == "--from" ? options.from_tool
       : arg == "--to" ? options.to_tool
                       : options.spindle_tool) = *number;
    } else if (arg == "--pocket") {
      if (text != "yes" && text != "no") {
        error = "--pocket: expected yes or no, got " + quote(text);
        return std::nullopt;
      }
      options.pocket_holds_tool = text == "yes";
    } else if (arg == "--config") {
      options.config_path = text;
    } else if (arg == "--state") {
      options.state_path = text;
    } else if (arg == "--lint") {
      options.program_path = text;
    } else if (arg == "--plot") {
      // A name that ends otherwise is likely the config or state given in the wrong place.
      const std::string tail = text.size() >= 4 ? text.substr(text.size() - 4) : "";
      if (tail != ".svg" && tail != ".SVG") {
        error = "--plot: expected a file name ending in .svg, got " + quote(text);
        return std::nullopt;
      }
      options.plot_path = text;
    } else if (arg == "--tool-table") {
      options.tool_table_path = text;
    } else if (arg == "--subroutine-path") {
      options.subroutine_path = text;
    } else if (arg == "--teach") {
      options.teach_target = parse_teach_target(text);
      if (!options.teach_target) {
        error = "--teach: expected pocket:N, loading, safe or sensor, got " + quote(text);
        return std::nullopt;
      }
    } else if (arg == "--at") {
      options.teach_at = position_argument(text);
      if (!options.teach_at) {
        error = "--at: expected X,Y,Z (three numbers, machine coordinates), got " + quote(text);
        return std::nullopt;
      }
    } else {
      options.ini_path = text;
    }
  }
  // An option the mode would not read is refused, not ignored.
  const std::string mode_name =
      mode_flag ? *mode_flag : "the component (no --check, --plan, --dot)";
  const std::map<std::string, std::set<Mode>> used_by = {
      {"--config",
       {Mode::component, Mode::check, Mode::plan, Mode::confirm, Mode::lint, Mode::teach,
        Mode::plot}},
      {"--state",
       {Mode::component, Mode::check, Mode::confirm, Mode::lint, Mode::plan, Mode::plot}},
      {"--spindle", {Mode::confirm}},
      {"--pocket", {Mode::confirm}},
      {"--ini", {Mode::check, Mode::plan, Mode::lint, Mode::teach}},
      {"--at", {Mode::teach}},
      {"--tool-table", {Mode::lint}},
      {"--subroutine-path", {Mode::lint}},
      {"--from", {Mode::plan, Mode::plot}},
      {"--to", {Mode::plan, Mode::plot}}};
  for (const auto& [option, modes] : used_by) {
    if (given.count(option) != 0 && modes.count(options.mode) == 0) {
      error = option + " is not used by " + mode_name;
      return std::nullopt;
    }
  }
  const bool needs_config = used_by.at("--config").count(options.mode) != 0;
  if (needs_config && options.config_path.empty()) {
    error = "--config FILE is required";
    return std::nullopt;
  }
  if (options.mode == Mode::confirm && !options.spindle_tool) {
    error = "--confirm needs --spindle N (0: the spindle is empty)";
    return std::nullopt;
  }
  if (options.mode == Mode::teach && !options.teach_at) {
    error = "--teach needs --at X,Y,Z (the machine position, G53)";
    return std::nullopt;
  }
  if (options.mode == Mode::plan && (!options.from_tool || !options.to_tool)) {
    error = "--plan needs --from A and --to B";
    return std::nullopt;
  }
  if (options.mode == Mode::plot && options.from_tool.has_value() != options.to_tool.has_value()) {
    error = "--plot: --from A and --to B go together (the change to draw)";
    return std::nullopt;
  }
  // --plan and --plot read a state file only when given one; the others default to CONFIG.state.
  if (used_by.at("--state").count(options.mode) != 0 && options.mode != Mode::plan &&
      options.mode != Mode::plot && options.state_path.empty()) {
    options.state_path = options.config_path + ".state";
  }
  return options;
}

namespace {

/// --teach: the machine position into config.json, the file as it was kept as PATH.bak.
int teach_position(const Options& options, std::ostream& out, std::ostream& err) {
  std::string error;
  const auto text = read_small_file(options.config_path, error);
  if (!text) {
    err << error << "\n";
    return 2;
  }
  std::optional<SoftLimits> limits;
  if (options.ini_path) {
    limits = read_limits(*options.ini_path, declared_units(*text), err);
    if (!limits) return 2;
  }
  const TeachResult taught = teach(*text, *options.teach_target, *options.teach_at, limits);
  if (!taught.text) {
    err << shown_path(options.config_path) << ": " << taught.error << "\n";
    return 1;
  }
  try {
    save_config_file(options.config_path, *text, *taught.text);
  } catch (const std::exception& e) {
    err << e.what() << "\n";
    return 2;
  }
  out << taught.change << "\n"
      << "written (previous file kept as " << shown_path(options.config_path + ".bak") << ")\n";
  return 0;
}

}  // namespace

int run_tool_mode(const Options& options, std::ostream& out, std::ostream& err) {
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
      out << kUsage;
      return 0;
    case Options::Mode::component:
      break;
  }
  return 2;
}

}  // namespace fatc::io
