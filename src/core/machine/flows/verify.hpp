#pragma once

// Verify a pocket: its request and its declaration; its table is in verify_flow.hpp,
// its words, its own rule and its run in verify_flow.cpp.

#include "flow_kind.hpp"

namespace fatc {

/// The operator asks for a dry run through pocket `pocket`'s approach (verify).
struct VerifyRequest {
  int pocket = 0;
};

}  // namespace fatc

namespace fatc::machine {

struct VerifyFlow_;
struct StopDryRun;

/// Verify a pocket (verify_flow.hpp): a dry run, so an abort is no fault.
struct Verify : FlowKind {
  using request = VerifyRequest;
  using front = VerifyFlow_;
  static constexpr Phase phase = Phase::verifying;
  static constexpr const char* word = "verifying";
  static constexpr bool dry_run = true;
  using when_cancelled = AnswerDone;
  using when_aborted = StopDryRun;
  static int tool(const Context& c, const VerifyRequest&);
  static std::string name(const VerifyRequest& e);
  static std::optional<std::string> why_not(const Context& c, const VerifyRequest& e);
  static std::string busy(const Context& c);
  static std::unique_ptr<FlowRun> run(Context& c, const VerifyRequest& e);
};

}  // namespace fatc::machine
