#pragma once

// An air run: its request and its declaration; its table is in
// air_run_flow.hpp, its words, its own rule and its run in air_run_flow.cpp.
// The route comes planned (dry_run/air_run.hpp): the sequence it flies over
// the rack is the Simulator's, above this layer.

#include <string>
#include <vector>

#include "../../motion/step.hpp"
#include "flow_kind.hpp"

namespace fatc {

/// The operator asks for a sequence flown in the air (plan_air_run makes it).
struct AirRunRequest {
  std::string name;  ///< "air run of M6 T3 with T1, 100.000 mm above the rack at F1000"
  std::vector<Step> route;  ///< every move, in order
};

}  // namespace fatc

namespace fatc::machine {

struct AirRunFlow_;
struct StopDryRun;

/// An air run (air_run_flow.hpp): a dry run, so an abort is no fault.
struct AirRun : FlowKind {
  using request = AirRunRequest;
  using front = AirRunFlow_;
  static constexpr Phase phase = Phase::air_run;
  static constexpr const char* word = "air run";
  static constexpr bool dry_run = true;
  using when_aborted = StopDryRun;
  static int tool(const Context& c, const AirRunRequest&);
  static std::string name(const AirRunRequest& e);
  static std::optional<std::string> why_not(const Context& c, const AirRunRequest& e);
  static std::string busy(const Context& c);
  static std::unique_ptr<FlowRun> run(Context& c, const AirRunRequest& e);
};

}  // namespace fatc::machine
