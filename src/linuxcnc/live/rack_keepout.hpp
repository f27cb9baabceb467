#pragma once

#include <optional>
#include <vector>

#include "core/machine/changer.hpp"
#include "core/rack/keepout.hpp"

namespace fatc::linuxcnc {

struct HalPins;
class NmlLink;

/// The component's side of the realtime guard `fatc-rack-guard`
/// (src/rt/fatc_rack_guard.comp), which holds motion before it enters the
/// rack: the rack's volume and the spindle tool's length out in machine
/// units, the guard armed only while the keep-out should hold, and a trip
/// turned into an abort of what task runs and one line saying what moved,
/// where, with which tool.
class RackKeepout {
 public:
  /// `tool_length`: the spindle tool's, as the keep-out counts it (config units).
  void poll(HalPins& pins, const Changer& changer, bool machine_ready, NmlLink* nml,
            double tool_length, Ports& ports);
  KeepoutState state() const { return state_; }

 private:
  /// The rack's volume for `config`, worked out again only when the rack changed.
  const std::vector<RackPart>& volume(const Config& config);

  KeepoutState state_ = KeepoutState::not_armed;
  std::optional<int> trips_;  ///< fatc-rack-guard.trips last read
  bool said_off_ = false;
  std::vector<double> rack_;  ///< what the volume was worked out from
  std::vector<RackPart> volume_;
};

}  // namespace fatc::linuxcnc
