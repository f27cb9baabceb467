#include "keepout_check.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <utility>

#include "../dry_run/simulator.hpp"
#include "../formatted.hpp"
#include "../machine/base/admission.hpp"
#include "canonical_call.hpp"

namespace fatc {
namespace {

using program::call_numbers;
using program::starts_with;

constexpr unsigned kX = 1, kY = 2, kZ = 4, kAll = 7;

/// What rs274 prints of nc_files/fixed_atc_probe_chuck_release.ngc's first
/// comment: the release, called by its M-code or by name, preview or not.
constexpr std::string_view kReleaseMarker =
    "COMMENT(\"Releases - opens - the chuck through fixed_atc_probe";

/// How far a chord of an arc may lie inside it: the arc is checked as chords
/// at most this far from it, in the config's units.
double arc_tolerance(const Config& config) { return config.units == Units::inch ? 0.00004 : 0.001; }
/// The most chords an arc is checked as; beyond (a radius of kilometres),
/// the chords lie farther from the arc than arc_tolerance.
constexpr double kMaxChords = 100000;

double& axis(Point& p, int a) { return a == 0 ? p.x : a == 1 ? p.y : p.z; }
double axis(const Point& p, int a) { return a == 0 ? p.x : a == 1 ? p.y : p.z; }

/// The machine point of a call's first three numbers, all finite; nullopt else.
std::optional<Point> point_of(const std::vector<double>& args) {
  if (args.size() < 3) return std::nullopt;
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(args[static_cast<std::size_t>(a)])) return std::nullopt;
  }
  return Point{args[0], args[1], args[2]};
}

double mm_of(std::string_view units) {
  if (units.find("INCHES") != std::string_view::npos) return 25.4;
  if (units.find("CM") != std::string_view::npos) return 10.0;
  return 1.0;
}

/// "X150.000 Y20.000 Z-25.000", machine coordinates in the config's units.
std::string machine_words(const Config& config, const Point& at) {
  return formatted(config.units == Units::inch ? "X%.4f Y%.4f Z%.4f" : "X%.3f Y%.3f Z%.3f", at.x,
                   at.y, at.z);
}

/// The length a G10 line wrote, in the program's units (`program_mm` mm
/// each), from the inches rs274 prints it in, to 4 decimals: the shortest
/// decimal that prints so. A length written to 0.01 mm comes back as written
/// (80, not 79.9998); beyond, within the 0.00127 mm rs274 leaves.
double written_length(double printed_inches, double program_mm) {
  const double length = printed_inches * 25.4 / program_mm;
  const double half_printed_step = 0.00005 * 25.4 / program_mm;
  for (double scale = 1; scale <= 1e4; scale *= 10) {
    const double shortest = std::round(length * scale) / scale;
    if (std::fabs(shortest - length) <= half_printed_step) return shortest;
  }
  return length;
}

bool boxes_meet(const Box& a, const Box& b) {
  return a.low.x < b.high.x && b.low.x < a.high.x && a.low.y < b.high.y && b.low.y < a.high.y &&
         a.low.z < b.high.z && b.low.z < a.high.z;
}

}  // namespace

KeepoutCheck::KeepoutCheck(KeepoutCheckInput input)
    : in_(std::move(input)), volume_(rack_volume(*in_.config)), spindle_(in_.tools.spindle) {
  const double config_mm = in_.config->units == Units::inch ? 25.4 : 1.0;
  rs274_.config_units_per_program_unit = 1.0 / config_mm;
}

