#pragma once

// What every flow declares where it differs from the rest: the base of a
// flow's declaration (NAME.hpp in this folder). Light on purpose: the
// changer's public header reads every declaration and no transition table.

#include <memory>
#include <optional>
#include <string>

#include "../base/status.hpp"

namespace fatc {
class Context;
}

namespace fatc::machine {

class FlowRun;
/// Operating's answer to a flow that finished (answers.hpp).
struct AnswerDone;

/// No row: a flow that declares none of this end.
struct NoRow {};

/// What a flow declares only where it differs. `tool` is the tool the
/// request is about (Context::requested_tool while the flow runs).
struct FlowKind {
  /// Runs inside a G-code program (M6, a chuck atom): the operator's answers
  /// hold the program, and a refusal fails it.
  static constexpr bool in_program = false;
  /// Its request is run on a copy of the changer before it is taken, once
  /// its own rule lets it (Operating's why_not).
  static constexpr bool rehearsed = true;
  /// A dry run (verify, an air run): the chuck stays closed and nothing is
  /// recorded, so an abort or the machine going off leaves the tools where
  /// they were (StopDryRun), no fault.
  static constexpr bool dry_run = false;
  /// A guard under which the request is answered done without a flow.
  using answered_at_once = NoRow;
  using when_finished = AnswerDone;
  /// The flow's Failed end: the changer faults.
  static constexpr bool may_fail = false;
  using when_cancelled = NoRow;
  /// LinuxCNC's abort while the flow runs; NoRow: the changer faults.
  using when_aborted = NoRow;
  template <class Request>
  static int tool(const Context&, const Request& e) {
    return e.tool;
  }
};

}  // namespace fatc::machine
