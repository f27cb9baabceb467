#pragma once

// Measuring every tool of the rack, one after another.

#include "../legs/probing_leg.hpp"
#include "../legs/retrieve_leg.hpp"
#include "../legs/return_leg.hpp"
#include "measure_all.hpp"

namespace fatc::machine {

// ================================================================ measure all
/// Measure all: each tool fetched from its pocket, measured on the sensor and
/// put back, one after another, with a report of each length and its change.
/// Cancel stops the batch once the tool under way is back in its pocket (a
/// probe under way stops too). The legs are the load's and M6's own types, so
/// the machine grows by one table, not by new copies of the legs.
/// docs/sequences.md#measure-all.
struct MeasureAllFlow_ : Flow<MeasureAllFlow_> {
  /// The tools to measure, in order, and how far the batch got.
  struct Batch {
    std::vector<int> tools;
    std::size_t done = 0;          ///< tools measured or tried
    bool cancel = false;           ///< stop once the tool under way is back in its pocket
    std::optional<double> stored;  ///< the length of the tool under way before it was measured
    std::vector<std::string> report;
  } batch;
  BatchCount batch_count() const {
    return {static_cast<int>(batch.done), static_cast<int>(batch.tools.size())};
  }
  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    if constexpr (std::is_same_v<Event, MeasureRequest>) {
      std::string skipped;
      std::string never;
      batch = {measurable_tools(*ctx, e.tools, skipped, never), 0, false, {}, {}};
      if (!skipped.empty()) {
        ctx->tell(MessageKind::info, "measure all skips what is not in the rack: " + skipped);
      }
      if (!never.empty()) {
        ctx->tell(MessageKind::info, "measure all skips what is never measured (\"never\": "
                                     "LinuxCNC's tool table length): " + never);
      }
    }
  }

  using Returning = ReturnLeg<Before>;
  using Probe = ProbingLeg;
  /// The spindle's tool goes back first; then the next tool, if any is left.
  struct DecidingNextTool : Decision {};
  /// LinuxCNC is told (M61) what the spindle holds after each fetch and return.
  using ReportingFetched = ReportingSpindleTool<AfterFetch>;
  using ReportingReturned = ReportingSpindleTool<AfterReturn>;

  struct ToolsLeft {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      const Batch& b = fsm.batch;
      return !b.cancel && b.done < b.tools.size();
    }
  };
  struct TakeNextTool {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      const int tool = fsm.batch.tools[fsm.batch.done];
      c.request.tool = tool;
      const auto stored = c.tools.lengths.find(tool);
      fsm.batch.stored =
          stored == c.tools.lengths.end() ? std::nullopt : std::optional<double>(stored->second);
      c.tell(MessageKind::info, "measure all: tool " + std::to_string(tool) + " (" +
                                    std::to_string(fsm.batch.done + 1) + " of " +
                                    std::to_string(fsm.batch.tools.size()) + ")");
    }
  };
  struct RecordMeasured {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      const double now = *fsm.template get_state<Probe&>().length;
      std::string line = "T" + std::to_string(c.request.tool) + " " + format_length(c.config, now);
      if (fsm.batch.stored) {
        char change[32];
        std::snprintf(change, sizeof change, "%+.4f", now - *fsm.batch.stored);
        line += " (was " + format_length(c.config, *fsm.batch.stored) + ", " + change + ")";
      } else {
        line += " (first measurement)";
      }
      fsm.batch.report.push_back(line);
      ++fsm.batch.done;
    }
  };
  struct RecordNotMeasured {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      fsm.batch.report.push_back("T" + std::to_string(c.request.tool) +
                                 " not measured: " + fsm.template get_state<Probe&>().problem);
      ++fsm.batch.done;
    }
  };
  struct SayReport {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      Context& c = *fsm.ctx;
      std::string text = "measure all " +
                         std::string(fsm.batch.cancel ? "cancelled after " : "done: ") +
                         std::to_string(fsm.batch.done) + " of " +
                         std::to_string(fsm.batch.tools.size()) + " tools";
      for (const auto& line : fsm.batch.report) text += "; " + line;
      c.tell(MessageKind::info, text);
    }
  };

  /// Cancel asks the batch to stop after the tool under way is put back; a
  /// probe under way stops too (its own row), and this still stops the batch.
  struct AskToStop {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.batch.cancel = true;
      fsm.ctx->tell(MessageKind::info, "measure all stops once tool " +
                                           std::to_string(fsm.ctx->request.tool) +
                                           " is back in its pocket");
    }
  };
  /// A second region: it hears Cancel whatever the batch is doing.
  struct ListeningForCancel : msmf::state<> {};

  using initial_state = boost::mpl::vector<DecidingNextTool, ListeningForCancel>;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                               Event         Next              Action             Guard
  // +-----------------------------------+--------------+-----------------+------------------+-----------------------------------+
  Row < DecidingNextTool                  , none          , Returning       , none             , SpindleHoldsTool                  >,
  Row < DecidingNextTool                  , none          , RetrieveLeg     , TakeNextTool     , And<Not<SpindleHoldsTool>, ToolsLeft> >,
  Row < DecidingNextTool                  , none          , Finished        , SayReport        , And<Not<SpindleHoldsTool>, Not<ToolsLeft>> >,
  Row < Returning::exit_pt<Finished>      , LegDone       , ReportingReturned, none            , none                              >,
  Row < ReportingReturned                 , CommandDone   , DecidingNextTool, none             , none                              >,
  Row < RetrieveLeg::exit_pt<Finished>    , LegDone       , ReportingFetched, none             , none                              >,
  Row < ReportingFetched                  , CommandDone   , ToSensor        , none             , none                              >,
  Row < ToSensor                          , InPosition    , Probe           , none             , none                              >,
  Row < Probe::exit_pt<Finished>          , LegDone       , DecidingNextTool, RecordMeasured   , none                              >,
  Row < Probe::exit_pt<Probe::NotMeasured>, LegDone       , DecidingNextTool, RecordNotMeasured, none                              >,
  Row < ListeningForCancel                , OperatorCancel, none            , AskToStop        , none                              >
  >;
  // clang-format on
};

}  // namespace fatc::machine
