#pragma once

// Building blocks shared by every table: the flow base, the kinds of state
// (moving, timed, waiting for the operator), targets, guards and actions.

#include <algorithm>
#include <boost/msm/back/favor_compile_time.hpp>
#include <boost/msm/back/state_machine.hpp>
#include <boost/msm/front/functor_row.hpp>
#include <boost/msm/front/state_machine_def.hpp>
#include <cstdio>
#include <type_traits>

#include "../../rack/geometry.hpp"
#include "admission.hpp"
#include "events.hpp"
#include "flow_run.hpp"

namespace fatc::machine {

namespace msm = boost::msm;
namespace msmf = boost::msm::front;
using msmf::Internal;
using msmf::none;
using msmf::Row;

/// Every machine of the changer: the top, Operating, each flow and each leg.
/// `favor_compile_time` lets a machine's event dispatch be generated in a
/// translation unit of its own (BOOST_MSM_BACK_GENERATE_PROCESS_EVENT in
/// machine/*.cpp), so no compiler run instantiates the whole machine at once.
template <class Front>
using Machine_of = msm::back::state_machine<Front, msm::back::favor_compile_time>;

/// Flags the states carry; the status view is computed from them
/// (`is_flag_active`), so what the pins show is what the machine is in.
namespace flag {
struct NotReady {};
struct Idle {};
struct Faulted {};
struct Busy {};          ///< a flow runs (its kind, flows/NAME.hpp, is a flag too)
struct AwaitsMotion {};  ///< the executor performs a move or a command
struct AwaitsProbe {};   ///< the executor performs a probe move
struct AwaitsTimer {};
struct AwaitsSpindle {};
struct AwaitsSensor {};    ///< a wired sensor must confirm a change (drawbar, tool, air)
struct AwaitsOperator {};  ///< Continue or Cancel
struct HoldsProgram {};    ///< an operator wait inside M6: the program holds
struct EndedFinished {};   ///< a flow reached its end
struct EndedCancelled {};  ///< a flow ended early: the operator cancelled
struct EndedFailed {};     ///< a flow cannot go on
template <class... Flags>
struct List {};
/// The flags a state inside a flow may carry: what FlowRun::flagged answers
/// (Busy and the flow's kind are on Running<Flow>, the rest on the machine above).
using InFlows = List<AwaitsMotion, AwaitsProbe, AwaitsTimer, AwaitsSpindle, AwaitsSensor,
                     AwaitsOperator, HoldsProgram, EndedFinished, EndedCancelled, EndedFailed>;
}  // namespace flag

/// A leg finished; raised by its exit point `Finished`.
struct LegDone {
  LegDone() = default;
  template <class Event>
  LegDone(const Event&) {}
};

struct Finished;
struct Failed;
struct Cancelled;
/// A leg or a flow cannot go on. A leg's failure is its flow's (Flow::failure
/// says why); the flow's end carries `reason` to the machine above (Engine).
struct FlowFailed {
  using ends_at = Failed;  ///< where the diagram draws it from
  FlowFailed() = default;
  explicit FlowFailed(std::string why) : reason(std::move(why)) {}
  template <class Event>
  FlowFailed(const Event&) {}
  std::string reason;
};
/// A flow reached its end, or ended early for the operator's Cancel.
struct FlowFinished {
  using ends_at = Finished;
};
struct FlowCancelled {
  using ends_at = Cancelled;
};

/// Where a leg or a flow ends. A leg's end is an exit point its flow takes
/// on; a flow runs as a machine of its own (flow_run.hpp), so its end is a
/// flag the machine above reads, then takes as FlowFinished, FlowCancelled
/// or FlowFailed.
struct Finished : msmf::exit_pseudo_state<LegDone> {
  using flag_list = boost::mpl::vector1<flag::EndedFinished>;
};
struct Failed : msmf::exit_pseudo_state<FlowFailed> {
  using flag_list = boost::mpl::vector1<flag::EndedFailed>;
};
/// The operator cancelled: the flow ends early, nothing is uncertain.
struct Cancelled : msmf::exit_pseudo_state<LegDone> {
  using flag_list = boost::mpl::vector1<flag::EndedCancelled>;
};

/// Base of every flow and leg front: takes the context from its parent on
/// entry (a flow, a machine of its own, from itself: FlowRunOf sets it) and
/// remembers which tool it serves and at which pocket.
/// Whether a parent has a flow run's failure to share: a flow or a leg has,
/// the machine above Operating has not.
template <class T, class = void>
struct HasFailure : std::false_type {};
template <class T>
struct HasFailure<T, std::void_t<decltype(std::declval<T&>().failure)>> : std::true_type {};

template <class Derived>
struct Flow : msmf::state_machine_def<Derived> {
  Context* ctx = nullptr;
  /// Why the flow failed, once it has: the run's (FlowRunOf), which a leg
  /// writes for its flow; the flow's end carries it (FlowFailed).
  std::string* failure = nullptr;
  int tool = 0;
  int pocket = 0;  ///< the pocket the tool comes from or goes to, 0 none

