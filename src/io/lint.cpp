#include "lint.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <ostream>

#include "core/gcode_scan.hpp"
#include "core/preflight.hpp"
#include "core/program_walk.hpp"
#include "core/tool_table.hpp"
#include "files.hpp"
#include "ini.hpp"

namespace fatc::io {
namespace {

/// How many rows and findings a section prints before it only counts the rest.
constexpr std::size_t kMaxRows = 200;
constexpr std::size_t kMaxFindings = 50;

std::string folder_of(const std::string& path) {
  const auto slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

std::string base_name(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

/// LinuxCNC's path lists: ':' between folders, `~/` for the home folder,
/// relative to `base` (the INI's folder, where LinuxCNC runs).
std::vector<std::string> folders_of(const std::string& list, const std::string& base) {
  std::vector<std::string> folders;
  std::size_t start = 0;
  while (start <= list.size()) {
    const auto colon = list.find(':', start);
    std::string folder =
        list.substr(start, colon == std::string::npos ? std::string::npos : colon - start);
    start = colon == std::string::npos ? list.size() + 1 : colon + 1;
    if (folder.empty()) continue;
    if (folder.rfind("~/", 0) == 0 && std::getenv("HOME") != nullptr) {
      folder = std::getenv("HOME") + folder.substr(1);
    } else if (folder[0] != '/' && !base.empty()) {
      folder = base + "/" + folder;
    }
    folders.push_back(folder);
  }
  return folders;
}

/// Reads one G-code file within what is left of the budget of bytes.
std::unique_ptr<gcode::SourceFile> read_source(const std::string& path, std::size_t& budget,
                                               std::string& error) {
  if (budget == 0) {
    error = shown_path(path) + ": not read: the lint reads at most " +
            std::to_string(kMaxProgramBytes / (1024 * 1024)) + " MiB of G-code in all";
    return nullptr;
  }
  std::uint64_t file_bytes = 0;
  auto text = read_file_start(path, budget, file_bytes, error);
  if (!text) return nullptr;
  budget -= text->size();
  auto file = std::make_unique<gcode::SourceFile>();
  file->name = shown_path(path);
  const bool cut = text->size() < file_bytes;
  // A cut file ends at its last whole line: half a line could read as another word.
  if (cut) text->resize(text->rfind('\n') == std::string::npos ? 0 : text->rfind('\n') + 1);
  file->scanned = gcode::scan(*text);
  if (cut) {
    file->scanned.problems.insert(
        file->scanned.problems.begin(),
        {0, "only the first " + std::to_string(text->size()) + " of its " +
                std::to_string(file_bytes) + " bytes read (the lint reads at most " +
                std::to_string(kMaxProgramBytes / (1024 * 1024)) +
                " MiB of G-code): tool changes after line " + std::to_string(file->scanned.lines) +
                " are not known"});
  }
  return file;
}

/// Subroutine files, `name`.ngc, looked for in a list of folders, each read once.
class FolderFinder : public gcode::SubroutineFinder {
 public:
  FolderFinder(std::vector<std::string> folders, std::size_t& budget)
      : folders_(std::move(folders)), budget_(budget) {}

  const gcode::SourceFile* find(const std::string& name, std::string& why_not) override {
    auto known = found_.find(name);
    if (known == found_.end()) known = found_.emplace(name, look_for(name)).first;
    why_not = known->second.why_not;
    return known->second.file.get();
  }

 private:
  struct Found {
    std::unique_ptr<gcode::SourceFile> file;
    std::string why_not;
  };

  Found look_for(const std::string& name) {
    Found found;
    for (const std::string& folder : folders_) {
      const std::string path = folder + "/" + name + ".ngc";
      struct stat st;
      if (::stat(path.c_str(), &st) != 0) continue;
      found.file = read_source(path, budget_, found.why_not);
      return found;
    }
    found.why_not = shown_path(name + ".ngc") + " not found in ";
    for (std::size_t i = 0; i < folders_.size() && i < 3; ++i) {
      found.why_not += (i == 0 ? "" : ", ") + shown_path(folders_[i]);
    }
    if (folders_.size() > 3) {
      found.why_not += " or " + std::to_string(folders_.size() - 3) + " more folders";
    }
    return found;
  }

  std::vector<std::string> folders_;
  std::size_t& budget_;
  std::map<std::string, Found> found_;
};

/// What the INI adds: rapid speed, remaps, where subroutines are.
struct MachineIni {
  double rapid_per_minute = 0.0;
  std::string rapid_source;  ///< how the rapid speed was found, for the estimate's line
  gcode::WalkOptions walk;
  std::vector<std::string> folders;
};

}  // namespace

std::optional<RapidSpeed> rapid_speed(const std::optional<std::string>& ini_path,
                                      const Config& config, std::string& error) {
  const char* unit = config.units == Units::inch ? "inch/min" : "mm/min";
  const double assumed = config.units == Units::inch ? kAssumedRapidInch : kAssumedRapidMm;
  char buffer[160];
  if (!ini_path) {
    std::snprintf(buffer, sizeof buffer,
                  "rapids at %.0f %s, assumed (--ini gives the machine's "
                  "[TRAJ]MAX_LINEAR_VELOCITY)",
                  assumed, unit);
    return RapidSpeed{assumed, buffer};
  }
  const auto ini = IniFile::read(*ini_path, error);
  if (!ini) return std::nullopt;
  const auto velocity = ini->number("TRAJ", "MAX_LINEAR_VELOCITY");
  const auto per_mm = ini->linear_units();
  if (velocity && per_mm && std::isfinite(*velocity) && *velocity > 0.0 && std::isfinite(*per_mm) &&
      *per_mm > 0.0) {
    const double mm_per_minute = *velocity / *per_mm * 60.0;
    const double per_minute = config.units == Units::inch ? mm_per_minute / 25.4 : mm_per_minute;
    std::snprintf(buffer, sizeof buffer, "rapids at %.0f %s ([TRAJ]MAX_LINEAR_VELOCITY of ",
                  per_minute, unit);
    return RapidSpeed{per_minute, buffer + shown_path(*ini_path) + ")"};
  }
  std::snprintf(buffer, sizeof buffer, "rapids at %.0f %s, assumed (", assumed, unit);
  return RapidSpeed{assumed, buffer + shown_path(*ini_path) +
                                 " has no usable [TRAJ]MAX_LINEAR_VELOCITY and LINEAR_UNITS)"};
}

namespace {

/// Reads what --lint uses of the INI; false and one line in `error` when it cannot be read.
bool read_ini(const Options& options, const Config& config, MachineIni& machine,
              std::string& error) {
  const auto rapid = rapid_speed(options.ini_path, config, error);
  if (!rapid) return false;
  machine.rapid_per_minute = rapid->per_minute;
  machine.rapid_source = rapid->source;
  if (!options.ini_path) return true;
  const auto ini = IniFile::read(*options.ini_path, error);
  if (!ini) return false;
  const std::string base = folder_of(*options.ini_path);
  machine.walk.remaps_known = true;
  for (const std::string& line : ini->get_all("RS274NGC", "REMAP")) {
    if (const auto remap = gcode::parse_remap(line)) machine.walk.remaps[remap->code] = *remap;
  }
  for (const char* key : {"PROGRAM_PREFIX", "SUBROUTINE_PATH"}) {
    const auto value = ini->get(key[0] == 'P' ? "DISPLAY" : "RS274NGC", key);
    if (!value) continue;
    for (const auto& folder : folders_of(*value, base)) machine.folders.push_back(folder);
  }
  return true;
}

}  // namespace

std::string seconds_text(double seconds) {
  char buffer[48];
  // A machine that would take over a day is a limit typed wrong: no figure.
  if (!(seconds < 86400.0)) return "over a day";
  if (seconds < 59.95) {
    std::snprintf(buffer, sizeof buffer, "%.1f s", seconds);
  } else {
    const long whole = std::lround(seconds);
    std::snprintf(buffer, sizeof buffer, "%ld min %02ld s", whole / 60, whole % 60);
  }
  return buffer;
}

namespace {

std::string padded(const std::string& text, std::size_t width) {
  return text.size() >= width ? text + " " : text + std::string(width - text.size(), ' ');
}

std::string site_text(const gcode::Site& where) {
  return where.line > 0 ? where.file + ": line " + std::to_string(where.line) : where.file;
}

void print_findings(const std::string& title, const std::vector<gcode::Finding>& findings,
                    std::ostream& out) {
  if (findings.empty()) return;
  out << "\n" << title << ":\n";
  for (std::size_t i = 0; i < findings.size() && i < kMaxFindings; ++i) {
    out << "  " << site_text(findings[i].where) << ": " << findings[i].text << "\n";
  }
  if (findings.size() > kMaxFindings) {
    out << "  ... and " << findings.size() - kMaxFindings << " more\n";
  }
}

std::string plural(std::size_t n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

void print_rows(const std::string& program, const Preflight& checked, std::ostream& out) {
  if (checked.rows.empty()) return;
  out << "\n  #  line      code          where                                 length"
         "                          time\n";
  for (std::size_t i = 0; i < checked.rows.size() && i < kMaxRows; ++i) {
    const PreflightRow& row = checked.rows[i];
    const gcode::Site& at = row.use.where;
    const std::string line = at.file == program
                                 ? std::to_string(at.line)
                                 : base_name(at.file) + ":" + std::to_string(at.line);
    char number[16];
    std::snprintf(number, sizeof number, "%3zu  ", i + 1);
    out << number << padded(line, 10) << padded(row.code, 14)
        << padded(row.where + (row.use.in_flow ? " (in a loop/conditional)" : ""), 38)
        << padded(row.length, 32) << (row.seconds ? seconds_text(*row.seconds) : "-") << "\n";
  }
  if (checked.rows.size() > kMaxRows) {
    out << "  ... and " << checked.rows.size() - kMaxRows << " more\n";
  }
}

void print_estimate(const Preflight& checked, const MachineIni& machine, std::ostream& out) {
  const int estimated = checked.changes - checked.not_estimated;
  if (estimated == 0) {
    out << "\nestimated tool-change time: not known: the tool or the spindle of every change is "
           "not known\n";
    return;
  }
  out << "\nestimated tool-change time: " << seconds_text(checked.seconds) << " for "
      << plural(static_cast<std::size_t>(estimated), "change", "changes")
      << ", from the steps --plan prints for each: moves at their feed, " << machine.rapid_source
      << ", plus the dwells; from safe to safe (the way between the work and safe, acceleration"
      << (checked.operator_waits > 0
              ? " and the operator at " + plural(checked.operator_waits, "prompt", "prompts")
              : std::string())
      << " not counted)";
  if (checked.not_estimated > 0) {
    out << "; " << plural(checked.not_estimated, "change", "changes")
        << " not estimated: the tool or the spindle is not known";
  }
  out << "\n";
}

/// Problems in the order of the program: by file as the walk met them, then line.
void sort_by_place(std::vector<gcode::Finding>& findings, const std::vector<std::string>& files) {
  const auto rank = [&](const gcode::Finding& f) {
    const auto at = std::find(files.begin(), files.end(), f.where.file);
    return std::make_pair(static_cast<std::size_t>(at - files.begin()), f.where.line);
  };
  std::stable_sort(
      findings.begin(), findings.end(),
      [&](const gcode::Finding& a, const gcode::Finding& b) { return rank(a) < rank(b); });
}

}  // namespace

namespace {

/// The program walked as LinuxCNC would run it: its own folder, the extra
/// subroutine folders and the INI's searched for what it calls.
std::optional<gcode::Walk> walk_program(const Options& options, const MachineIni& machine,
                                        std::string& error, std::string* name = nullptr) {
  std::size_t budget = kMaxProgramBytes;
  const auto program = read_source(options.program_path, budget, error);
  if (!program) return std::nullopt;
  if (name) *name = program->name;
  std::vector<std::string> folders = {folder_of(options.program_path)};
  if (options.subroutine_path) {
    for (const auto& folder : folders_of(*options.subroutine_path, "")) folders.push_back(folder);
  }
  folders.insert(folders.end(), machine.folders.begin(), machine.folders.end());
  FolderFinder finder(folders, budget);
  return gcode::walk(*program, finder, machine.walk);
}

}  // namespace

std::optional<std::vector<int>> program_tools(const std::string& program_path,
                                              const std::string& ini_path, const Config& config,
                                              std::string& error) {
  Options options;
  options.program_path = program_path;
  if (!ini_path.empty()) options.ini_path = ini_path;
  MachineIni machine;
  if (!read_ini(options, config, machine, error)) return std::nullopt;
  const auto walked = walk_program(options, machine, error);
  if (!walked) return std::nullopt;
  std::vector<int> tools;
  for (const auto& use : walked->uses) {
    if (!use.tool || *use.tool == 0) continue;
    if (std::find(tools.begin(), tools.end(), *use.tool) == tools.end()) tools.push_back(*use.tool);
  }
  return tools;
}

int lint(const Options& options, std::ostream& out, std::ostream& err) {
  const auto loaded = load_config_file(options.config_path);
  if (!loaded.config) {
    for (const auto& error : loaded.errors) err << error << "\n";
    return 2;
  }
  const Config& config = *loaded.config;
  const auto state = load_state_file(options.state_path, config);
  if (!state.state) {
    err << state.error << "\n";
    return 2;
  }
  std::string error;
  std::optional<ToolTable> table;
  std::string table_name;
  if (options.tool_table_path) {
    const auto text = read_small_file(*options.tool_table_path, error);
    if (!text) {
      err << error << "\n";
      return 2;
    }
    table = parse_tool_table(*text);
    table_name = shown_path(*options.tool_table_path);
  }
  MachineIni machine;
  if (!read_ini(options, config, machine, error)) {
    err << error << "\n";
    return 2;
  }
  std::string name;
  auto walk = walk_program(options, machine, error, &name);
  if (!walk) {
    err << error << "\n";
    return 2;
  }
  gcode::Walk& walked = *walk;

  PreflightInput input;
  input.config = &config;
  input.tools = *state.state;
  input.state_name = shown_path(options.state_path);
  input.table = table ? &*table : nullptr;
  input.table_name = table_name;
  input.rapid_per_minute = machine.rapid_per_minute;
  const Preflight checked = preflight(walked, input);

  std::vector<gcode::Finding> problems = walked.problems;
  problems.insert(problems.end(), checked.problems.begin(), checked.problems.end());
  sort_by_place(problems, walked.files);
  sort_by_place(walked.unknowns, walked.files);
  if (table) {
    for (const auto& note : table->problems)
      problems.push_back({{table_name, note.line}, note.text});
  }

  struct stat st;
  const bool first_start = ::stat(options.state_path.c_str(), &st) != 0 && errno == ENOENT;
  const int spindle = state.state->spindle;
  out << name << ": at the start the spindle holds "
      << (spindle == 0 ? std::string("nothing") : "T" + std::to_string(spindle))
      << (first_start ? " (no state file yet at " + input.state_name +
                            ": each pocket holds its first-start tool)"
                      : " (state file " + input.state_name + ")")
      << "\n";
  if (!checked.tools.empty()) {
    out << "tools in the order of the changes:";
    for (const int tool : checked.tools) out << " T" << tool;
    out << "\n";
  }
  print_rows(name, checked, out);
  print_findings("not known without running the program", walked.unknowns, out);
  print_findings("problems", problems, out);
  if (checked.changes > 0) print_estimate(checked, machine, out);

  const auto changes = std::count_if(checked.rows.begin(), checked.rows.end(), [](const auto& r) {
    return r.use.kind == gcode::ToolUse::Kind::change;
  });
  out << "\n"
      << name << ": "
      << plural(static_cast<std::size_t>(changes), "tool change (M6)", "tool changes (M6)") << ", "
      << checked.rows.size() - static_cast<std::size_t>(changes) << " M61, "
      << plural(problems.size(), "problem", "problems") << ", " << walked.unknowns.size()
      << " not known\n";
  return problems.empty() ? 0 : 1;
}

}  // namespace fatc::io
