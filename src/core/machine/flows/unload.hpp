#pragma once

// Unload: its request and its declaration; its table is in unload_flow.hpp,
// its words, its own rule and its run in unload_flow.cpp.

#include "flow_kind.hpp"

namespace fatc {

/// The operator asks to take tool `tool` out of the machine.
struct UnloadRequest {
  int tool = 0;
};

}  // namespace fatc

namespace fatc::machine {

struct UnloadFlow_;

/// Unload (unload_flow.hpp).
struct Unload : FlowKind {
  using request = UnloadRequest;
  using front = UnloadFlow_;
  static constexpr Phase phase = Phase::unloading;
  static constexpr const char* word = "unloading";
  static std::string name(const UnloadRequest& e);
  static std::optional<std::string> why_not(const Context& c, const UnloadRequest& e);
  static std::string busy(const Context& c);
  static std::unique_ptr<FlowRun> run(Context& c, const UnloadRequest& e);
};

}  // namespace fatc::machine
