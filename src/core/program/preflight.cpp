#include "preflight.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>
#include <utility>

#include "../config/measuring.hpp"
#include "../dry_run/sequence_check.hpp"
#include "../formatted.hpp"
#include "interpreter_output.hpp"

namespace fatc {

namespace {

std::string tool_word(int tool) { return "T" + std::to_string(tool); }

/// One change planned by the changer itself, as --plan prints it.
struct PlannedChange {
  double seconds = 0.0;
  int operator_waits = 0;
  std::string refused;  ///< the changer's reason when it refuses the change
  std::vector<Step> steps;
  /// What check_steps found on them, by the lengths of the tool it takes
  /// back and the one it fetches: a long program repeats its changes.
  std::map<std::pair<double, double>, std::vector<Violation>> carried;
};

class Checker {
 public:
  explicit Checker(const PreflightInput& input)
      : in_(input), config_(*input.config), lengths_(input.lengths), planning_(*input.config) {
    tools_ = input.tools;
    datum_changes_ = tools_.datum.changes;
    // The rack datum is judged here, change by change (datum_refusal): each
    // change is planned as the changer makes it once the datum lets it.
    if (planning_.rack_touch) {
      planning_.rack_touch->check_every_changes = 0;
      planning_.rack_touch->check_at_start = false;
    }
  }

  Preflight run(const std::vector<program::ToolUse>& uses) {
    auto set = in_.lengths_set.begin();
    auto start = in_.spindle_starts.begin();
    std::size_t ran = 0;
    for (const auto& use : uses) {
      for (; set != in_.lengths_set.end() && set->before_use <= ran && use.ran; ++set) {
        lengths_.table[set->tool] = set->length;
      }
      for (; start != in_.spindle_starts.end() && start->before_use <= ran && use.ran; ++start) {
        spindle_started(*start);
      }
      ran += use.ran ? 1 : 0;
      PreflightRow row;
      row.use = use;
      if (use.kind == program::ToolUse::Kind::change) {
        result_.order.push_back(use.tool);
        change(row);
      } else {
        set_tool(row);
      }
      result_.rows.push_back(row);
    }
    for (; start != in_.spindle_starts.end(); ++start) spindle_started(*start);
    return std::move(result_);
  }

 private:
  void problem(const program::Site& where, const std::string& text) {
    result_.problems.push_back({where, text});
  }

  /// The spindle set turning, or M19, while a probe is in it or may be (a
  /// cut-off sequence: spindle_probe, as the component holds the spindle):
  /// the guard holds it and the changer aborts. The program stops at the
  /// first, so it is named once each time a probe goes into the spindle.
  void spindle_started(const program::SpindleStart& start) {
    const int probe = spindle_known_ ? spindle_probe(config_, tools_) : 0;
    if (probe == 0) return;
    const std::string held =
        (probe == tools_.spindle ? " with " + tool_word(probe) + " in it, a probe (tools."
                                 : " while it may hold " + tool_word(probe) +
                                       ", a probe, as the cut-off sequence of the state file left "
                                       "it (tools.") +
        std::to_string(probe) + ".kind)";
    if (start.orients) {
      problem(start.where, "M19 orients the spindle" + held +
                               ": fatc-spindle-guard does not hold an orient; change to a cutter "
                               "first");
      return;
    }
    if (probe_start_said_) return;
    probe_start_said_ = true;
    char speed[96];
    if (start.css_maximum != 0.0) {
      std::snprintf(speed, sizeof speed, "G96 up to D%g", start.css_maximum);
    } else {
      std::snprintf(speed, sizeof speed, "S%g", start.speed);
    }
    problem(start.where, std::string("the spindle turns here (") + (start.clockwise ? "M3" : "M4") +
                             " in force, " + speed + ")" + held +
                             ": fatc-spindle-guard holds the spindle and the changer aborts the "
                             "program here");
  }

