#pragma once

#include <string>

namespace fatc {

/// Which flow the changer is in; the value of the `state` pin.
enum class Phase { not_ready = 0, idle = 1, changing = 2, loading = 3, unloading = 4, fault = 5 };

/// Which event the changer waits for now; adapters deliver only that one. The
/// values are those of the `awaiting` pin.
enum class Awaiting {
  nothing = 0,
  motion = 1,
  probe = 2,
  timer = 3,
  spindle = 4,
  operator_choice = 5
};

struct Status {
  Phase phase = Phase::not_ready;
  Awaiting awaiting = Awaiting::nothing;
  std::string activity;  ///< what it is doing, in the machinist's words
};

const char* phase_name(Phase phase);

/// A probe of the load flow runs over MDI: Cancel stops it (the adapter
/// aborts the motion first). M6 probes run inside the program, which the
/// operator stops with LinuxCNC's own Stop.
inline bool probe_cancellable(const Status& status) {
  return status.phase == Phase::loading && status.awaiting == Awaiting::probe;
}

}  // namespace fatc
