#pragma once

// Fetching a tool from its pocket. docs/sequences.md#retrieve.

#include <boost/mpl/vector/vector30.hpp>

#include "cover.hpp"
#include "flush_leg.hpp"
#include "screwing_on.hpp"

namespace fatc::machine {

// ================================================================ retrieve
/// Takes the requested tool out of its pocket (docs/sequences.md#retrieve).
/// The tool must show in the spindle once the chuck closed on it; if not, it
/// is gripped once more where it is (the chuck opens and closes again), and
/// seen neither time, the changer faults.
struct RetrieveLeg_ : Flow<RetrieveLeg_> {
  int retries = 0;  ///< grips tried again
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    retries = 0;
    ctx->record_progress(
        "fetching tool " + std::to_string(tool) + " from pocket " + std::to_string(pocket), pocket);
  }
  // The phases; plan/routes.hpp says where each goes.
  /// Over the pocket to above-chuck; straight over it from safe, or, on the
  /// direct path, from anywhere at safe Z (where a direct return ends):
  /// Context::walk leaves out the way to where the spindle already stands.
  struct ToAboveChuck : GoingAtPocket<plan::fetch_to_above_chuck> {};
  struct WaitingToOpen : WaitingToOpenChuck<AbovePocket> {};
  struct OpeningChuck : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      const std::string p = std::to_string(fsm.pocket);
      fsm.ctx->open_chuck();
      fsm.ctx->wait(fsm.ctx->config.chuck_seconds,
                    fsm.retries == 0 ? "opening the chuck above pocket " + p
                                     : "opening the chuck again at pocket " + p + " to grip tool " +
                                           std::to_string(fsm.tool) + " once more");
    }
  };
  struct DownAroundTool : GoingAtPocket<plan::fetch_down_to_tool> {};
  struct Settling : Waiting<ChuckSeconds> {};
  struct GrippingTool : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      fsm.ctx->close_chuck();
      fsm.ctx->wait(fsm.ctx->config.chuck_seconds, "gripping tool " + std::to_string(fsm.tool));
    }
  };
  /// The drawbar reads closed and the spindle's sensor sees the tool.
  struct Gripped : SensorGuard<Gripped> {
    template <class Leg>
    static bool holds(const Context& c, const Leg&) {
      return c.sensors.drawbar_reads_closed() && c.sensors.spindle_reads(true);
    }
    static std::string awaited(const Context&) {
      return "waiting for the drawbar to report closed and " + Sensors::tool_pin() +
             " to see the tool";
    }
  };
  struct CheckingGrip : AwaitingSensor<Gripped> {};
  struct OutAndAway : GoingAtPocket<plan::fetch_out_and_away> {};

  /// The grip was tried once more already.
  struct Retried {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.retries > 0;
    }
  };
  struct CannotFetch {
    template <class Leg>
    static std::string text(const Context& c, const Leg& leg) {
      const std::string t = std::to_string(leg.tool);
      if (!c.sensors.pocket_reads(leg.pocket, true)) {
        return "pocket " + std::to_string(leg.pocket) + " reads empty (" + pocket_pin(leg.pocket) +
               " off): tool " + t + " cannot be fetched";
      }
      return "the spindle is not empty (" + Sensors::tool_pin() + " on): tool " + t +
             " cannot be fetched";
    }
  };
  using FaultCannotFetch = FaultSaying<CannotFetch, false>;
  struct SayGrippingAgain {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      ++fsm.retries;
      fsm.ctx->tell(MessageKind::info, "tool " + std::to_string(fsm.tool) +
                                           " not in the spindle after the chuck closed at pocket " +
                                           std::to_string(fsm.pocket) + " (" + Sensors::tool_pin() +
                                           " off); gripping it once more");
    }
  };
  struct NotGripped {
    template <class Leg>
    static std::string text(const Context&, const Leg& leg) {
      return "tool " + std::to_string(leg.tool) +
             " not in the spindle after the chuck closed at pocket " + std::to_string(leg.pocket) +
             " (" + Sensors::tool_pin() + " off, retried once)";
    }
  };
  using FaultToolNotGripped = FaultSaying<NotGripped, true>;
  /// Where the chuck opens: above the pocket, or at it when gripping again.
  struct WhereItOpens {
    template <class Leg>
    static std::string where(const Leg& leg) {
      return leg.retries == 0 ? AbovePocket::where(leg) : AtPocket::where(leg);
    }
  };

  /// A collet-nut changer screws the nut on instead (`chuck.kind`).
  struct Starting : Decision {};
  using initial_state = Starting;
  // 22 rows, more than boost::mpl::vector takes, hence vector22.
  // clang-format off
  using transition_table = boost::mpl::vector22<
  //    Start                        Event          Next                 Action                                  Guard
  // +----------------------------+--------------+--------------------+---------------------------------------+----------------------------------+
  Row < Starting                   , none         , Halted             , FaultCannotFetch                      , Not<ReadyToFetch>                >,
  Row < Starting                   , none         , OpeningCover       , none                                  , And<ReadyToFetch, Not<ScrewsNuts>> >,
  Row < Starting                   , none         , ScrewingOn         , none                                  , And<ReadyToFetch, ScrewsNuts>    >,
  Row < ScrewingOn::exit_pt<Finished>, LegDone    , Finished           , none                                  , none                             >,
  Row < OpeningCover               , SensorReport , ToAboveChuck       , none                                  , CoverOpen                        >,
  Row < OpeningCover               , TimerElapsed , Halted             , FaultCoverDidNotOpen                  , CoverHasOpenedSensor             >,
  Row < ToAboveChuck               , InPosition   , FlushLeg           , none                                  , none                             >,
  Row < FlushLeg::exit_pt<Finished>, LegDone      , WaitingToOpen      , none                                  , none                             >,
  Row < WaitingToOpen              , SensorReport , OpeningChuck       , none                                  , ChuckMayOpen                     >,
  Row < WaitingToOpen              , TimerElapsed , Halted             , FaultChuckMayNotOpen<WhereItOpens>    , none                             >,
  Row < OpeningChuck               , TimerElapsed , CheckingDrawbarOpen, none                                  , none                             >,
  Row < CheckingDrawbarOpen        , SensorReport , DownAroundTool     , none                                  , And<DrawbarOpen, Not<Retried>>   >,
  Row < CheckingDrawbarOpen        , SensorReport , GrippingTool       , none                                  , And<DrawbarOpen, Retried>        >,
  Row < CheckingDrawbarOpen        , TimerElapsed , Halted             , FaultDrawbarStayedClosed<WhereItOpens>, none                             >,
  Row < DownAroundTool             , InPosition   , Settling           , none                                  , none                             >,
  Row < Settling                   , TimerElapsed , GrippingTool       , none                                  , none                             >,
  Row < GrippingTool               , TimerElapsed , CheckingGrip       , none                                  , none                             >,
  Row < CheckingGrip               , SensorReport , OutAndAway         , RecordToolInSpindle                   , Gripped                          >,
  Row < CheckingGrip               , TimerElapsed , Halted             , FaultDrawbarStayedOpen<AtPocket>      , Not<DrawbarClosed>               >,
  Row < CheckingGrip               , TimerElapsed , WaitingToOpen      , SayGrippingAgain                      , And<DrawbarClosed, Not<Retried>> >,
  Row < CheckingGrip               , TimerElapsed , Halted             , FaultToolNotGripped                   , And<DrawbarClosed, Retried>      >,
  Row < OutAndAway                 , InPosition   , Finished           , none                                  , none                             >
  >;
  // clang-format on
};
using RetrieveLeg = Machine_of<RetrieveLeg_>;

}  // namespace fatc::machine