  template <class Event, class Parent>
  void on_entry(const Event&, Parent& parent) {
    ctx = parent.ctx;
    if constexpr (HasFailure<Parent>::value) failure = parent.failure;
    tool = Derived::served_tool(*ctx);
    pocket = Derived::served_pocket(*ctx, tool, parent);
  }
  static int served_tool(const Context& ctx) { return ctx.request.tool; }
  template <class Parent>
  static int served_pocket(const Context& ctx, int tool, const Parent&) {
    return ctx.tools.pocket_holding(tool).value_or(0);
  }
  /// A fetch follows a return of this flow's: on the direct path that return
  /// may end at safe Z over its pocket, where the fetch starts.
  static bool fetch_follows_return(const Context&) { return false; }
  /// How far a batch got: measure all's, none for the other flows.
  BatchCount batch_count() const { return {}; }

  /// An event a flow has no row for goes on to the machine above
  /// (Engine::take), as Boost.MSM hands on a submachine's.
  template <class Fsm, class Event>
  void no_transition(const Event&, Fsm&, int) {}
};

// ---------------------------------------------------------------- kinds of state

/// A phase: a run of moves with no decision between them. On entry it walks
/// the route `Derived::route(ctx, leg)` makes in one call into plan/
/// (plan::phase), one waypoint after the other (Context::walk); its table
/// sees one InPosition, at the route's end.
/// Leaving it early (a fault, an abort) drops the rest of the route.
template <class Derived>
struct Walking : msmf::state<> {
  using flag_list = boost::mpl::vector1<flag::AwaitsMotion>;
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    fsm.ctx->walk(Derived::route(*fsm.ctx, fsm));
  }
  template <class Event, class Fsm>
  void on_exit(const Event&, Fsm& fsm) {
    fsm.ctx->stop_walking();
  }
};
/// A phase whose route comes from the config alone.
template <plan::Route (*Plan)(const Config&)>
struct Going : Walking<Going<Plan>> {
  template <class Leg>
  static plan::Route route(const Context& c, const Leg&) {
    return plan::phase(c.config, c.standing(), Plan);
  }
};
/// A phase whose route comes from the config and the pocket the leg serves.
template <plan::Route (*Plan)(const Config&, int)>
struct GoingAtPocket : Walking<GoingAtPocket<Plan>> {
  template <class Leg>
  static plan::Route route(const Context& c, const Leg& leg) {
    return plan::phase(c.config, c.standing(), Plan, leg.pocket);
  }
};

/// Publishes the command (M61, G10) `Command` makes on entry, then waits
/// for CommandDone.
template <class Command>
struct Commanding : msmf::state<> {
  using flag_list = boost::mpl::vector1<flag::AwaitsMotion>;
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    fsm.ctx->publish(Command{}(*fsm.ctx, fsm));
  }
};

/// Publishes the probe move `Target` makes on entry, then waits for
/// ProbeResult. Over MDI the operator may stop it; inside a program only
/// LinuxCNC's Stop does.
template <class Target>
struct Probing : msmf::state<> {
  using flag_list = boost::mpl::vector1<flag::AwaitsProbe>;
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    fsm.ctx->publish(Target{}(*fsm.ctx, fsm));
  }
};

/// Stands still while its timer runs; leaving it stops the timer, so no
/// TimerElapsed outlives the state that asked for it.
struct Timed : msmf::state<> {
  using flag_list = boost::mpl::vector1<flag::AwaitsTimer>;
  template <class Event, class Fsm>
  void on_exit(const Event&, Fsm& fsm) {
    fsm.ctx->ports.cancel_timer();
  }
};

