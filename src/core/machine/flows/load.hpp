#pragma once

// Load and probe: its request and its declaration; its table is in load_flow.hpp,
// its words, its own rule and its run in load_flow.cpp.

#include "flow_kind.hpp"

namespace fatc {

/// The operator asks to load tool `tool` by hand, measure it and store it.
struct LoadRequest {
  int tool = 0;
  int pocket = 0;  ///< where it goes; 0: its own pocket, else the nearest free one
};

}  // namespace fatc

namespace fatc::machine {

struct LoadFlow_;

/// Load and probe (load_flow.hpp).
struct Load : FlowKind {
  using request = LoadRequest;
  using front = LoadFlow_;
  static constexpr Phase phase = Phase::loading;
  static constexpr const char* word = "loading";
  static std::string name(const LoadRequest& e);
  static std::optional<std::string> why_not(const Context& c, const LoadRequest& e);
  static std::string busy(const Context& c);
  static std::unique_ptr<FlowRun> run(Context& c, const LoadRequest& e);
};

}  // namespace fatc::machine
