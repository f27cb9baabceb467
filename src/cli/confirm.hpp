#pragma once

#include <iosfwd>

#include "options.hpp"

namespace fatc::io {

/// --confirm: the recovery of a fault without LinuxCNC. Returns 0 when the
/// state file was written, 1 when the answer or a file was refused.
int confirm(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace fatc::io
