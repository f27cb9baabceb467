#pragma once

// Every flow the changer runs, declared once: the request that starts it, the
// phase the `state` pin shows, the words of its refusals, and how Operating
// answers its end. Operating's rows, the refusals of the other states, the
// status and the run of each flow are derived from this list; a flow's table
// is in its own header and its words and run in its own .cpp.

#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <type_traits>

#include "common.hpp"
#include "status.hpp"

namespace fatc::machine {

// ================================================================ how an end is answered

/// The executor's last step: done, with the tool in the spindle.
inline void publish_done(Context& c) {
  Step done;
  done.kind = StepKind::done;
  done.tool = c.tools.spindle;
  done.label = "done";
  c.publish(done);
}
struct AnswerDone {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    fsm.ctx->end_sequence();
    publish_done(*fsm.ctx);
  }
};
/// A chuck atom is done. A release leaves its sequence recorded until the
/// clamp: a restart or the machine going off meanwhile leaves what the
/// spindle holds for the operator to confirm.
struct AnswerChuckDone {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    Context& c = *fsm.ctx;
    if (c.outputs.chuck_open) {
      c.record_progress(kChuckHeldOpen, 0);
    } else {
      c.end_sequence();
    }
    publish_done(c);
  }
};
/// The operator cancelled an M6: the executor stops the program, saying where
/// the tools are; nothing is uncertain.
struct StopProgram {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    Context& c = *fsm.ctx;
    c.end_sequence();
    const std::string why =
        "M6 T" + std::to_string(c.request.tool) + " cancelled by the operator; " + c.whereabouts();
    Step fail = failure_step(why);
    fail.tool = c.tools.spindle;
    c.publish(fail);
    c.tell(MessageKind::error, why);
  }
};
/// A dry run cut off by an abort or the machine going off: nothing to
/// record, no fault; but the spindle stopped somewhere along the approach.
struct StopDryRun {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event& e, Fsm& fsm, Source&, Target&) const {
    Context& c = *fsm.ctx;
    std::string why = "the machine went off, lost homing or entered estop";
    if constexpr (std::is_same_v<Event, Abort>) why = e.reason;
    const int pocket = c.sequence_pocket();
    c.end_sequence();
    c.tell(MessageKind::info, "verify of pocket " + std::to_string(pocket) + " stopped (" + why +
                                  "); nothing was recorded. The spindle may be in the rack: jog "
                                  "it out the way it came in before the next change");
  }
};
/// The request asks for the tool the spindle already holds: answered done at once.
struct AlreadyInSpindle {
  template <class Fsm, class Source, class Target>
  bool operator()(const ToolChange& e, Fsm& fsm, Source&, Target&) const {
    return e.tool == fsm.ctx->tools.spindle;
  }
};

// ================================================================ the flows

/// No row: a flow that declares none of this end.
struct NoRow {};

/// What a flow declares only where it differs. `tool` is the tool the
/// request is about (Context::requested_tool while the flow runs).
struct FlowKind {
  /// Runs inside a G-code program (M6, a chuck atom): the operator's answers
  /// hold the program, and a refusal fails it.
  static constexpr bool in_program = false;
  /// A guard under which the request is answered done without a flow.
  using answered_at_once = NoRow;
  using when_finished = AnswerDone;
  /// The flow's Failed end: the changer faults.
  static constexpr bool may_fail = false;
  using when_cancelled = NoRow;
  /// LinuxCNC's abort while the flow runs; NoRow: the changer faults.
  using when_aborted = NoRow;
  template <class Request>
  static int tool(const Context&, const Request& e) {
    return e.tool;
  }
};

struct ChangeFlow_;
struct LoadFlow_;
struct UnloadFlow_;
struct MeasureAllFlow_;
struct VerifyFlow_;
struct ChuckFlow_;

