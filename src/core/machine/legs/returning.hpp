#pragma once

// What both returns share, the drawbar's and the collet nut's: the pocket
// that must be empty, the record, and the way away. docs/sequences.md#return.

#include "cover.hpp"

namespace fatc::machine {

/// The leg's tool sits in the leg's pocket now.
struct RecordToolInPocket {
  template <class Event, class Fsm, class Source, class Target>
  void operator()(const Event&, Fsm& fsm, Source&, Target&) const {
    fsm.ctx->record_in_pocket(fsm.tool, fsm.pocket);
  }
};
struct PocketFull {
  template <class Leg>
  static std::string text(const Context&, const Leg& leg) {
    return "pocket " + std::to_string(leg.pocket) + " is not empty (" + pocket_pin(leg.pocket) +
           " on): tool " + std::to_string(leg.tool) + " cannot go in";
  }
};
using FaultPocketFull = FaultSaying<PocketFull, false>;
/// Up and away from the pocket; a fetch that follows on the direct path
/// starts over it (the leg's `fetch_follows`).
struct AwayFromPocket : Walking<AwayFromPocket> {
  template <class Leg>
  static plan::Route route(const Context& c, const Leg& leg) {
    return plan::phase(c.config, c.standing(), plan::return_away, leg.pocket, leg.fetch_follows);
  }
};

}  // namespace fatc::machine
