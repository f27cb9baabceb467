#pragma once

// M6: its request and its declaration; its table is in change_flow.hpp,
// its words, its own rule and its run in change_flow.cpp.

#include "flow_kind.hpp"

namespace fatc {

/// M6: put `tool` in the spindle (0 leaves it empty).
struct ToolChange {
  int tool = 0;
};

}  // namespace fatc

namespace fatc::machine {

struct ChangeFlow_;
struct AlreadyInSpindle;
struct StopProgram;
struct AnswerChangeDone;

/// M6 (change_flow.hpp).
struct Change : FlowKind {
  using request = ToolChange;
  using front = ChangeFlow_;
  static constexpr Phase phase = Phase::changing;
  static constexpr const char* word = "changing";
  static constexpr bool in_program = true;
  using answered_at_once = AlreadyInSpindle;
  static constexpr bool may_fail = true;
  using when_cancelled = StopProgram;
  using when_finished = AnswerChangeDone;
  static std::string name(const ToolChange& e);
  static std::optional<std::string> why_not(const Context& c, const ToolChange& e);
  static std::string busy(const Context& c);
  static std::unique_ptr<FlowRun> run(Context& c, const ToolChange& e);
};

}  // namespace fatc::machine
