#pragma once

// The rack cover (`rack_cover`): it opens before a leg's first move into
// the rack; docs/sequences.md#rack-cover.

#include "../chuck.hpp"

namespace fatc::machine {

// ================================================================ the rack cover
/// `rack_cover`: the cover opens before a leg's first move into the rack (at
/// once where there is none or it is open already); it closes when the
/// changer is done with the rack (Operating's ComparingSensors). Rows:
/// SensorReport [CoverOpen] on, TimerElapsed to the fault.
struct OpeningCover : msmf::state<> {
  using flag_list = boost::mpl::vector1<flag::AwaitsSensor>;
  template <class Event, class Fsm>
  void on_entry(const Event&, Fsm& fsm) {
    Context& c = *fsm.ctx;
    c.open_cover();
    if (c.cover_reads_open()) {
      c.raise.sensor_report();
    } else if (c.sensors.senses_cover_opened()) {
      c.await_sensor(c.config.rack_cover->timeout_seconds,
                     "waiting for the rack cover to open (" + Sensors::cover_opened_pin() + ")");
    } else {
      c.await_sensor(c.config.rack_cover->seconds, "opening the rack cover");
    }
  }
  template <class Event, class Fsm>
  void on_exit(const Event&, Fsm& fsm) {
    fsm.ctx->ports.cancel_timer();
  }
  /// A cover with no opened sensor is open once it has had its seconds.
  struct HasNoOpenedSensor {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      return !fsm.ctx->sensors.senses_cover_opened();
    }
  };
  struct Settle {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
      fsm.ctx->outputs.cover_settled = true;
      fsm.ctx->raise.sensor_report();
    }
  };
  using internal_transition_table =
      boost::mpl::vector<msmf::Internal<TimerElapsed, Settle, HasNoOpenedSensor>>;
};
/// The rack cover is open, or there is none.
struct CoverOpen : SensorGuard<CoverOpen> {
  template <class Leg>
  static bool holds(const Context& c, const Leg&) {
    return c.cover_reads_open();
  }
};
struct CoverDidNotOpen {
  template <class Leg>
  static std::string text(const Context& c, const Leg&) {
    return "the rack cover did not open within rack_cover.timeout_seconds (" +
           seconds_words(c.config.rack_cover->timeout_seconds) + ", " +
           Sensors::cover_opened_pin() + " off): nothing moved into the rack";
  }
};
using FaultCoverDidNotOpen = FaultSaying<CoverDidNotOpen, false>;
/// Only then is a timeout a fault: without it the timer means "open by now".
struct CoverHasOpenedSensor {
  template <class Event, class Fsm, class Source, class Target>
  bool operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    return fsm.ctx->config.rack_cover && fsm.ctx->sensors.senses_cover_opened();
  }
};

}  // namespace fatc::machine
