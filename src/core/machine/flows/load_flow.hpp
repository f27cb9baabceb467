#pragma once

// Loading a tool by hand, measuring it and putting it away.

#include "../legs/handover.hpp"
#include "../legs/probing_leg.hpp"
#include "../legs/return_leg.hpp"
#include "load.hpp"

namespace fatc::machine {

// ================================================================ load and probe
/// The operator loads a tool by hand at `loading`; it is measured on the
/// sensor (unless its rule is "never") and put away in its pocket.
/// docs/sequences.md#load-and-probe.
struct LoadFlow_ : Flow<LoadFlow_> {

  int load_pocket = 0;  ///< the pocket the loaded tool goes into (PutAway)
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    if constexpr (std::is_same_v<Event, LoadRequest>) {
      load_pocket = choose_load_pocket(*ctx, e.tool, e.pocket).pocket;
    }
  }

  struct JogPrompt {
    template <class Leg>
    Prompt operator()(const Context& c, const Leg&) const {
      Prompt jog;
      jog.kind = Prompt::Kind::jog_to_sensor;
      jog.tool = c.request.tool;
      return jog;
    }
  };
  struct AwaitingProbe : AskingOperator<JogPrompt> {};
  struct SayCancelled {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->tell(MessageKind::info, "load of tool " + std::to_string(fsm.ctx->request.tool) +
                                           " cancelled, nothing measured; " +
                                           fsm.ctx->whereabouts());
    }
  };

  /// Its rule lets nothing take it to the sensor: LinuxCNC's tool table has its length.
  struct MeasuredAtLoad {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return !fsm.ctx->measuring(fsm.ctx->request.tool).never;
    }
  };
  /// A "never" tool already in the spindle: nothing to insert or measure.
  struct PutAwayAtOnce {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event& e, Fsm& fsm, Source& source, Target& target) const {
      return RequestedToolInSpindle{}(e, fsm, source, target) &&
             !MeasuredAtLoad{}(e, fsm, source, target);
    }
  };
  /// "tool 3 measured 29.9980 mm, in pocket 3": a finished load says what it did.
  struct SayLoaded {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Context& c = *fsm.ctx;
      std::string length;
      if (c.measuring(c.request.tool).never) {
        length = " not measured (\"never\": LinuxCNC's tool table length),";
      } else if (const auto measured = fsm.template get_state<Probe&>().length) {
        length = " measured " + format_length(c.config, *measured) + ",";
      }
      fsm.ctx->tell(MessageKind::info, "tool " + std::to_string(c.request.tool) + length +
                                           " in pocket " + std::to_string(fsm.load_pocket));
    }
  };

  using Returning = ReturnLeg<Before>;
  using Inserting = InsertLeg;
  using Probe = ProbingLeg;
  using PuttingAway = ReturnLeg<PutAway>;
  using ReportingTool = ReportingSpindleTool<AfterInsertion>;
  using ReportingFinalTool = ReportingSpindleTool<AtTheEnd>;
  struct DecidingToReturn : Decision {};
  using initial_state = DecidingToReturn;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                              Event             Next                Action        Guard
  // +----------------------------------+-----------------+-------------------+-------------+-----------------------------+
  Row < DecidingToReturn                 , none            , Returning         , none        , SpindleHoldsOtherTool       >,
  Row < DecidingToReturn                 , none            , PuttingAway       , none        , PutAwayAtOnce               >,
  Row < DecidingToReturn                 , none            , ToLoading         , none        , And<Not<SpindleHoldsOtherTool>, Not<PutAwayAtOnce>> >,
  Row < Returning::exit_pt<Finished>     , LegDone         , ToLoading         , none        , none                        >,
  Row < ToLoading                        , InPosition      , Inserting         , none        , Not<RequestedToolInSpindle> >,
  Row < ToLoading                        , InPosition      , AwaitingProbe     , none        , RequestedToolInSpindle      >,
  Row < Inserting::exit_pt<Finished>     , LegDone         , ReportingTool     , none        , none                        >,
  Row < Inserting::exit_pt<Cancelled>    , LegDone         , ReportingFinalTool, SayCancelled, none                        >,
  Row < ReportingTool                    , CommandDone     , AwaitingProbe     , none        , MeasuredAtLoad              >,
  Row < ReportingTool                    , CommandDone     , PuttingAway       , none        , Not<MeasuredAtLoad>         >,
  Row < AwaitingProbe                    , OperatorContinue, Probe             , none        , none                        >,
  Row < AwaitingProbe                    , OperatorCancel  , ReportingFinalTool, SayCancelled, none                        >,
  Row < Probe::exit_pt<Finished>         , LegDone         , PuttingAway       , none        , none                        >,
  Row < Probe::exit_pt<Probe::NotMeasured>, LegDone        , ReportingFinalTool, none        , none                        >,
  Row < PuttingAway::exit_pt<Finished>   , LegDone         , ReportingFinalTool, SayLoaded   , none                        >,
  Row < ReportingFinalTool               , CommandDone     , Finished          , none        , none                        >
  >;
  // clang-format on
};

}  // namespace fatc::machine