void KeepoutCheck::call(int line, bool numbered, std::string_view call) {
  // The calls that move or set the coordinate system; the rest (feeds,
  // spindle, comments) change nothing here.
  if (starts_with(call, "STRAIGHT_TRAVERSE(") || starts_with(call, "STRAIGHT_FEED(")) {
    if (const auto to = point_of(call_numbers(call))) {
      move(line, numbered, starts_with(call, "STRAIGHT_TRAVERSE(") ? "G0" : "G1", *to);
    }
  } else if (starts_with(call, "ARC_FEED(")) {
    arc(line, numbered, call_numbers(call));
  } else if (starts_with(call, "STRAIGHT_PROBE(")) {
    if (const auto to = point_of(call_numbers(call))) probe(line, numbered, *to);
  } else if (starts_with(call, "RIGID_TAP(")) {
    if (const auto to = point_of(call_numbers(call))) rigid_tap(line, numbered, *to);
  } else if (starts_with(call, "NURBS_FEED(") || starts_with(call, "SPLINE_FEED(")) {
    // rs274 prints neither a spline's points nor its end: its way is not
    // known, and where it ends only from the next move's X and Y.
    settle();
    known_ &= ~(kX | kY);
    out_of_step_ &= ~(kX | kY);
    if (!said_spline_) {
      said_spline_ = true;
      unknown(line, "a spline (G5, G5.1, G5.2): its way is not checked against the rack");
    }
  } else if (starts_with(call, "USE_LENGTH_UNITS(")) {
    const double config_mm = in_.config->units == Units::inch ? 25.4 : 1.0;
    rs274_.config_units_per_program_unit = mm_of(call) / config_mm;
  } else if (starts_with(call, "SELECT_PLANE(")) {
    plane_ = call.find("XZ") != std::string_view::npos   ? 18
             : call.find("YZ") != std::string_view::npos ? 19
                                                         : 17;
  } else if (starts_with(call, "SET_XY_ROTATION(")) {
    const auto args = call_numbers(call);
    if (!args.empty()) rs274_.xy_rotation_degrees = args[0];
  } else if (starts_with(call, "SET_TOOL_TABLE_ENTRY(")) {
    // G10 L1, L10, L11: (row, tool, X Y Z A B C U V W, ...).
    const auto args = call_numbers(call);
    if (args.size() >= 5 && args[1] > 0 && std::isfinite(args[4])) {
      const double config_mm = in_.config->units == Units::inch ? 25.4 : 1.0;
      const double program_mm = rs274_.config_units_per_program_unit * config_mm;
      const int tool = static_cast<int>(args[1]);
      const double length = written_length(args[4], program_mm) * program_mm / config_mm;
      set_lengths_[tool] = length;
      // rs274 prints the tool's row and the spindle's: one a tool between two uses.
      if (!lengths_set_.empty() && lengths_set_.back().before_use == uses_told_ &&
          lengths_set_.back().tool == tool) {
        lengths_set_.back().length = length;
      } else if (uses_told_ <= program::kMaxToolUses) {
        lengths_set_.push_back({uses_told_, tool, length});
      }
    }
  } else if (starts_with(call, "START_SPINDLE_")) {
    turning_ = true;
  } else if (starts_with(call, "STOP_SPINDLE_TURNING(")) {
    turning_ = false;
  } else if (starts_with(call, kReleaseMarker)) {
    chuck_release(line);
  } else {
    // Offsets, in the program's units when they are set (LinuxCNC keeps them in its own).
    const double k = rs274_.config_units_per_program_unit;
    auto offset = [k](const std::vector<double>& args, std::size_t first) -> std::optional<Point> {
      if (args.size() < first + 3) return std::nullopt;
      return Point{args[first] * k, args[first + 1] * k, args[first + 2] * k};
    };
    if (starts_with(call, "SET_G5X_OFFSET(")) {
      if (const auto o = offset(call_numbers(call), 1)) rs274_.g5x = *o;
    } else if (starts_with(call, "SET_G92_OFFSET(")) {
      if (const auto o = offset(call_numbers(call), 0)) rs274_.g92 = *o;
    } else if (starts_with(call, "USE_TOOL_LENGTH_OFFSET(")) {
      if (const auto o = offset(call_numbers(call), 0)) rs274_.tool_offset = *o;
    }
  }
}

std::pair<Point, unsigned> KeepoutCheck::target(const Point& program_to) {
  const Point said = rs274_.machine(program_to);
  Point to = said;
  unsigned known = kAll;
  // Where rs274's position is not the machine's (at the start, after an M6),
  // an axis the line leaves where rs274 has it is one the line does not
  // name: the machine's stays where it is (unknown before the first move
  // that names it). So the start position, unknown, is never checked: a
  // move counts from the axes it sets. An axis set to the very value rs274
  // had (machine 0 at the start) reads as not named: skipped, not guessed.
  for (int a = 0; a < 3; ++a) {
    const unsigned bit = 1u << a;
    if (!(out_of_step_ & bit)) continue;
    if (std::fabs(axis(said, a) - axis(rs274_at_, a)) < 1e-4) {
      axis(to, a) = axis(nose_, a);
      if (!(known_ & bit)) known &= ~bit;
    } else {
      out_of_step_ &= ~bit;
    }
  }
  rs274_at_ = said;
  return {to, known};
}

