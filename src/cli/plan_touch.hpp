#pragma once

#include <iosfwd>

#include "inputs.hpp"

namespace fatc::io {

/// --plan --touch POCKETS: the path that finds those features by touch
/// (rack_touch), each touch as if it touched where expected, checked against
/// the keep-out with the probe's length; 0 printed, 1 refused or invalid.
int plan_touch(const Options& options, const Loaded& loaded, std::ostream& out);

}  // namespace fatc::io
