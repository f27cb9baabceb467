#pragma once

#include <iosfwd>
#include <vector>

#include "core/dry_run/sequence_check.hpp"
#include "options.hpp"

namespace fatc::io {

/// --check: 0 when config, state and INI are valid and no planned move breaks
/// the keep-out or the soft limits, 1 otherwise.
int check(const Options& options, std::ostream& out, std::ostream& err);

/// Prints the violations, one indented line each, capped; returns how many.
int report(const std::vector<SequenceViolation>& violations, std::ostream& out);

}  // namespace fatc::io
