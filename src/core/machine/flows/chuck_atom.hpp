#pragma once

// A chuck atom: its request and its declaration; its table is in chuck_flow.hpp,
// its words, its own rule and its run in chuck_flow.cpp.

#include "../../motion/point.hpp"
#include "flow_kind.hpp"

namespace fatc {

/// A chuck atom from G-code (nc_files/fixed_atc_probe_chuck_*.ngc): release
/// (open) the chuck and leave it open, or clamp (close) it. `at`: where the
/// machine stands (machine coordinates, config units), when LinuxCNC says.
struct ChuckRequest {
  enum class Action { release, clamp };
  Action action = Action::clamp;
  std::optional<Point> at;
};

}  // namespace fatc

namespace fatc::machine {

struct ChuckFlow_;
struct AnswerChuckDone;

/// A chuck atom from G-code (chuck_flow.hpp); Operating does not rehearse it.
struct ChuckAtom : FlowKind {
  using request = ChuckRequest;
  using front = ChuckFlow_;
  static constexpr Phase phase = Phase::chuck;
  static constexpr const char* word = "chuck";
  static constexpr bool in_program = true;
  static constexpr bool rehearsed = false;
  using when_finished = AnswerChuckDone;
  static int tool(const Context& c, const ChuckRequest&);
  static std::string name(const ChuckRequest& e);
  static std::optional<std::string> why_not(const Context& c, const ChuckRequest& e);
  static std::string busy(const Context& c);
  static std::unique_ptr<FlowRun> run(Context& c, const ChuckRequest& e);
};

}  // namespace fatc::machine