  void change(PreflightRow& row) {
    const program::ToolUse& use = row.use;
    row.code = use.tool ? "M6 " + tool_word(*use.tool) : "M6";
    if (!use.tool) {
      row.where = "not known";
      row.length = "-";
      ++result_.changes;
      ++result_.not_estimated;
      spindle_known_ = false;
      return;
    }
    const int tool = *use.tool;
    if (tools_.uncertain && !said_uncertain_) {
      said_uncertain_ = true;
      problem(use.where, "the state file " + in_.state_name +
                             " records a sequence that was cut off: the changer refuses M6 "
                             "until the fault is cleared (panel, or --confirm)");
    }
    row.length = length(use, tool);
    if (tool != 0) row.rule = rule_words(config_, tool);
    if (spindle_known_ && tool == tools_.spindle) {
      row.where = tool == 0 ? "the spindle is empty already" : "in the spindle already";
      row.seconds = 0.0;
      return;
    }
    if (const auto datum = datum_refusal(tool)) problem(use.where, *datum);
    ++result_.changes;
    if (tool != 0 &&
        std::find(result_.tools.begin(), result_.tools.end(), tool) == result_.tools.end()) {
      result_.tools.push_back(tool);
    }
    const auto pocket = tools_.home_of(tool);
    if (tool == 0) {
      row.where = "empties the spindle";
    } else if (tools_.pocket_holding(tool)) {
      row.where = "pocket " + std::to_string(*pocket);
    } else if (pocket) {
      row.where = "out of the rack (pocket " + std::to_string(*pocket) + " empty)";
      problem(use.where, "M6 " + tool_word(tool) + ": the state file " + in_.state_name +
                             " has pocket " + std::to_string(*pocket) + " empty (" +
                             tool_word(tool) +
                             " is not in it): the changer refuses the change; load it first");
    } else {
      row.where = "manual: handed over at loading";
      ++result_.manual;
    }
    if (!spindle_known_) {
      ++result_.not_estimated;
    } else {
      PlannedChange& planned = plan(tools_.spindle, tool);
      if (!planned.refused.empty()) {
        // The changer stops the program there; the lint reads on with the spindle as it was.
        row.where = "refused: " + row.where;
        problem(use.where, planned.refused);
        return;
      } else {
        row.seconds = planned.seconds;
        result_.seconds += planned.seconds;
        result_.operator_waits += planned.operator_waits;
        carried(use, planned);
      }
    }
    // The rack after the change: the old tool home, the new one in the spindle.
    if (spindle_known_ && tools_.spindle != 0) {
      if (const auto back = return_pocket(tools_, config_, tools_.spindle)) {
        tools_.pockets[*back] = {tools_.spindle, true};
      }
    }
    tools_.put_in_spindle(tool);
    // The change was planned as if the fault were cleared: the spindle is known from here.
    tools_.uncertain = false;
    tools_.in_progress.reset();
    spindle_known_ = true;
    probe_start_said_ = false;
    // Measured at this change: a "new" tool is not measured at the next.
    if (tool != 0 && measuring_of(config_, tool, measured(tool)).after_change) {
      measured_here_.insert(tool);
    }
  }

  /// The rack datum (rack_touch) at a change to `tool`: the drift the state
  /// file records, or its check falling due after check_every_changes,
  /// makes the changer refuse it; said once, the first time.
  std::optional<std::string> datum_refusal(int tool) {
    if (!config_.rack_touch || said_datum_) return std::nullopt;
    const std::string change = "M6 " + tool_word(tool) + ": ";
    if (!tools_.datum.drift.empty()) {
      said_datum_ = true;
      return change + "the state file " + in_.state_name + " says " + tools_.datum.drift +
             ": the changer refuses M6 until teach-datum or clear-datum-drift";
    }
    const int every = config_.rack_touch->check_every_changes;
    if (every <= 0) return std::nullopt;
    const int made = datum_changes_++;
    if (made < every || (tool != 0 && config_.is_probe(tool))) return std::nullopt;
    said_datum_ = true;
    return change + "the rack datum check falls due here, " + std::to_string(made) +
           " changes after the last (" + std::to_string(tools_.datum.changes) +
           " in the state file, rack_touch.check_every_changes " + std::to_string(every) +
           "): the changer refuses it; run check-datum before the program";
  }

