#pragma once

// A flow (M6, load, unload, measure all, verify, a chuck atom) runs as a
// Boost.MSM machine of its own, built in its own file. Operating holds the
// one running (state Running<Flow>) and the Engine gives it each event it
// can take first, as Boost.MSM gives a submachine; what it leaves goes on to
// the machine above. No compiler run instantiates a flow and the machine
// above together, and Boost.MSM never merges the flows' tables into Operating's.

#include <boost/msm/back/common_types.hpp>
#include <memory>
#include <string>
#include <type_traits>
#include <typeindex>
#include <variant>

#include "events.hpp"

namespace fatc {
class Context;
}

namespace fatc::machine {

/// The events a flow's tables answer; every other event goes straight to
/// the machine above.
using FlowEvent = std::variant<InPosition, CommandDone, ProbeResult, TimerElapsed, SensorReport,
                               OperatorContinue, OperatorCancel>;
template <class Event, class Events = FlowEvent>
constexpr bool flow_takes = false;
template <class Event, class... Events>
constexpr bool flow_takes<Event, std::variant<Events...>> = (std::is_same_v<Event, Events> || ...);

/// How far a batch got (measure all); none for the other flows.
struct BatchCount {
  int done = 0;
  int total = 0;
};

/// How a flow ended, once it has.
enum class FlowEnd { running, finished, cancelled, failed };

class FlowRun {
 public:
  virtual ~FlowRun() = default;
  /// Boost.MSM's answer: taken, not taken, or rows whose guards all said no.
  virtual boost::msm::back::HandledEnum take(const FlowEvent& event) = 0;
  /// Whether a state of the flow carries `flag` (a type of namespace flag).
  virtual bool flagged(std::type_index flag) const = 0;
  /// How the flow ended, told once: `running` until it ends and after.
  virtual FlowEnd take_end() = 0;
  /// Why it failed, once it has.
  virtual const std::string& failure() const = 0;
  virtual BatchCount batch() const = 0;
  /// Leaves the flow's states, as the machine above leaves Running<Flow>.
  virtual void stop() = 0;
};

}  // namespace fatc::machine
