#pragma once

// Reading `chuck` of config.json (chuck.cpp): a drawbar, or a collet-nut
// magazine whose nuts the spindle screws (docs/collet_nut.md).

#include "reader.hpp"

namespace fatc::reading {

/// `chuck`; with "collet_nut" every pocket is entered from the top and the
/// tool-recognition sensor is wired where `recognition` is given.
void read_chuck(Reader& reader, const Json& root, Config& config);
/// Its keys against each other, safe Z, the sensors and the rack's tools,
/// once every key read cleanly.
void check_chuck(Reader& reader, const Config& config);

}  // namespace fatc::reading
