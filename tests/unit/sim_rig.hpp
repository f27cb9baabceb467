#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "core/machine/changer.hpp"
#include "core/dry_run/simulator.hpp"
#include "sim_lines.hpp"

namespace fatc::test {

/// A changer on a Simulator that models the rack as `tools` has it, started
/// (sensors reported, machine ready, settled); an unexpected event fails the test.
struct SimRig {
  SimRig(Config c, ToolState t) : config(std::move(c)), tools(std::move(t)) {
    sim.model_rack(config, tools);
    changer = std::make_unique<Changer>(config, sim, tools);
    sim.report_sensors(*changer);
    changer->ready();
    sim.run(*changer);
    seen = sim.records.size();
  }
  ~SimRig() {
    EXPECT_TRUE(sim.unexpected_events.empty())
        << (sim.unexpected_events.empty() ? "" : sim.unexpected_events.front());
  }
  /// What the changer did since the last look, once the simulated executor
  /// has done what it asked.
  Lines run() {
    sim.run(*changer);
    const std::size_t from = seen;
    seen = sim.records.size();
    return record_lines(sim, from);
  }
  std::string last_message() const { return test::last_message(sim); }

  Config config;
  ToolState tools;
  Simulator sim;
  std::unique_ptr<Changer> changer;
  std::size_t seen = 0;  ///< records run() has returned
};

}  // namespace fatc::test