/// M6 (change_flow.hpp).
struct Change : FlowKind {
  using request = ToolChange;
  using front = ChangeFlow_;
  static constexpr Phase phase = Phase::changing;
  static constexpr const char* word = "changing";
  static constexpr bool in_program = true;
  using answered_at_once = AlreadyInSpindle;
  static constexpr bool may_fail = true;
  using when_cancelled = StopProgram;
  static std::string name(const ToolChange& e);
  static std::optional<std::string> why_not(const Context& c, const ToolChange& e);
  static std::string busy(const Context& c);
  static std::unique_ptr<FlowRun> run(Context& c, const ToolChange& e);
};
/// Load and probe (load_flow.hpp).
struct Load : FlowKind {
  using request = LoadRequest;
  using front = LoadFlow_;
  static constexpr Phase phase = Phase::loading;
  static constexpr const char* word = "loading";
  static std::string name(const LoadRequest& e);
  static std::optional<std::string> why_not(const Context& c, const LoadRequest& e);
  static std::string busy(const Context& c);
  static std::unique_ptr<FlowRun> run(Context& c, const LoadRequest& e);
};
/// Unload (unload_flow.hpp).
struct Unload : FlowKind {
  using request = UnloadRequest;
  using front = UnloadFlow_;
  static constexpr Phase phase = Phase::unloading;
  static constexpr const char* word = "unloading";
  static std::string name(const UnloadRequest& e);
  static std::optional<std::string> why_not(const Context& c, const UnloadRequest& e);
  static std::string busy(const Context& c);
  static std::unique_ptr<FlowRun> run(Context& c, const UnloadRequest& e);
};
/// Measure all (measure_all_flow.hpp): the flow picks each tool in turn.
struct MeasureAll : FlowKind {
  using request = MeasureRequest;
  using front = MeasureAllFlow_;
  static constexpr Phase phase = Phase::measuring;
  static constexpr const char* word = "measuring";
  static int tool(const Context& c, const MeasureRequest&);
  static std::string name(const MeasureRequest& e);
  static std::optional<std::string> why_not(const Context& c, const MeasureRequest& e);
  static std::string busy(const Context& c);
  static std::unique_ptr<FlowRun> run(Context& c, const MeasureRequest& e);
};
/// Verify a pocket (verify_flow.hpp): a dry run, so an abort is no fault.
struct Verify : FlowKind {
  using request = VerifyRequest;
  using front = VerifyFlow_;
  static constexpr Phase phase = Phase::verifying;
  static constexpr const char* word = "verifying";
  using when_cancelled = AnswerDone;
  using when_aborted = StopDryRun;
  static int tool(const Context& c, const VerifyRequest&);
  static std::string name(const VerifyRequest& e);
  static std::optional<std::string> why_not(const Context& c, const VerifyRequest& e);
  static std::string busy(const Context& c);
  static std::unique_ptr<FlowRun> run(Context& c, const VerifyRequest& e);
};
/// A chuck atom from G-code (chuck_flow.hpp).
struct ChuckAtom : FlowKind {
  using request = ChuckRequest;
  using front = ChuckFlow_;
  static constexpr Phase phase = Phase::chuck;
  static constexpr const char* word = "chuck";
  static constexpr bool in_program = true;
  using when_finished = AnswerChuckDone;
  static int tool(const Context& c, const ChuckRequest&);
  static std::string name(const ChuckRequest& e);
  static std::optional<std::string> why_not(const Context& c, const ChuckRequest& e);
  static std::string busy(const Context& c);
  static std::unique_ptr<FlowRun> run(Context& c, const ChuckRequest& e);
};

template <class... Kinds>
struct FlowList {
  /// Calls `f(Kind{})` for each, in order, until one returns true.
  template <class F>
  static bool any(F&& f) {
    return (f(Kinds{}) || ...);
  }
};
/// Every flow, in the order Operating lists them.
using Flows = FlowList<Change, Load, Unload, MeasureAll, Verify, ChuckAtom>;

/// The flow `Request` starts.
template <class Request, class List = Flows>
struct KindOf;
template <class Request, class... Kinds>
struct KindOf<Request, FlowList<Kinds...>> {
  static constexpr bool found[] = {std::is_same_v<Request, typename Kinds::request>...};
  static constexpr std::size_t index() {
    std::size_t i = 0;
    while (!found[i]) ++i;
    return i;
  }
  using type = std::tuple_element_t<index(), std::tuple<Kinds...>>;
};
template <class Request>
using kind_of = typename KindOf<Request>::type;

/// "M6 T3", "load of tool 3 into pocket 2": a request in a message.
template <class Request>
std::string request_name(const Request& e) {
  return kind_of<Request>::name(e);
}
inline std::string request_name(const ConfigChanged& e) { return e.request; }

}  // namespace fatc::machine
