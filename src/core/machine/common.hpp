#pragma once

// Building blocks shared by every table: the flow base, the kinds of state
// (moving, timed, waiting for the operator), targets, guards and actions.

#include <boost/msm/back/state_machine.hpp>
#include <boost/msm/front/functor_row.hpp>
#include <boost/msm/front/state_machine_def.hpp>

#include "../events.hpp"
#include "../geometry.hpp"
#include "context.hpp"

namespace fatc::machine {

namespace msm = boost::msm;
namespace msmf = boost::msm::front;
using msmf::none;
using msmf::Row;

/// A submachine finished; raised by its exit point `Finished`.
struct LegDone {
  LegDone() = default;
  template <class Event>
  LegDone(const Event&) {}
};

/// A submachine cannot go on; ctx.fault_reason says why.
struct FlowFailed {
  FlowFailed() = default;
  template <class Event>
  FlowFailed(const Event&) {}
};

struct Finished : msmf::exit_pseudo_state<LegDone> {};
struct Failed : msmf::exit_pseudo_state<FlowFailed> {};
/// The operator cancelled inside a program: the program stops, nothing is uncertain.
struct Stopped : msmf::exit_pseudo_state<LegDone> {};

/// Base of every submachine front: takes the context from its parent on
/// entry and remembers which tool's pocket it serves.
template <class Derived>
struct Flow : msmf::state_machine_def<Derived> {
  Context* ctx = nullptr;
  int pocket_tool = 0;

  template <class Event, class Parent>
  void on_entry(const Event&, Parent& parent) {
    ctx = parent.ctx;
    pocket_tool = Derived::served_tool(*ctx);
  }
  static int served_tool(const Context& ctx) { return ctx.requested_tool; }
};

// ---------------------------------------------------------------- kinds of state

/// Publishes the step `Target` computes on entry, then waits for InPosition
/// (or ProbeResult, for a probe step).
template <class Target>
struct Moving : msmf::state<> {
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    fsm.ctx->status.awaiting = Awaiting::motion;
    fsm.ctx->publish(Target{}(*fsm.ctx, fsm.pocket_tool));
  }
};

/// Stands still for `Seconds` of the config, then TimerElapsed.
template <class Seconds>
struct Waiting : msmf::state<> {
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    fsm.ctx->wait(Seconds{}(fsm.ctx->config), fsm.ctx->status.activity);
  }
};

/// Ends the executor run and asks the operator; Continue or Cancel follow.
template <class Prompt>
struct AskingOperator : msmf::state<> {
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    Step pause;
    pause.kind = StepKind::wait_operator;
    pause.label = "operator";
    fsm.ctx->publish(pause);
    fsm.ctx->ask_operator(Prompt{}(*fsm.ctx));
  }
};

/// Asks the operator inside a running program (M6): nothing is published, so
/// the executor keeps waiting for its next step; Continue or Cancel follow.
template <class Prompt>
struct HoldingForOperator : msmf::state<> {
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    fsm.ctx->ask_operator(Prompt{}(*fsm.ctx));
  }
};

/// A state that decides at once, through guarded anonymous rows.
struct Choosing : msmf::state<> {};

// ---------------------------------------------------------------- durations

struct ChuckSeconds {
  double operator()(const Config& c) const { return c.chuck_seconds; }
};
struct FlushPulseSeconds {
  double operator()(const Config& c) const { return c.flush.pulse_seconds; }
};
struct FlushPauseSeconds {
  double operator()(const Config& c) const { return c.flush.pause_seconds; }
};

// ---------------------------------------------------------------- targets

