// The keep-out check's side of the tool in the spindle: its length as the
// guard counts it, the changes that put it there, and the chuck release.
#include <cmath>
#include <utility>

#include "../dry_run/simulator.hpp"
#include "../machine/base/admission.hpp"
#include "keepout_axes.hpp"
#include "keepout_check.hpp"

namespace fatc {

using namespace keepout_axes;

std::optional<double> KeepoutCheck::table_length(int tool) const {
  if (tool == 0) return 0.0;
  if (const auto set = set_lengths_.find(tool); set != set_lengths_.end()) return set->second;
  if (!in_.lengths) return std::nullopt;
  const auto found = in_.lengths->find(tool);
  if (found == in_.lengths->end()) return std::nullopt;
  return found->second;
}

double KeepoutCheck::tool_length(int line) {
  if (!spindle_) {
    if (!said_unknown_tool_) {
      said_unknown_tool_ = true;
      unknown(line, "the tool in the spindle is known only when the program runs: its moves are "
                    "checked against the rack with no tool length");
    }
    return 0.0;
  }
  if (*spindle_ == 0) return 0.0;
  if (!in_.lengths && !set_lengths_.count(*spindle_)) {
    if (!said_no_table_) {
      said_no_table_ = true;
      unknown(line, "no tool table (--tool-table, or the INI's [EMCIO]TOOL_TABLE): the moves "
                    "are checked against the rack with no tool length");
    }
    return 0.0;
  }
  // A Z of 0 or below, or none, never lowers the boundary: the guard's rule.
  ToolLengths lengths;
  if (const auto z = table_length(*spindle_)) lengths.table[*spindle_] = *z;
  if (lengths.of(*spindle_, in_.tools.lengths).source == LengthSource::longest) {
    if (!longest_) longest_ = in_.longest ? in_.longest() : 0.0;
    lengths.longest = *longest_;
  }
  if (said_no_length_.size() < program::kMaxErrors &&
      lengths.of(*spindle_, in_.tools.lengths).source != LengthSource::table &&
      said_no_length_.insert(*spindle_).second) {
    // A length G10 set is the running table's, not the file's.
    unknown(line, keepout_length_words(*in_.config, lengths, *spindle_, in_.tools.lengths) +
                      (set_lengths_.count(*spindle_) ? "" : " (tool table " + in_.table_name + ")"));
  }
  return lengths.of(*spindle_, in_.tools.lengths).length;
}

void KeepoutCheck::tool_use(const program::ToolUse& use) {
  ++uses_told_;
  if (use.kind == program::ToolUse::Kind::set) {
    spindle_ = use.tool;  // M61: LinuxCNC is told; nothing moves
    return;
  }
  change(use);
}

void KeepoutCheck::change(const program::ToolUse& use) {
  const bool moves = !use.tool || !spindle_ || *use.tool != *spindle_;
  if (moves) {
    // Where the change ends is worked out when a move needs it (a program of
    // changes alone plans none); a change that follows before any move
    // replaces it, and the first one's way back with RETURN_TO_XY goes unchecked.
    pending_ = PendingChange{use.where.line, spindle_, use.tool, nose_, known_};
    known_ = 0;
    out_of_step_ = kAll;
  }
  spindle_ = use.tool;
}

void KeepoutCheck::chuck_release(int line) {
  settle();
  const Config& config = *in_.config;
  std::string why;
  if (turning_) {
    why = "the spindle is on: M5 first";
  } else if (spindle_ && *spindle_ != 0) {
    const Point& loading = config.loading;
    const double tolerance = loading_tolerance(config);
    const bool at_loading = known_ == kAll && std::fabs(nose_.x - loading.x) <= tolerance &&
                            std::fabs(nose_.y - loading.y) <= tolerance &&
                            std::fabs(nose_.z - loading.z) <= tolerance;
    if (!at_loading) {
      why = "T" + std::to_string(*spindle_) + " is in the spindle and would drop: release it only at loading (machine " +
            machine_words(config, loading) + ") or with the spindle empty";
    }
  }
  if (why.empty()) return;
  problems_.push_back(
      program::finding(in_.program, line, "the chuck release would be refused: " + why));
}

void KeepoutCheck::settle() {
  if (!pending_) return;
  const PendingChange change = *pending_;
  pending_.reset();
  if (!change.from || !change.to) return;  // nothing is known of the change, nor where it ends
  const auto end = change_end(*change.from, *change.to);
  if (!end) return;
  nose_ = *end;
  known_ = kAll;
  if (in_.return_to_xy && (change.known & (kX | kY)) == (kX | kY)) {
    // fixed_atc_probe_m6.ngc: back over the XY it was called at, at the Z the change ended.
    const Point back{change.called_at.x, change.called_at.y, nose_.z};
    check(change.line, true, "M6's way back over where it was called (RETURN_TO_XY)", nose_, back);
    nose_ = back;
  }
}

std::optional<Point> KeepoutCheck::change_end(int from, int to) {
  const auto known = change_ends_.find({from, to});
  if (known != change_ends_.end()) return known->second;
  // The changer's own plan for the change, from the rack as the state file
  // has it (the problems --lint names itself, a cut-off state or a tool not
  // in its pocket, resolved as the estimate resolves them); a refused
  // change stops the program, and where it leaves the nose is not known.
  ToolState tools = in_.tools;
  tools.uncertain = false;
  tools.in_progress.reset();
  tools.put_in_spindle(from);
  if (const auto home = tools.home_of(to); home && to != from) tools.pockets[*home].holds = true;
  const Simulator sim = plan_change(*in_.config, tools, to, in_.config->probe_limit.z);
  Point end;
  unsigned set = 0;
  bool refused = false;
  for (const Step& step : sim.steps()) {
    if (step.kind == StepKind::fail) refused = true;
    if (!is_motion(step.kind)) continue;
    for (int a = 0; a < 3; ++a) {
      if (step.axes & (1u << a)) axis(end, a) = axis(step.target, a);
    }
    set |= step.axes;
  }
  std::optional<Point> result;
  if (!refused && (set & kAll) == kAll) result = end;
  change_ends_.emplace(std::make_pair(from, to), result);
  return result;
}

}  // namespace fatc
