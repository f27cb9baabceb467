#include "inputs.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <ostream>

#include "core/dry_run/sequence_check.hpp"
#include "core/program/tool_table.hpp"
#include "io/files.hpp"
#include "linuxcnc/offline/ini.hpp"

namespace fatc::io {

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

std::string fault_of(const char* input, const std::string& path) {
  std::string ignored;
  return std::string(input) + (read_small_file(path, ignored) ? " not valid" : " unreadable");
}

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

namespace {

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

}  // namespace

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

std::string spindle_words(int tool) {
  return tool == 0 ? "an empty spindle" : "T" + std::to_string(tool) + " in the spindle";
}

std::optional<std::string> refusal(const Simulator& plan) {
  for (const Step& step : plan.steps()) {
    if (step.kind == StepKind::fail) return step.label;
  }
  return std::nullopt;
}

}  // namespace fatc::io
