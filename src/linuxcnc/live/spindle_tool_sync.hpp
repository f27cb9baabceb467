#pragma once

#include <chrono>
#include <optional>

#include "core/machine/changer.hpp"

namespace fatc::linuxcnc {

class NmlLink;

/// Keeps LinuxCNC's tool in spindle in line with the changer's: LinuxCNC
/// starts with an empty spindle, and an operator's confirmation after a
/// fault changes what the spindle holds. Told by M61 over MDI once the
/// changer is idle and task free; nothing is sent while the changer is unsure.
class SpindleToolSync {
 public:
  using Clock = std::chrono::steady_clock;

  /// The changer's record may differ from LinuxCNC's from now on.
  void want() { wanted_ = true; }
  /// Only while task is free for an MDI; `linuxcnc_tool`: iocontrol's tool-number now.
  void poll(Clock::time_point now, int linuxcnc_tool, const Changer& changer, NmlLink& nml,
            Ports& ports);

 private:
  bool wanted_ = true;
  std::optional<Clock::time_point> sent_;
};

}  // namespace fatc::linuxcnc
