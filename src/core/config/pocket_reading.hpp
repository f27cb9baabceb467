#pragma once

// Reading `pockets` and `pocket_default` of config.json (pocket_reading.cpp).

#include "reader.hpp"

namespace fatc::reading {

/// Each pocket: where it is, the tool it holds at first start and how the
/// spindle enters it, pocket_default merged.
void read_pockets(Reader& reader, const Json& root, Config& config);

}  // namespace fatc::reading