namespace to {

inline Step move(StepKind kind, unsigned axes, const Point& target, std::string label,
                 int pocket = 0, bool approach = false, double feed = 0.0) {
  Step step;
  step.kind = kind;
  step.axes = axes;
  step.target = target;
  step.label = std::move(label);
  step.pocket = pocket;
  step.approach = approach;
  step.feed = feed;
  return step;
}

inline std::string of_pocket(const char* what, int tool) {
  return std::string(what) + " of pocket " + std::to_string(tool);
}

struct SafeZ {
  Step operator()(const Context& c, int) const {
    return move(StepKind::rapid, axis_z, c.config.safe, "safe Z");
  }
};
struct SafeXY {
  Step operator()(const Context& c, int) const {
    return move(StepKind::rapid, axis_xy, c.config.safe, "safe XY");
  }
};
/// Straight up from the pocket or its side, still within its approach.
struct SafeZOverPocket {
  Step operator()(const Context& c, int tool) const {
    return move(StepKind::rapid, axis_z, c.config.safe, "safe Z", tool, true);
  }
};
struct SideAtSafeZ {
  Step operator()(const Context& c, int tool) const {
    const Point side = pocket_waypoints(c.config, tool).side;
    return move(StepKind::rapid, axis_xy, side, of_pocket("over the side", tool), tool);
  }
};
struct Side {
  Step operator()(const Context& c, int tool) const {
    return move(StepKind::rapid, axis_z, pocket_waypoints(c.config, tool).side,
                of_pocket("side", tool), tool, true);
  }
};
struct SlowlyToSide {
  Step operator()(const Context& c, int tool) const {
    return move(StepKind::feed, axis_xy, pocket_waypoints(c.config, tool).side,
                of_pocket("side", tool), tool, true, c.config.pocket_feed);
  }
};
struct SlowlyIntoPocket {
  Step operator()(const Context& c, int tool) const {
    return move(StepKind::feed, axis_xy, pocket_waypoints(c.config, tool).pocket,
                "pocket " + std::to_string(tool), tool, true, c.config.pocket_feed);
  }
};
struct SlowlyDownToPocket {
  Step operator()(const Context& c, int tool) const {
    return move(StepKind::feed, axis_z, pocket_waypoints(c.config, tool).pocket,
                "pocket " + std::to_string(tool), tool, true, c.config.pocket_feed);
  }
};
struct PocketAtSafeZ {
  Step operator()(const Context& c, int tool) const {
    return move(StepKind::rapid, axis_xy, pocket_waypoints(c.config, tool).pocket,
                "over pocket " + std::to_string(tool), tool);
  }
};
struct AboveChuck {
  Step operator()(const Context& c, int tool) const {
    return move(StepKind::rapid, axis_z, pocket_waypoints(c.config, tool).above_chuck,
                of_pocket("above-chuck", tool), tool, true);
  }
};
struct AboveClearance {
  Step operator()(const Context& c, int tool) const {
    return move(StepKind::rapid, axis_z, pocket_waypoints(c.config, tool).above_clearance,
                of_pocket("above-clearance", tool), tool, true);
  }
};
struct LoadingZ {
  Step operator()(const Context& c, int) const {
    return move(StepKind::rapid, axis_z, c.config.loading, "loading Z");
  }
};
struct LoadingXY {
  Step operator()(const Context& c, int) const {
    return move(StepKind::rapid, axis_xy, c.config.loading, "loading XY");
  }
};
/// Over the touch-off sensor, at the current Z.
struct SensorXY {
  Step operator()(const Context& c, int) const {
    return move(StepKind::rapid, axis_xy, c.config.probe_limit, "over the touch-off sensor");
  }
};
struct ProbeSeek {
  Step operator()(const Context& c, int) const {
    return move(StepKind::probe, axis_z, c.config.probe_limit, "touch-off sensor (seek)", 0,
                false, c.config.probe_seek_feed);
  }
};
struct ProbeBackOff {
  Step operator()(const Context& c, int) const {
    Point above = c.config.probe_limit;
    above.z = c.first_touch_z + c.config.probe_backoff;
    return move(StepKind::feed, axis_z, above, "back off the sensor", 0, false,
                c.config.probe_seek_feed);
  }
};
struct ProbeLatch {
  Step operator()(const Context& c, int) const {
    return move(StepKind::probe, axis_z, c.config.probe_limit, "touch-off sensor (latch)", 0,
                false, c.config.probe_latch_feed);
  }
};
struct RetractFromSensor {
  Step operator()(const Context& c, int) const {
    Point up = c.config.probe_limit;
    up.z = c.latched_z + c.config.probe_retract_offset_z;
    return move(StepKind::rapid, axis_z, up, "retract from the sensor");
  }
};
/// Tells LinuxCNC (M61) what the spindle holds now.
struct SpindleTool {
  Step operator()(const Context& c, int) const {
    Step step;
    step.kind = StepKind::set_spindle_tool;
    step.tool = c.tools.spindle;
    step.label = "tool in spindle";
    return step;
  }
};
struct ToolLength {
  Step operator()(const Context& c, int tool) const {
    Step step;
    step.kind = StepKind::set_tool_length;
    step.tool = tool;
    step.value = c.tools.lengths.at(tool);
    step.label = "tool table";
    return step;
  }
};

}  // namespace to

// ---------------------------------------------------------------- guards

template <class Guard>
struct Not {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event& e, Fsm& fsm, Source& s, Target& t) const {
    return !Guard{}(e, fsm, s, t);
  }
};

template <class First, class Second>
struct And {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event& e, Fsm& fsm, Source& s, Target& t) const {
    return First{}(e, fsm, s, t) && Second{}(e, fsm, s, t);
  }
};

struct SpindleHoldsTool {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->tools.spindle != 0;
  }
};
struct RequestedToolInSpindle {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->tools.spindle == fsm.ctx->requested_tool;
  }
};
struct SpindleHoldsOtherTool {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->tools.spindle != 0 && fsm.ctx->tools.spindle != fsm.ctx->requested_tool;
  }
};
/// The spindle holds a tool that has a pocket to go back to.
struct SpindleHoldsRackTool {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->tools.spindle != 0 && fsm.ctx->config.has_pocket(fsm.ctx->tools.spindle);
  }
};
/// The spindle holds a manual tool: one with no pocket, handed over at `loading`.
struct SpindleHoldsManualTool {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->tools.spindle != 0 && !fsm.ctx->config.has_pocket(fsm.ctx->tools.spindle);
  }
};
struct RequestedRackTool {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->requested_tool != 0 && fsm.ctx->config.has_pocket(fsm.ctx->requested_tool);
  }
};
struct RequestedManualTool {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->requested_tool != 0 && !fsm.ctx->config.has_pocket(fsm.ctx->requested_tool);
  }
};
struct ToolRequested {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->requested_tool != 0;
  }
};

// ---------------------------------------------------------------- actions

struct CloseChuck {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    fsm.ctx->close_chuck();
  }
};
struct CancelTimer {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    fsm.ctx->ports.cancel_timer();
  }
};

}  // namespace fatc::machine
