#pragma once

// Step by step (issue 44): while it is on, each move and each chuck action of
// a sequence waits for the operator's Continue before it goes out. The
// Context's publish path asks it (Context::stop_before); no table knows of it.

#include <deque>
#include <functional>
#include <utility>
#include <vector>

#include "../../motion/step.hpp"
#include "prompt.hpp"

namespace fatc {

class StepGate {
 public:
  /// The operator's switch (the step-by-step pin: the panel, --operator --step).
  void switch_to(bool on) { switched_on_ = on; }
  /// A sequence starts: the switch as it stands now holds for the whole of
  /// it, so that one thrown mid-sequence counts from the next sequence on.
  void begin() { on_ = switched_on_; }
  /// The sequence's flow ended (finished, failed, cancelled, aborted):
  /// nothing stays held, and nothing more will be.
  void end();
  bool on() const { return on_; }

  /// Holds the step `question` describes, behind any held already (a chuck
  /// action and the phase its row enters); `go` makes it at Continue.
  void hold(Prompt question, std::function<void()> go);
  /// What the state that holds a step does after it (the timer of a chuck
  /// action) waits behind it; with nothing held it is done now.
  void then(std::function<void()> effect);
  bool holding() const { return !held_.empty(); }
  /// The step Continue makes next.
  const Prompt& question() const { return held_.front().question; }
  /// Continue: the first step held goes, with what waited behind it.
  void release();

  /// The moves of a run of rapids still to go, each a step of its own in
  /// this mode (no corner blended across a stop), with its --plan number.
  std::deque<std::pair<int, Step>> rest;

 private:
  bool switched_on_ = false;
  bool on_ = false;
  struct Held {
    Prompt question;
    std::vector<std::function<void()>> effects;  ///< the step, then what waits behind it
  };
  std::deque<Held> held_;
};

}  // namespace fatc
