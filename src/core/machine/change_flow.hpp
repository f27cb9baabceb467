#pragma once

// M6: the change flow.

#include "handover.hpp"
#include "probing_leg.hpp"
#include "retrieve_leg.hpp"
#include "return_leg.hpp"
#include "spindle_run_down.hpp"

namespace fatc::machine {

// ================================================================ change (M6)
/// M6: empty the spindle (its tool back to its pocket, or handed out), then
/// fetch the requested tool (from its pocket, or handed in), then measure it
/// if `probe_after_change` asks. docs/sequences.md#m6.
struct ChangeFlow_ : Flow<ChangeFlow_> {
  /// The requested tool is in the rack: a fetch follows the return.
  static bool fetch_follows_return(const Context& c) {
    return c.tools.pocket_holding(c.requested_tool).has_value();
  }

  struct ProbesAfterChange {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.ctx->config.probe_after_change != ProbeAfterChange::off;
    }
  };

  using Returning = ReturnLeg<Before>;
  struct DecidingHowToEmpty : Decision {};
  /// The spindle is empty: how does the requested tool get into it?
  struct DecidingHowToFetch : Decision {};
  struct DecidingToMeasure : Decision {};
  using initial_state = SpindleRunDown;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                               Event        Next                 Action   Guard
  // +-----------------------------------+------------+--------------------+--------+------------------------+
  Row < SpindleRunDown::exit_pt<Finished> , LegDone    , DecidingHowToEmpty , none   , none                   >,
  Row < SpindleRunDown::exit_pt<Failed>   , FlowFailed , Failed             , none   , none                   >,
  Row < DecidingHowToEmpty                , none       , Returning          , none   , SpindleHoldsRackTool   >,
  Row < DecidingHowToEmpty                , none       , HandOutLeg         , none   , SpindleHoldsManualTool >,
  Row < DecidingHowToEmpty                , none       , DecidingHowToFetch , none   , Not<SpindleHoldsTool>  >,
  Row < Returning::exit_pt<Finished>      , LegDone    , DecidingHowToFetch , none   , none                   >,
  Row < HandOutLeg::exit_pt<Finished>     , LegDone    , DecidingHowToFetch , none   , none                   >,
  Row < HandOutLeg::exit_pt<Cancelled>    , LegDone    , Cancelled          , none   , none                   >,
  Row < DecidingHowToFetch                , none       , RetrieveLeg        , none   , RequestedRackTool      >,
  Row < DecidingHowToFetch                , none       , HandInLeg          , none   , RequestedManualTool    >,
  Row < DecidingHowToFetch                , none       , Finished           , none   , Not<ToolRequested>     >,
  Row < RetrieveLeg::exit_pt<Finished>    , LegDone    , DecidingToMeasure  , none   , none                   >,
  Row < HandInLeg::exit_pt<Finished>      , LegDone    , DecidingToMeasure  , none   , none                   >,
  Row < HandInLeg::exit_pt<Cancelled>     , LegDone    , Cancelled          , none   , none                   >,
  Row < DecidingToMeasure                 , none       , MeasureLeg         , none   , ProbesAfterChange      >,
  Row < DecidingToMeasure                 , none       , Finished           , none   , Not<ProbesAfterChange> >,
  Row < MeasureLeg::exit_pt<Finished>     , LegDone    , Finished           , none   , none                   >,
  Row < MeasureLeg::exit_pt<Failed>       , FlowFailed , Failed             , none   , none                   >
  >;
  // clang-format on
};

}  // namespace fatc::machine