  void set_tool(PreflightRow& row) {
    const program::ToolUse& use = row.use;
    row.code = use.tool ? "M61 Q" + std::to_string(*use.tool) : "M61";
    row.seconds = 0.0;
    if (!use.tool) {
      row.where = "LinuxCNC is told a tool not known; nothing moves";
      row.length = "-";
      return;
    }
    const int tool = *use.tool;
    row.length = length(use, tool);
    row.where = "LinuxCNC is told " + (tool == 0 ? std::string("nothing") : tool_word(tool)) +
                " is in the spindle; nothing moves";
    if (spindle_known_ && tool != tools_.spindle) {
      problem(use.where,
              "M61 Q" + std::to_string(tool) + ": tells LinuxCNC the spindle holds " +
                  (tool == 0 ? std::string("nothing") : tool_word(tool)) +
                  " while the changer has " +
                  (tools_.spindle == 0 ? std::string("nothing") : tool_word(tools_.spindle)) +
                  " in it: the next G43 would apply the wrong length");
    }
  }

  /// The Length column; a problem, once per tool, when the tool has no length
  /// and the change does not measure it.
  std::string length(const program::ToolUse& use, int tool) {
    if (tool == 0) return "-";
    const bool change = use.kind == program::ToolUse::Kind::change;
    // M6 of the tool already in the spindle answers at once: it measures nothing.
    const bool already = change && spindle_known_ && tool == tools_.spindle;
    const Measuring measuring = measuring_of(config_, tool, measured(tool));
    const bool measures = change && !already && measuring.after_change;
    std::optional<std::string> stored;  // the length as the column shows it
    std::string missing;                // why there is none
    if (in_.table != nullptr) {
      // The table is in the machine's units, which may not be the config's.
      const auto entry = in_.table->tools.find(tool);
      if (entry == in_.table->tools.end()) {
        missing = "not in the tool table " + in_.table_name;
      } else if (!entry->second.z) {
        missing = "no Z in the tool table " + in_.table_name + " (line " +
                  std::to_string(entry->second.line) + ")";
      } else if (*entry->second.z == 0.0) {
        missing = "Z0 in the tool table " + in_.table_name + " (line " +
                  std::to_string(entry->second.line) + ")";
      } else {
        stored = formatted("Z%.4f (tool table)", *entry->second.z);
      }
    } else {
      const auto entry = tools_.lengths.find(tool);
      if (entry == tools_.lengths.end()) {
        missing = "no length in the state file " + in_.state_name;
      } else {
        stored = format_length(config_, entry->second) + " (state file)";
      }
    }
    if (measures) {
      return std::string(measuring.checks ? "checked" : "measured") + " at the change" +
             (stored ? ", stored " + *stored : "");
    }
    if (measured_here_.count(tool) != 0) return "measured at an earlier change";
    if (stored) return *stored;
    if (never_measured_.insert(tool).second) {
      const std::string why =
          already ? "this M6 measures nothing (the tool is in the spindle already)"
                  : "M6 measures nothing (" + rule_said(config_, tool) +
                        (measuring.never ? ": give its length in the tool table" : "") +
                        ")";
      problem(use.where, tool_word(tool) + " was never measured: " + missing + ", and " + why);
    }
    return "never measured";
  }

