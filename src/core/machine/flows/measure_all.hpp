#pragma once

// Measure all: its request and its declaration; its table is in measure_all_flow.hpp,
// its words, its own rule and its run in measure_all_flow.cpp.

#include <vector>

#include "flow_kind.hpp"

namespace fatc {

/// The operator asks to measure `tools` one after another (measure all).
struct MeasureRequest {
  std::vector<int> tools;
};

}  // namespace fatc

namespace fatc::machine {

struct MeasureAllFlow_;

/// Measure all (measure_all_flow.hpp): the flow picks each tool in turn.
struct MeasureAll : FlowKind {
  using request = MeasureRequest;
  using front = MeasureAllFlow_;
  static constexpr Phase phase = Phase::measuring;
  static constexpr const char* word = "measuring";
  static int tool(const Context& c, const MeasureRequest&);
  static std::string name(const MeasureRequest& e);
  static std::optional<std::string> why_not(const Context& c, const MeasureRequest& e);
  static std::string busy(const Context& c);
  static std::unique_ptr<FlowRun> run(Context& c, const MeasureRequest& e);
};

}  // namespace fatc::machine
