#include "lint.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <ostream>

#include "core/config/quote.hpp"
#include "core/dry_run/sequence_check.hpp"
#include "core/program/keepout_check.hpp"
#include "core/program/preflight.hpp"
#include "core/program/tool_table.hpp"
#include "io/files.hpp"
#include "io/interruption.hpp"
#include "linuxcnc/offline/machine_ini.hpp"
#include "linuxcnc/offline/program_tools.hpp"

namespace fatc::io {
namespace {

/// How many rows and findings a section prints before it only counts the rest.
constexpr std::size_t kMaxRows = 200;
constexpr std::size_t kMaxFindings = 50;

}  // namespace

std::string estimate_costs_text(const MachineTiming& timing) {
  char buffer[320];
  std::snprintf(buffer, sizeof buffer,
                "each an exact stop (G61.1) at the axes' full acceleration as LinuxCNC plans it, plus the "
                "dwells, %.0f ms a step (the executor's handshake) and %.2f s a change (%g of "
                "iocontrol's %g s cycles for T and M6, %.0f ms for the remap)",
                kStepSeconds * 1000.0,
                kIocontrolCycles * timing.iocontrol_cycle_seconds + kChangeSeconds,
                kIocontrolCycles, timing.iocontrol_cycle_seconds, kChangeSeconds * 1000.0);
  return buffer;
}

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

/// How many characters a terminal shows of UTF-8 `text` ("±" is one).
std::size_t shown_width(const std::string& text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  }));
}

/// `text` and spaces to `width` characters as a terminal shows them.
std::string padded(const std::string& text, std::size_t width) {
  const std::size_t shown = shown_width(text);
  return shown >= width ? text + " " : text + std::string(width - shown, ' ');
}

std::string site_text(const program::Site& where) {
  return where.line > 0 ? where.file + ": line " + std::to_string(where.line) : where.file;
}

