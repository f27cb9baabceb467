#pragma once

// The machine on and homed: idle, or running one flow; the requests and
// their refusals.

#include "answers.hpp"
#include "base/admission.hpp"
#include "base/chuck.hpp"
#include "base/flow_run.hpp"
#include "flows/flows.hpp"

namespace fatc::machine {

// ================================================================ requests and refusals
/// Why a copy of the changer would not take `request` (a move of its sequence
/// breaks the keep-out or the soft limits), or nothing; changer.cpp, where
/// the Changer is whole.
std::optional<std::string> rehearse(const Context& c, const FlowRequest& request);
/// Why a request cannot be taken now, or nothing if it can. A request the
/// changer could take by its flow's own rule (why_not) is rehearsed last:
/// its whole sequence is checked with the tools it carries before anything moves.
template <class Request>
std::optional<std::string> why_not(const Context& c, const Request& e) {
  using Flow = kind_of<Request>;
  if (auto why = Flow::why_not(c, e)) return why;
  if constexpr (Flow::rehearsed) return rehearse(c, e);
  return std::nullopt;
}
inline std::optional<std::string> why_not(const Context& c, const ConfigChanged&) {
  return why_not_reconfigure(c, true, false);
}

/// Refuses a request, saying why `Because` gives. The executor of an M6 or a
/// chuck atom waits for a step: it gets one that fails its program with the
/// same words.
template <class Because>
struct Refuse {
  template <class Request, class Fsm, class Source, class Target>
  void operator()(const Request& e, Fsm& fsm, Source&, Target&) const {
    const std::string text = request_name(e) + " refused: " + Because{}(fsm, e);
    if constexpr (!std::is_same_v<Request, ConfigChanged>) {
      if constexpr (kind_of<Request>::in_program) {
        Step fail = failure_step(text);
        // M6's executor names the tool it was asked for.
        if constexpr (std::is_same_v<Request, ToolChange>) fail.tool = e.tool;
        // Straight to the executor: the flow running (if any) goes on as it was.
        fsm.ctx->ports.publish(fail);
      }
    }
    fsm.ctx->tell(MessageKind::error, text);
  }
};
struct BecauseNotPossible {
  template <class Fsm, class Request>
  std::string operator()(Fsm& fsm, const Request& e) const {
    return *why_not(*fsm.ctx, e);
  }
};
struct BecauseNotReady {
  template <class Fsm, class Request>
  std::string operator()(Fsm&, const Request&) const {
    return "the machine is not on and homed, or is in estop";
  }
};
struct BecauseFaulted {
  template <class Fsm, class Request>
  std::string operator()(Fsm& fsm, const Request&) const {
    return "the changer is in fault (" + fsm.ctx->activity.fault_reason + "); clear it first";
  }
};
struct BecauseBusy {
  template <class Fsm, class Request>
  std::string operator()(Fsm& fsm, const Request&) const {
    std::string words = "the changer is busy";
    Flows::any([&](auto flow) {
      using Flow = decltype(flow);
      if (!fsm.template is_flag_active<Flow>()) return false;
      words = Flow::busy(*fsm.ctx);
      return true;
    });
    return words;
  }
};
/// A taught config is refused in the same words wherever the changer is not
/// plainly idle (Changer::why_not_teach asks the same before anything is read).
struct BecauseNotIdle {
  template <class Fsm>
  std::string operator()(Fsm& fsm, const ConfigChanged&) const {
    return why_not_reconfigure(*fsm.ctx, fsm.template is_flag_active<flag::Idle>(),
                               fsm.template is_flag_active<flag::AwaitsSensor>())
        .value_or("only while the changer is idle");
  }
};
/// The requests, refused for one reason (a taught config: for not being idle):
/// a state's internal rows. With `Guard`, a request is refused only where it
/// holds (a taught config always).
template <class Because, class Guard = none, class List = Flows>
struct RefusingRequests;
template <class Because, class Guard, class... Each>
struct RefusingRequests<Because, Guard, FlowList<Each...>> {
  using type = boost::mpl::vector<msmf::Internal<typename Each::request, Refuse<Because>, Guard>...,
                                  msmf::Internal<ConfigChanged, Refuse<BecauseNotIdle>, none>>;
};
template <class Because, class Guard = none>
using RefusesRequests = typename RefusingRequests<Because, Guard>::type;

/// Tables joined into one, in order.
template <class... Tables>
struct Joined;
template <class Table>
struct Joined<Table> {
  using type = Table;
};
template <class Table, class... Rest>
struct Joined<Table, Rest...> {
  using type = boost::mpl::joint_view<Table, typename Joined<Rest...>::type>;
};
template <class... Tables>
using joined = typename Joined<Tables...>::type;
/// `Row` where `present`, else nothing: a row a flow may declare.
template <bool present, class Row>
using row_if = std::conditional_t<present, boost::mpl::vector1<Row>, boost::mpl::vector0<>>;
/// The rows `Rows<Flow>` of every flow, in order.
template <template <class> class Rows, class List = Flows>
struct ForEachFlow;
template <template <class> class Rows, class... Each>
struct ForEachFlow<Rows, FlowList<Each...>> {
  using type = joined<Rows<Each>...>;
};

// ================================================================ operating
/// The machine on and homed: idle, or running one flow.
struct BecauseSensorsDisagree {
  template <class Fsm, class Request>
  std::string operator()(Fsm& fsm, const Request&) const {
    std::string words = "the sensors disagree with the saved tool state";
    for (const auto& disagreement : fsm.ctx->disagreements()) words += "; " + disagreement;
    return words;
  }
};

/// A flow running as a machine of its own (flow_run.hpp), started on entry
/// with the request that asked for it and stopped on exit; it carries the
/// flags Busy and the flow's own kind (Change, ...). Only the flow's own file
/// reads its table.
template <class Kind>
struct Running : msmf::state<> {
  using flow_front = typename Kind::front;
  using flag_list = boost::mpl::vector2<flag::Busy, Kind>;
  template <class Event, class Fsm>
  void on_entry(const Event& e, Fsm& fsm) {
    // Boost.MSM builds an entry for each event that enters Operating; only
    // the request enters this state.
    if constexpr (std::is_same_v<Event, typename Kind::request>) {
      fsm.flow = Kind::run(*fsm.ctx, e);
    }
  }
  template <class Event, class Fsm>
  void on_exit(const Event&, Fsm& fsm) {
    // Nothing stays held for Continue: a fault's close of the chuck goes at once.
    fsm.ctx->steps.end();
    fsm.flow->stop();
    fsm.flow.reset();
  }
};

struct Operating_ : Flow<Operating_> {
  /// The flow running, if any (Running<Flow>).
  std::unique_ptr<FlowRun> flow;

