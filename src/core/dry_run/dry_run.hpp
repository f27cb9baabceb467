#pragma once

#include "../machine/base/rehearsal.hpp"

namespace fatc {

/// The rehearsal the running changer uses: the request planned with the
/// Simulator from where the spindle stands and the tools where they are, the
/// operator continuing at every wait and the sensor touching as low as
/// `probe_limit` lets it; every move checked with the length of the tool it
/// carries (the changer's keepout_lengths) and against the soft limits.
class DryRun : public Rehearsal {
 public:
  std::optional<std::string> why_not(
      const Context& ctx, const std::function<void(Changer&)>& request) const override;
};

}  // namespace fatc
