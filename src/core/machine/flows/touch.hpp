#pragma once

// The rack found by touch: its request and its declaration; its table is in
// touch_flow.hpp, its words, its own rule and its run in touch_flow.cpp. The
// touches themselves, where each starts and what they give, are
// rack/touch.hpp's.

#include <vector>

#include "flow_kind.hpp"

namespace fatc {

/// The operator asks the probe in the spindle to touch the rack.
struct TouchRequest {
  enum class Goal {
    pockets,      ///< teach `pockets` by touch: their positions into config.json once accepted
    teach_datum,  ///< touch the rack datum and keep where it is as its taught position
    check_datum,  ///< touch the rack datum and compare: the drift check
  };
  Goal goal = Goal::pockets;
  std::vector<int> pockets;  ///< Goal::pockets: which, in order; empty: every pocket
};

}  // namespace fatc

namespace fatc::machine {

struct TouchFlow_;
struct StopDryRun;
struct AnswerTouchEnd;

/// Touching the rack (touch_flow.hpp): the chuck stays closed and nothing is
/// recorded until the operator accepts, so an abort is no fault.
struct TouchRack : FlowKind {
  using request = TouchRequest;
  using front = TouchFlow_;
  static constexpr Phase phase = Phase::touching;
  static constexpr const char* word = "touching";
  static constexpr bool dry_run = true;
  using when_finished = AnswerTouchEnd;
  using when_cancelled = AnswerTouchEnd;
  using when_aborted = StopDryRun;
  static int tool(const Context& c, const TouchRequest&);
  static std::string name(const TouchRequest& e);
  static std::optional<std::string> why_not(const Context& c, const TouchRequest& e);
  static std::string busy(const Context& c);
  static std::unique_ptr<FlowRun> run(Context& c, const TouchRequest& e);
};

}  // namespace fatc::machine
