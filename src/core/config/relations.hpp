#pragma once

// The relations between config.json's keys (relations.cpp): each key may be
// within its bounds and still not fit the others.

#include "reader.hpp"

namespace fatc::reading {

/// The rack's geometry, the sensor outside it, the blend, the probing window
/// and feeds against each other, once every key read cleanly.
void check_relations(Reader& reader, const Config& config);

}  // namespace fatc::reading
