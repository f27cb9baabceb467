#pragma once

// Flushing the chuck before the spindle receives a tool.
// docs/sequences.md#flush.

#include "../chuck.hpp"

namespace fatc::machine {

// ================================================================ flush
/// Opens the chuck briefly, `flush.pulses` times, so that whatever the spindle
/// may still hold drops before it receives a tool (docs/sequences.md#flush).
/// Each opening waits until the chuck may open and must read open; each
/// closing must read closed. Ends with the chuck closed.
struct FlushLeg_ : Flow<FlushLeg_> {
  int pulses_done = 0;

  template <class Event, class Parent>
  void on_entry(const Event& e, Parent& parent) {
    Flow::on_entry(e, parent);
    pulses_done = 0;
  }

  struct WaitingToOpen : WaitingToOpenChuck<ToFlush> {};
  struct PulseOpen : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      ++fsm.pulses_done;
      fsm.ctx->open_chuck();
      fsm.ctx->wait(fsm.ctx->config.flush.pulse_seconds, "flushing the chuck (open)");
    }
  };
  struct PulseClosed : Timed {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      fsm.ctx->close_chuck();
      fsm.ctx->wait(fsm.ctx->config.flush.pause_seconds, "flushing the chuck (closed)");
    }
  };
  struct PulsesLeft {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return fsm.pulses_done < fsm.ctx->config.flush.pulses;
    }
  };

  struct DecidingToPulse : Decision {};
  using initial_state = DecidingToPulse;
  // clang-format off
  using transition_table = boost::mpl::vector<
  //    Start                  Event          Next                 Action                             Guard
  // +----------------------+--------------+--------------------+----------------------------------+-----------------+
  Row < DecidingToPulse      , none         , WaitingToOpen      , none                             , PulsesLeft      >,
  Row < DecidingToPulse      , none         , Finished           , none                             , Not<PulsesLeft> >,
  Row < WaitingToOpen        , SensorReport , PulseOpen          , none                             , ChuckMayOpen    >,
  Row < WaitingToOpen        , TimerElapsed , Halted             , FaultChuckMayNotOpen<ToFlush>    , none            >,
  Row < PulseOpen            , TimerElapsed , CheckingDrawbarOpen, none                             , none            >,
  Row < CheckingDrawbarOpen  , SensorReport , PulseClosed        , none                             , DrawbarOpen     >,
  Row < CheckingDrawbarOpen  , TimerElapsed , Halted             , FaultDrawbarStayedClosed<ToFlush>, none            >,
  Row < PulseClosed          , TimerElapsed , CheckingDrawbarClosed, none                           , none            >,
  Row < CheckingDrawbarClosed, SensorReport , DecidingToPulse    , none                             , DrawbarClosed   >,
  Row < CheckingDrawbarClosed, TimerElapsed , Halted             , FaultDrawbarStayedOpen<ToFlush>  , none            >
  >;
  // clang-format on
};
using FlushLeg = Machine_of<FlushLeg_>;

}  // namespace fatc::machine
