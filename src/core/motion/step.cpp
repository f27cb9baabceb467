#include "step.hpp"

#include "../formatted.hpp"

namespace fatc {

Step move_step(StepKind kind, unsigned axes, const Point& target, std::string label, int pocket,
               bool may_enter_column, double feed) {
  Step step;
  step.kind = kind;
  step.axes = axes;
  step.target = target;
  step.label = std::move(label);
  step.pocket = pocket;
  step.may_enter_column = may_enter_column;
  step.feed = feed;
  return step;
}

Step spindle_step(double rpm, std::string label, int pocket) {
  Step step;
  step.kind = StepKind::spindle;
  step.value = rpm;
  step.label = std::move(label);
  step.pocket = pocket;
  return step;
}

Step failure_step(std::string why) {
  Step step;
  step.kind = StepKind::fail;
  step.label = std::move(why);
  return step;
}

Step resync_step() {
  Step step;
  step.kind = StepKind::resync;
  step.label = "resync";
  return step;
}

bool is_motion(StepKind kind) {
  return kind == StepKind::rapid || kind == StepKind::feed || kind == StepKind::probe;
}

Point moved_to(const Point& from, const Step& move) {
  Point to = from;
  if (move.axes & axis_x) to.x = move.target.x;
  if (move.axes & axis_y) to.y = move.target.y;
  if (move.axes & axis_z) to.z = move.target.z;
  return to;
}

std::vector<Step> moves_of(const Step& step) {
  std::vector<Step> moves;
  for (Step move : step.before) {
    move.blend = step.blend;
    move.held = step.held;
    moves.push_back(std::move(move));
  }
  Step last = step;
  last.before.clear();
  last.blend = 0.0;
  moves.push_back(std::move(last));
  return moves;
}

Via via_of(const Step& step) {
  int via = 0;
  for (const Step& move : step.before) via |= move.axes == axis_z ? 1 : 2;
  return static_cast<Via>(via);
}

const char* step_kind_name(StepKind kind) {
  switch (kind) {
    case StepKind::resync:
      return "resync";
    case StepKind::rapid:
      return "rapid";
    case StepKind::feed:
      return "feed";
    case StepKind::probe:
      return "probe";
    case StepKind::set_tool_length:
      return "set-length";
    case StepKind::set_spindle_tool:
      return "set-tool";
    case StepKind::wait_operator:
      return "wait";
    case StepKind::done:
      return "done";
    case StepKind::fail:
      return "fail";
    case StepKind::spindle:
      return "spindle";
  }
  return "?";
}

std::string describe(const Step& step) {
  std::string coordinates;
  if (is_motion(step.kind)) {
    const char* names[] = {"X", "Y", "Z"};
    const double values[] = {step.target.x, step.target.y, step.target.z};
    for (int i = 0; i < 3; ++i) {
      if (step.axes & (1u << i)) {
        coordinates += formatted("%s%s=%.3f", coordinates.empty() ? "" : " ", names[i], values[i]);
      }
    }
    if (step.kind != StepKind::rapid) {
      coordinates += formatted(" F%.0f", step.feed);
    }
  } else if (step.kind == StepKind::set_tool_length) {
    coordinates = formatted("T%d length=%.4f", step.tool, step.value);
  } else if (step.kind == StepKind::set_spindle_tool || step.kind == StepKind::done) {
    coordinates = "T" + std::to_string(step.tool);
  } else if (step.kind == StepKind::spindle) {
    coordinates = step.value > 0.0   ? formatted("M3 S%.0f", step.value)
                  : step.value < 0.0 ? formatted("M4 S%.0f", -step.value)
                                     : std::string("M5");
  }
  std::string line = formatted("%-10s ", step_kind_name(step.kind));
  line += coordinates;
  if (line.size() < 48) line.resize(48, ' ');
  line += " " + step.label;
  if (step.blend > 0.0) {
    line += formatted(", on into the next within %.3f", step.blend);
  }
  return line;
}

}  // namespace fatc
