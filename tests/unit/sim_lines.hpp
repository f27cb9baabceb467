#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "core/dry_run/simulator.hpp"

namespace fatc::test {

using Lines = std::vector<std::string>;

/// The Simulator's records since `from`, compactly: "rapid safe Z",
/// "chuck open", "dwell 0.50", "done T4"; messages and saves left out.
inline Lines record_lines(const Simulator& sim, std::size_t from = 0) {
  Lines out;
  char buffer[32];
  for (std::size_t i = from; i < sim.records.size(); ++i) {
    const Record& r = sim.records[i];
    switch (r.kind) {
      case Record::Kind::step:
        if (r.step.kind == StepKind::done || r.step.kind == StepKind::set_spindle_tool) {
          out.push_back(std::string(step_kind_name(r.step.kind)) + " T" +
                        std::to_string(r.step.tool));
        } else {
          out.push_back(std::string(step_kind_name(r.step.kind)) + " " + r.step.label);
        }
        break;
      case Record::Kind::chuck:
        out.push_back(r.chuck_open ? "chuck open" : "chuck close");
        break;
      case Record::Kind::cover:
        out.push_back(r.on ? "cover open" : "cover close");
        break;
      case Record::Kind::blast:
        out.push_back(r.on ? "blast on" : "blast off");
        break;
      case Record::Kind::dwell:
        std::snprintf(buffer, sizeof buffer, "dwell %.2f", r.seconds);
        out.push_back(buffer);
        break;
      case Record::Kind::message:
      case Record::Kind::save:
        break;
    }
  }
  return out;
}

/// The last message the changer told, of any kind; "" when none.
inline std::string last_message(const Simulator& sim) {
  for (auto it = sim.records.rbegin(); it != sim.records.rend(); ++it) {
    if (it->kind == Record::Kind::message) return it->text;
  }
  return "";
}

}  // namespace fatc::test
