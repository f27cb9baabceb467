#pragma once

// Unloading a tool: fetched, then taken out by the operator.

#include "../legs/handover.hpp"
#include "../legs/retrieve_leg.hpp"
#include "../legs/return_leg.hpp"

namespace fatc::machine {

// ================================================================ unload
/// The requested tool is fetched (if not in the spindle already) and taken
/// out by the operator at `loading`. docs/sequences.md#unload.
struct UnloadFlow_ : Flow<UnloadFlow_> {
  static bool fetch_follows_return(const Context&) { return true; }

  struct SayCancelled {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->tell(MessageKind::info, "unload of tool " + std::to_string(fsm.ctx->request.tool) +
                                           " cancelled; " + fsm.ctx->whereabouts());
    }
  };
  struct SpindleEmpty {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.ctx->tools.spindle == 0;
    }
  };

  using Returning = ReturnLeg<Before>;
  using Removing = RemoveLeg;
  using ReportingTool = ReportingSpindleTool<AfterInsertion>;
  using ReportingFinalTool = ReportingSpindleTool<AtTheEnd>;
  struct DecidingWhereToStart : Decision {};
  using initial_state = DecidingWhereToStart;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                            Event         Next                Action        Guard
  // +--------------------------------+-------------+-------------------+-------------+------------------------+
  Row < DecidingWhereToStart           , none        , ToLoading         , none        , RequestedToolInSpindle >,
  Row < DecidingWhereToStart           , none        , Returning         , none        , SpindleHoldsOtherTool  >,
  Row < DecidingWhereToStart           , none        , RetrieveLeg       , none        , SpindleEmpty           >,
  Row < Returning::exit_pt<Finished>   , LegDone     , RetrieveLeg       , none        , none                   >,
  Row < RetrieveLeg::exit_pt<Finished> , LegDone     , ToLoading         , none        , none                   >,
  Row < ToLoading                      , InPosition  , ReportingTool     , none        , none                   >,
  Row < ReportingTool                  , CommandDone , Removing          , none        , none                   >,
  Row < Removing::exit_pt<Finished>    , LegDone     , FlushLeg          , none        , none                   >,
  Row < Removing::exit_pt<Cancelled>   , LegDone     , ReportingFinalTool, SayCancelled, none                   >,
  Row < FlushLeg::exit_pt<Finished>    , LegDone     , ReportingFinalTool, none        , none                   >,
  Row < ReportingFinalTool             , CommandDone , Finished          , none        , none                   >
  >;
  // clang-format on
};

}  // namespace fatc::machine
