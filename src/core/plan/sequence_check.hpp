#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "../config/config.hpp"
#include "../rack/geometry.hpp"
#include "simulator.hpp"
#include "../protocol/step.hpp"

namespace fatc {

/// One move of a planned sequence that breaks the rack keep-out or the soft limits.
struct SequenceViolation {
  std::string sequence;  ///< "M6 T3 from empty", "load T3"
  std::size_t step = 0;  ///< index into the sequence's steps
  Step move;
  std::string what;
};

/// "M6 T3 from empty, step 5 (rapid to side of pocket 3): passes through the rack at pocket 4".
std::string describe(const SequenceViolation& violation);

/// The violations of one planned sequence, named `sequence`.
std::vector<SequenceViolation> check_sequence(const std::string& sequence, const Config& config,
                                              const Simulator& planned,
                                              const std::optional<SoftLimits>& limits);

struct SequencesChecked {
  int sequences = 0;
  std::vector<SequenceViolation> violations;
};

/// Plans every sequence the changer can run through each pocket (M6 to it
/// with an empty spindle, M6 T0 from it, load, unload) and checks each move
/// against the keep-out and the soft limits: what `--check` reports and what
/// a taught position must pass.
SequencesChecked check_sequences(const Config& config, const std::optional<SoftLimits>& limits);

}  // namespace fatc