/// Stands still for `Seconds` of the config, then TimerElapsed.
template <class Seconds>
struct Waiting : Timed {
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    fsm.ctx->wait(Seconds{}(fsm.ctx->config), Seconds::what);
  }
};

/// Asks the operator what `Question` makes (a Prompt); Continue or Cancel
/// follow. An operator flow ends the executor run first, so the GUI and
/// jogging are free while the operator works; inside a program (M6) nothing
/// is published, and the program holds at `loading` until the operator answers.
template <class Question>
struct AskingOperator : msmf::state<> {
  using flag_list = boost::mpl::vector1<flag::AwaitsOperator>;
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    Prompt prompt = Question{}(*fsm.ctx, fsm);
    if (fsm.ctx->request.in_program) {
      prompt.m6_tool = fsm.ctx->request.tool;
    } else {
      Step pause;
      pause.kind = StepKind::wait_operator;
      pause.label = "operator";
      fsm.ctx->publish(pause);
    }
    fsm.ctx->ask_operator(prompt);
  }
};

/// Asks the operator while the executor runs (a dry run over MDI): nothing is
/// published, so the executor keeps waiting for its next step and nothing can
/// be jogged meanwhile; Continue or Cancel follow.
template <class Question>
struct HoldingForOperator : msmf::state<> {
  using flag_list = boost::mpl::vector2<flag::AwaitsOperator, flag::HoldsProgram>;
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    fsm.ctx->ask_operator(Question{}(*fsm.ctx, fsm));
  }
};

/// A state that decides at once, through guarded anonymous rows.
struct Decision : msmf::state<> {};

// ---------------------------------------------------------------- durations

/// The chuck's dwell, where the tool settles in the pocket or the spindle.
struct ChuckSeconds {
  static constexpr const char* what = "letting the tool settle";
  double operator()(const Config& c) const { return c.chuck_seconds; }
};

// ---------------------------------------------------------------- phases and commands

/// To `loading`, Z first: where the operator reaches the spindle.
struct ToLoading : Going<plan::to_loading> {};
/// To `loading` Z, then over the touch-off sensor.
struct ToSensor : Going<plan::to_sensor> {};
struct UpToSafeZ : Going<plan::to_safe_z> {};

/// Tells LinuxCNC (M61) what the spindle holds now.
struct SpindleToolCommand {
  template <class Leg>
  Step operator()(const Context& c, const Leg&) const {
    return plan::spindle_tool(c.tools.spindle);
  }
};

/// Tells LinuxCNC (M61) what the spindle holds; `Which` tells uses apart.
template <class Which>
struct ReportingSpindleTool : Commanding<SpindleToolCommand> {};
struct AfterInsertion {};
struct AtTheEnd {};
struct AfterFetch {};
struct AfterReturn {};

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
    return fsm.ctx->tools.spindle == fsm.ctx->request.tool;
  }
};
struct SpindleHoldsOtherTool {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->tools.spindle != 0 && fsm.ctx->tools.spindle != fsm.ctx->request.tool;
  }
};
/// The spindle holds a tool that has a pocket to go back to.
struct SpindleHoldsRackTool {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->tools.spindle != 0 && fsm.ctx->return_pocket(fsm.ctx->tools.spindle);
  }
};
/// The spindle holds a manual tool: one with no pocket, handed over at `loading`.
struct SpindleHoldsManualTool {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->tools.spindle != 0 && !fsm.ctx->return_pocket(fsm.ctx->tools.spindle);
  }
};
struct RequestedRackTool {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->request.tool != 0 && fsm.ctx->tools.home_of(fsm.ctx->request.tool);
  }
};
struct RequestedManualTool {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->request.tool != 0 && !fsm.ctx->tools.home_of(fsm.ctx->request.tool);
  }
};
struct ToolRequested {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->request.tool != 0;
  }
};

// ---------------------------------------------------------------- actions

/// The tool the leg serves is in the spindle now (gripped from its pocket, or
/// inserted by the operator).
struct RecordToolInSpindle {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    fsm.ctx->record_in_spindle(fsm.tool);
  }
};
/// The operator took the tool the leg serves out of the machine.
struct RecordToolRemoved {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    fsm.ctx->record_out_of_machine(fsm.tool);
  }
};
struct CloseChuck {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    fsm.ctx->close_chuck();
  }
};

}  // namespace fatc::machine