void KeepoutCheck::move(int line, bool numbered, const char* code, const Point& program_to) {
  settle();
  const auto [to, known] = target(program_to);
  if (known_ == kAll && known == kAll) {
    check(line, numbered, code, nose_, to);
  } else if (known == kAll) {
    check(line, numbered, code, to, to);  // only where it ends: where it starts is not known
  }
  nose_ = to;
  known_ = known;
}

void KeepoutCheck::probe(int line, bool numbered, const Point& program_to) {
  settle();
  const Point from = nose_;
  move(line, numbered, "G38", program_to);
  // It stops where it touches, which only the machine knows; the
  // interpreter goes on from there.
  for (int a = 0; a < 3; ++a) {
    if (std::fabs(axis(nose_, a) - axis(from, a)) > 1e-9) {
      known_ &= ~(1u << a);
      out_of_step_ |= 1u << a;
    }
  }
}

void KeepoutCheck::rigid_tap(int line, bool numbered, const Point& program_to) {
  settle();
  // Down to the hole's bottom and back out to where it started.
  const Point from = nose_, said = rs274_at_;
  const unsigned known = known_;
  move(line, numbered, "G33.1", program_to);
  nose_ = from;
  known_ = known;
  rs274_at_ = said;
}

void KeepoutCheck::arc(int line, bool numbered, const std::vector<double>& args) {
  // ARC_FEED(first end, second end, first centre, second centre, turns,
  // axis end, ...): G17 first X second Y; G18 first Z second X; G19 first Y
  // second Z. Turns: > 0 counterclockwise from first to second, < 0
  // clockwise; |turns| - 1 full turns more.
  settle();
  if (args.size() < 6) return;
  for (std::size_t i = 0; i < 6; ++i) {
    if (!std::isfinite(args[i])) return;
  }
  const std::array<int, 3> axes = plane_ == 18   ? std::array<int, 3>{2, 0, 1}
                                  : plane_ == 19 ? std::array<int, 3>{1, 2, 0}
                                                 : std::array<int, 3>{0, 1, 2};
  Point end;
  axis(end, axes[0]) = args[0];
  axis(end, axes[1]) = args[1];
  axis(end, axes[2]) = args[5];
  const int turns = static_cast<int>(std::lround(args[4]));
  const char* code = turns < 0 ? "G2" : "G3";
  // The way is known where the machine's position is rs274's: else (the
  // first move, or the first after an M6) only its chord is checked.
  if (known_ != kAll || out_of_step_ != 0 || turns == 0) {
    move(line, numbered, code, end);
    return;
  }
  const Point start = rs274_.program(rs274_at_);
  const double c1 = args[2], c2 = args[3];
  const double s1 = axis(start, axes[0]) - c1, s2 = axis(start, axes[1]) - c2;
  const double e1 = args[0] - c1, e2 = args[1] - c2;
  const double r0 = std::hypot(s1, s2), r1 = std::hypot(e1, e2);
  const double a0 = std::atan2(s2, s1);
  double sweep = std::atan2(e2, e1) - a0;
  if (turns > 0) {
    while (sweep <= 1e-12) sweep += 2.0 * M_PI;
    sweep += 2.0 * M_PI * (turns - 1);
  } else {
    while (sweep >= -1e-12) sweep -= 2.0 * M_PI;
    sweep -= 2.0 * M_PI * (-turns - 1);
  }
  const double z0 = axis(start, axes[2]), z1 = args[5];
  auto program_at = [&](double t) {
    Point p;
    const double r = r0 + (r1 - r0) * t;
    const double angle = a0 + sweep * t;
    axis(p, axes[0]) = c1 + r * std::cos(angle);
    axis(p, axes[1]) = c2 + r * std::sin(angle);
    axis(p, axes[2]) = z0 + (z1 - z0) * t;
    return p;
  };
  // Most arcs are nowhere near the rack: the box around their whole circle
  // first, chords only where it meets the volume.
  const double radius = std::max(r0, r1);
  Box around{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
  for (const double d1 : {-radius, radius}) {
    for (const double d2 : {-radius, radius}) {
      for (const double z : {z0, z1}) {
        Point corner;
        axis(corner, axes[0]) = c1 + d1;
        axis(corner, axes[1]) = c2 + d2;
        axis(corner, axes[2]) = z;
        const Point m = rs274_.machine(corner);
        around.low = {std::min(around.low.x, m.x), std::min(around.low.y, m.y),
                      std::min(around.low.z, m.z)};
        around.high = {std::max(around.high.x, m.x), std::max(around.high.y, m.y),
                       std::max(around.high.z, m.z)};
      }
    }
  }
  const double length = std::max(tool_length(line), 0.0);
  const bool near_rack = std::any_of(volume_.begin(), volume_.end(), [&](const RackPart& part) {
    Box raised = part.box;
    raised.high.z += length;
    raised.low = {raised.low.x - 1.0, raised.low.y - 1.0, raised.low.z - 1.0};
    raised.high = {raised.high.x + 1.0, raised.high.y + 1.0, raised.high.z + 1.0};
    return boxes_meet(around, raised);
  });
  const auto [to, known] = target(end);
  if (near_rack) {
    // Chords whose sagitta r (1 - cos(step / 2)) stays within the tolerance.
    const double tolerance = arc_tolerance(*in_.config) / rs274_.config_units_per_program_unit;
    const double step =
        radius > tolerance ? 2.0 * std::acos(1.0 - tolerance / radius) : 2.0 * M_PI;
    const double chords = std::clamp(std::ceil(std::fabs(sweep) / step), 1.0, kMaxChords);
    Point from = nose_;
    for (double i = 1; i <= chords; ++i) {
      const Point at = i == chords ? to : rs274_.machine(program_at(i / chords));
      if (!check(line, numbered, code, from, at)) break;
      from = at;
    }
  }
  nose_ = to;
  known_ = known;
}

bool KeepoutCheck::check(int line, bool numbered, const char* code, const Point& from,
                         const Point& to) {
  if (named_.count(line)) return false;
  const double length = tool_length(line);
  // A move that starts in the volume was named where it went in (or starts
  // where nothing is known): only a place where it ends, `from` == `to`, or
  // a way in counts.
  const auto inside = std::find_if(volume_.begin(), volume_.end(), [&](const RackPart& part) {
    Box raised = part.box;
    raised.high.z += std::max(length, 0.0);
    return entry_along(from, from, raised).has_value();
  });
  const bool only_the_end = from.x == to.x && from.y == to.y && from.z == to.z;
  std::optional<RackEntry> entry;
  if (inside != volume_.end()) {
    if (only_the_end) entry = RackEntry{nearest_pocket(*inside, to), to};
  } else if (!only_the_end) {
    entry = rack_entry(volume_, from, to, length);
  }
  if (!entry) return true;
  if (named_.size() >= program::kMaxErrors) {
    ++more_;
    return false;
  }
  named_.insert(line);
  const Config& config = *in_.config;
  std::string held;
  if (!spindle_) {
    held = "with a tool known only when the program runs (counted with no length)";
  } else if (*spindle_ == 0 || in_.lengths || set_lengths_.count(*spindle_)) {
    held = held_words(config, *spindle_, length);
  } else {
    held = "with T" + std::to_string(*spindle_) + " (no length known: counted as 0)";
  }
  problems_.push_back(program::finding(
      in_.program, line,
      std::string(code) + " would enter the rack at pocket " + std::to_string(entry->pocket) +
          " " + held + ", the nose at machine " + machine_words(config, entry->nose) +
          (numbered ? "" : " (in a subroutine this line calls)")));
  return false;
}

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

void KeepoutCheck::unknown(int line, const std::string& text) {
  if (unknowns_.size() < program::kMaxErrors) unknowns_.push_back(program::finding(in_.program, line, text));
}

std::vector<program::Finding> KeepoutCheck::problems() const {
  std::vector<program::Finding> all = problems_;
  if (more_ > 0) {
    all.push_back(program::finding(in_.program, 0,
                                   std::to_string(more_) + " more lines would enter the rack"));
  }
  return all;
}

}  // namespace fatc
