#pragma once

#include <iosfwd>

#include "options.hpp"

namespace fatc::io {

/// --plan: the steps of one change, checked, and its estimated time; 0
/// printed, 1 refused or invalid.
int plan(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace fatc::io
