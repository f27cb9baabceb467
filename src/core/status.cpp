#include "status.hpp"

namespace fatc {

const char* phase_name(Phase phase) {
  switch (phase) {
    case Phase::not_ready: return "not ready";
    case Phase::idle: return "idle";
    case Phase::changing: return "changing tool";
    case Phase::loading: return "loading tool";
    case Phase::unloading: return "unloading tool";
    case Phase::fault: return "fault";
  }
  return "?";
}

}  // namespace fatc