void print_findings(const std::string& title, const std::vector<program::Finding>& findings,
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

void print_rows(const Preflight& checked, std::ostream& out) {
  if (checked.rows.empty()) return;
  // The rule and length columns as wide as their longest text (a tool table's
  // "measured at the change, stored Z35.0000 (tool table)").
  std::size_t rule_width = 38;
  std::size_t length_width = 32;
  for (std::size_t i = 0; i < checked.rows.size() && i < kMaxRows; ++i) {
    rule_width = std::max(rule_width, shown_width(checked.rows[i].rule) + 1);
    length_width = std::max(length_width, shown_width(checked.rows[i].length) + 1);
  }
  out << "\n  #  line      code          where                                 "
      << padded("rule", rule_width) << padded("length", length_width) << "time\n";
  for (std::size_t i = 0; i < checked.rows.size() && i < kMaxRows; ++i) {
    const PreflightRow& row = checked.rows[i];
    const int line = row.use.where.line;
    char number[16];
    std::snprintf(number, sizeof number, "%3zu  ", i + 1);
    out << number << padded(line > 0 ? std::to_string(line) : "-", 10) << padded(row.code, 14)
        << padded(row.where, 38) << padded(row.rule.empty() ? "-" : row.rule, rule_width)
        << padded(row.length, length_width)
        << (row.seconds ? seconds_text(*row.seconds) : "-") << "\n";
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
  // The figure, then how it was worked out, each line under 400 characters.
  out << "\nestimated tool-change time: " << seconds_text(checked.seconds) << " for "
      << plural(static_cast<std::size_t>(estimated), "change", "changes")
      << ", from safe to safe (the way between the work and safe"
      << (checked.operator_waits > 0
              ? " and the operator at " + plural(checked.operator_waits, "prompt", "prompts")
              : std::string())
      << " not counted)";
  if (checked.not_estimated > 0) {
    out << "; " << plural(checked.not_estimated, "change", "changes")
        << " not estimated: the tool or the spindle is not known";
  }
  out << "\n  from the steps --plan prints for each: " << machine.motion.source << ", "
      << estimate_costs_text(machine.motion.timing) << "\n";
}

/// Findings in the order of the program's lines.
void sort_by_line(std::vector<program::Finding>& findings) {
  std::stable_sort(findings.begin(), findings.end(),
                   [](const program::Finding& a, const program::Finding& b) {
                     return a.where.line < b.where.line;
                   });
}

/// The program run through LinuxCNC's interpreter with the machine's INI
/// and tool table (`tool_table`, else the INI's); `listener` told of its calls.
std::optional<program::InterpreterRun> interpret(const Options& options, const Config& config,
                                                 const std::optional<std::string>& tool_table,
                                                 std::string& error,
                                                 program::CallListener* listener) {
  InterpreterInput input;
  input.program_path = options.program_path;
  input.ini_path = options.ini_path;
  input.tool_table_path = tool_table;
  input.subroutine_path = options.subroutine_path;
  input.listener = listener;
  return io::interpret(input, config, error);
}

}  // namespace

int lint(const Options& options, std::ostream& out, std::ostream& err) {
  // Interrupted, it removes its copy of the program before it ends.
  const Interruptible interruptible;
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
  const auto read = read_machine_ini(options.ini_path, config, error);
  if (!read) {
    err << error << "\n";
    return 2;
  }
  const MachineIni& machine = *read;
  // The table rs274 is given: --tool-table, else the INI's. Its problems are
  // the program's; its lengths stand for the state file's only when given.
  const auto table_path = options.tool_table_path ? options.tool_table_path : machine.tool_table;
  std::optional<ToolTable> table;
  std::string table_name;
  if (table_path) {
    const auto text = read_small_file(*table_path, error);
    if (!text) {
      err << error << "\n";
      return 2;
    }
    table = parse_tool_table(*text);
    table_name = shown_path(*table_path);
  }
  const std::string name = shown_path(options.program_path);
  KeepoutCheckInput rack;
  rack.config = &config;
  rack.program = name;
  rack.tools = *state.state;
  rack.return_to_xy = machine.return_to_xy;
  if (table) {
    // The table is in the machine's units: the INI's, else the config's.
    const double config_per_mm = config.units == Units::inch ? 1.0 / 25.4 : 1.0;
    const double table_per_mm = machine.units_per_mm.value_or(config_per_mm);
    rack.lengths.emplace();
    for (const auto& [tool, entry] : table->tools) {
      (*rack.lengths)[tool] = entry.z.value_or(0.0) / table_per_mm * config_per_mm;
    }
    rack.table_name = table_name;
  }
  // The changer's own moves as --check plans them, once the INI's soft
  // limits, a change or a tool of no length need them: what the config
  // allows the tools it carries.
  std::optional<SequencesChecked> sequences;
  const auto sequences_checked = [&]() -> const SequencesChecked& {
    if (!sequences) sequences = check_sequences(config, machine.limits);
    return *sequences;
  };
  rack.longest = [&] { return longest_carried(config, sequences_checked()); };
  ToolLengths carried;
  carried.table = rack.lengths.value_or(std::map<int, double>{});
  KeepoutCheck keepout(std::move(rack));
  auto run = interpret(options, config, table_path, error, &keepout);
  if (!run) {
    err << error << "\n";
    return 2;
  }

  PreflightInput input;
  input.config = &config;
  input.tools = *state.state;
  input.state_name = shown_path(options.state_path);
  input.table = table && options.tool_table_path ? &*table : nullptr;
  input.table_name = table_name;
  input.machine = machine.motion.timing;
  const auto first_change = std::find_if(run->uses.begin(), run->uses.end(), [](const auto& use) {
    return use.kind == program::ToolUse::Kind::change;
  });
  if (first_change != run->uses.end()) carried.longest = longest_carried(config, sequences_checked());
  input.lengths = std::move(carried);
  input.lengths_set = keepout.lengths_set();
  input.spindle_starts = run->spindle_starts;
  const Preflight checked = preflight(run->uses, input);

  std::vector<program::Finding> problems = run->problems;
  problems.insert(problems.end(), checked.problems.begin(), checked.problems.end());
  const auto entries = keepout.problems();
  problems.insert(problems.end(), entries.begin(), entries.end());
  // The config against the machine's soft limits, as --check has it: a
  // change the program calls would stop there.
  if (machine.limits) {
    for (const SequenceViolation& violation : sequences_checked().violations) {
      problems.push_back(program::finding(shown_path(options.config_path), 0, describe(violation)));
    }
  }
  for (const std::string& move : machine.builtin_m6_moves) {
    problems.push_back(program::finding(shown_path(*options.ini_path), 0, move));
  }
  if (!machine.remaps_m6 && first_change != run->uses.end()) {
    problems.push_back({first_change->where,
                        "the INI remaps no M6: LinuxCNC's own M6 would run here, not "
                        "fixed_atc_probe_m6"});
  }
  sort_by_line(problems);
  std::vector<program::Finding>& unknowns = run->unknowns;
  unknowns.insert(unknowns.end(), keepout.unknowns().begin(), keepout.unknowns().end());
  if (run->uses_not_kept > 0) {
    unknowns.push_back(program::finding(name, 0, "more than " + std::to_string(program::kMaxToolUses) +
                                       " tool changes and M61: the other " +
                                       std::to_string(run->uses_not_kept) + " are not counted"));
  }
  if (options.ini_path && !machine.limits) {
    unknowns.push_back(program::finding(
        name, 0, machine.limits_error + ": the config is not checked against the soft limits"));
  }
  sort_by_line(unknowns);
  // The files' own problems after the program's, each file's in its order.
  problems.insert(problems.end(), machine.include_problems.begin(), machine.include_problems.end());
  if (table) {
    for (const auto& note : table->problems) problems.push_back(program::finding(table_name, note.line, note.text));
  }

  struct stat st;
  const bool first_start = ::stat(options.state_path.c_str(), &st) != 0 && errno == ENOENT;
  const ToolState& start = *state.state;
  const std::string last = start.spindle == 0 ? "nothing" : "T" + std::to_string(start.spindle);
  if (start.uncertain) {
    // As the component holds the spindle after a cut-off sequence.
    const int probe = spindle_probe(config, start);
    // The state file is named at the first M6 it refuses; this line stays short.
    out << name << ": at the start the spindle is uncertain (the state file's "
        << (start.in_progress ? escape(start.in_progress->sequence) : std::string("sequence"))
        << " was cut off; last known: " << last << "): "
        << (probe != 0 ? "it may hold T" + std::to_string(probe) + ", a probe (tools." +
                             std::to_string(probe) +
                             ".kind): fatc-spindle-guard holds the spindle until the fault is "
                             "cleared (panel, or --confirm)"
                       : "the changer refuses M6 until the fault is cleared (panel, or --confirm)")
        << "\n";
  } else {
    out << name << ": at the start the spindle holds " << last
        << (first_start ? " (no state file yet at " + input.state_name +
                              ": each pocket holds its first-start tool)"
                        : " (state file " + input.state_name + ")")
        << "\n";
  }
  if (!checked.order.empty()) {
    out << "tools in the order of the changes:";
    for (const auto& tool : checked.order) out << " T" << (tool ? std::to_string(*tool) : "?");
    out << "\n";
  }
  print_rows(checked, out);
  print_findings("not known without running the program", unknowns, out);
  print_findings("problems", problems, out);
  if (checked.changes > 0) print_estimate(checked, machine, out);

  const auto changes = std::count_if(checked.rows.begin(), checked.rows.end(), [](const auto& r) {
    return r.use.kind == program::ToolUse::Kind::change;
  });
  out << "\n"
      << name << ": "
      << plural(static_cast<std::size_t>(changes), "tool change (M6)", "tool changes (M6)") << ", "
      << checked.rows.size() - static_cast<std::size_t>(changes) << " M61, "
      << plural(problems.size(), "problem", "problems") << ", " << unknowns.size()
      << " not known\n";
  return problems.empty() ? 0 : 1;
}

}  // namespace fatc::io