  struct Idle : msmf::state<> {
    using flag_list = boost::mpl::vector1<flag::Idle>;
  };
  /// The changer is done with the rack: its cover (if any) closes, and its
  /// closed sensor (if wired) has its own timeout to say so.
  struct SensorOrCoverTimeout {
    double operator()(const Config& c) const {
      return c.rack_cover && Sensors(c.sensors).senses_cover_closed()
                 ? std::max(c.sensor_timeout_seconds, c.rack_cover->timeout_seconds)
                 : c.sensor_timeout_seconds;
    }
  };
  /// The cover this state commanded closed is still on its way, and nothing
  /// else disagrees: a request waits for it (the top machine defers it).
  struct CoverStillClosing {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.ctx->cover_still_closing();
    }
  };
  /// Before the changer takes work (at start, after a fault, after every
  /// flow, and whenever a sensor changes while idle) the wired sensors must
  /// agree with the tool state, or come to within sensor_timeout_seconds.
  /// A request meanwhile is refused, unless it only waits for the cover to close.
  struct ComparingSensors : AwaitingSensor<SensorsAgree, SensorOrCoverTimeout> {
    using flag_list = boost::mpl::vector2<flag::Idle, flag::AwaitsSensor>;
    using internal_transition_table =
        RefusesRequests<BecauseSensorsDisagree, Not<CoverStillClosing>>;
    template <class Event, class Fsm>
    void on_entry(const Event& e, Fsm& fsm) {
      fsm.ctx->close_cover();
      AwaitingSensor::on_entry(e, fsm);
    }
    template <class Event, class Fsm>
    void on_exit(const Event& e, Fsm& fsm) {
      fsm.ctx->outputs.cover_closing = false;
      AwaitingSensor::on_exit(e, fsm);
    }
  };
  struct SaySensorsDisagree {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event& e, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->activity.fault_reason = BecauseSensorsDisagree{}(fsm, e);
    }
  };

  struct Refused {
    template <class Request, class Fsm, class Source, class Target>
    bool operator()(const Request& e, Fsm& fsm, Source&, Target&) const {
      return why_not(*fsm.ctx, e).has_value();
    }
  };
  struct TakeRequest {
    template <class Request, class Fsm, class Source, class Target>
    void operator()(const Request& e, Fsm& fsm, Source&, Target&) const {
      // What the flow itself needs of the request it takes on entry.
      using Flow = kind_of<Request>;
      Context& c = *fsm.ctx;
      c.request.in_program = Flow::in_program;
      c.request.tool = Flow::tool(c, e);
      c.begin_sequence(request_name(e));
    }
  };
  /// The changer works with the taught config from the next request on.
  struct TakeConfig {
    template <class Fsm, class Source, class Target>
    void operator()(const ConfigChanged& e, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->take_config(e.config);
    }
  };

  using initial_state = ComparingSensors;
  // clang-format off
  /// A flow's request while idle: refused with a reason, answered at once
  /// where the flow says so (M6 of the tool in the spindle), or its flow started.
  template <class Flow, class Request = typename Flow::request, class AtOnce = typename Flow::answered_at_once>
  struct RequestRows { using type = boost::mpl::vector<
  //    Start  Event     Next           Action                      Guard
  // +------+---------+--------------+---------------------------+----------------------------------+
  Row < Idle , Request , none          , Refuse<BecauseNotPossible>, Refused                          >,
  Row < Idle , Request , none          , AnswerDone                , And<Not<Refused>, AtOnce>        >,
  Row < Idle , Request , Running<Flow> , TakeRequest               , And<Not<Refused>, Not<AtOnce>>   >
  >; };
  template <class Flow, class Request>
  struct RequestRows<Flow, Request, NoRow> { using type = boost::mpl::vector<
  Row < Idle , Request , none          , Refuse<BecauseNotPossible>, Refused                          >,
  Row < Idle , Request , Running<Flow> , TakeRequest               , Not<Refused>                     >
  >; };
  template <class Flow>
  using request_rows = typename RequestRows<Flow>::type;
  /// Where a flow ends (its declaration, flows/NAME.hpp, says which of these it has).
  template <class Flow, class Ending = Running<Flow>>
  using end_rows_of = joined<
  boost::mpl::vector1<
  Row < Ending  , FlowFinished , ComparingSensors , typename Flow::when_finished , none >>,
  row_if<Flow::may_fail,
  Row < Ending  , FlowFailed   , Failed           , none                         , none >>,
  row_if<!std::is_same_v<typename Flow::when_cancelled, NoRow>,
  Row < Ending  , FlowCancelled, ComparingSensors , typename Flow::when_cancelled, none >>,
  row_if<!std::is_same_v<typename Flow::when_aborted, NoRow>,
  Row < Ending  , Abort        , ComparingSensors , typename Flow::when_aborted  , none >>>;
  template <class Flow>
  using end_rows = end_rows_of<Flow>;
  /// A taught config while idle.
  using config_rows = boost::mpl::vector<
  Row < Idle , ConfigChanged , none , Refuse<BecauseNotPossible>, Refused      >,
  Row < Idle , ConfigChanged , none , TakeConfig                , Not<Refused> >
  >;
  /// Comparing the sensors before work.
  using comparing_sensors = boost::mpl::vector<
  //    Start              Event          Next              Action              Guard
  // +------------------+--------------+-----------------+-------------------+-------------------+
  Row < ComparingSensors , SensorReport , Idle            , none              , SensorsAgree      >,
  Row < ComparingSensors , TimerElapsed , Failed          , SaySensorsDisagree, none              >,
  Row < Idle             , SensorReport , ComparingSensors, none              , Not<SensorsAgree> >
  >;
  using transition_table = joined<typename ForEachFlow<request_rows>::type, config_rows,
                                  comparing_sensors, typename ForEachFlow<end_rows>::type>;
  // clang-format on
};
using Operating = Machine_of<Operating_>;

}  // namespace fatc::machine