  /// Each move of a planned change with the length of the tool it carries:
  /// a tip that would enter a holder is a problem on the change's line.
  void carried(const program::ToolUse& use, PlannedChange& planned) {
    const std::pair<double, double> held{lengths_.of(tools_.spindle, tools_.lengths).length,
                                         lengths_.of(*use.tool, tools_.lengths).length};
    auto checked = planned.carried.find(held);
    if (checked == planned.carried.end()) {
      const StepsFrom from{config_.safe, axis_xyz, lengths_, tools_.lengths};
      checked = planned.carried.emplace(held, check_steps(config_, planned.steps, std::nullopt, from)).first;
    }
    const std::string sequence = "M6 " + tool_word(*use.tool) + " from " +
                                 (tools_.spindle == 0 ? "empty" : tool_word(tools_.spindle));
    for (const Violation& violation : checked->second) {
      std::string text =
          describe({sequence, violation.step, planned.steps[violation.step], violation.what});
      if (named_.size() < program::kMaxErrors && named_.insert({use.where.line, text}).second) {
        problem(use.where, std::move(text));
      }
    }
  }

  /// The changer has a length of `tool`: from the state file, or measured by
  /// an earlier change of the program.
  bool measured(int tool) const {
    return tools_.lengths.count(tool) != 0 || measured_here_.count(tool) != 0;
  }

  /// The probe touches at the stored length, or at its limit when none is known.
  double sensor_z(int tool) const {
    const auto stored = tools_.lengths.find(tool);
    if (stored == tools_.lengths.end()) return config_.probe_limit.z;
    return std::max(config_.probe_length_compensation_offset + stored->second,
                    config_.probe_limit.z);
  }

  /// M6 T`to` from the rack as it is now (`from` in the spindle).
  PlannedChange& plan(int from, int to) {
    const double touch = sensor_z(to);
    // The same change plans the same while the pockets involved are the same.
    const auto key =
        std::make_tuple(from, to, touch, return_pocket(tools_, config_, from).value_or(0),
                        tools_.pocket_holding(to).value_or(0), measured(to));
    const auto known = plans_.find(key);
    if (known != plans_.end()) return known->second;
    // The problems the lint reports itself (a state cut off, a tool not in
    // its pocket) do not stop the estimate: it plans as if they were resolved.
    ToolState resolved = tools_;
    resolved.datum = {};
    resolved.uncertain = false;
    resolved.in_progress.reset();
    if (const auto home = resolved.home_of(to); home && to != from)
      resolved.pockets[*home].holds = true;
    if (measured(to) && resolved.lengths.count(to) == 0) {
      resolved.lengths[to] = touch - config_.probe_length_compensation_offset;
    }
    const Simulator sim = plan_change_timed(planning_, resolved, to, touch);
    PlannedChange planned;
    for (const Step& step : sim.steps()) {
      if (step.kind == StepKind::fail) planned.refused = step.label;
    }
    const ChangeTime time = change_time(sim, config_.safe, in_.machine);
    planned.seconds = time.seconds();
    planned.operator_waits = time.operator_waits;
    planned.steps = sim.steps();
    return plans_.emplace(key, std::move(planned)).first->second;
  }

  const PreflightInput& in_;
  const Config& config_;
  ToolState tools_;
  ToolLengths lengths_;  ///< the input's, with what the program set so far
  /// Lines and the problems named on them: a change in a loop is named once.
  std::set<std::pair<int, std::string>> named_;
  bool spindle_known_ = true;
  bool said_uncertain_ = false;
  Config planning_;  ///< the config each change is planned with: the datum judged apart
  int datum_changes_ = 0;  ///< changes since the datum's last check, as the changer counts them
  bool said_datum_ = false;
  std::set<int> never_measured_;
  std::set<int> measured_here_;  ///< tools a change of the program measured
  bool probe_start_said_ = false;  ///< an M3 or M4 with the probe in the spindle now was named
  std::map<std::tuple<int, int, double, int, int, bool>, PlannedChange> plans_;
  Preflight result_;
};

}  // namespace

Preflight preflight(const std::vector<program::ToolUse>& uses, const PreflightInput& input) {
  return Checker(input).run(uses);
}

}  // namespace fatc
