#pragma once

// Reading `rack_touch` of config.json (rack_touch.cpp): how a 3D probe finds
// the pockets and the rack datum (docs/sequences.md, teach by touch).

#include "reader.hpp"

namespace fatc::reading {

/// `rack_touch`, its lengths defaulted in the config's units.
void read_rack_touch(Reader& reader, const Json& root, Config& config);
/// Its keys against each other and the pockets, once every key read cleanly.
void check_rack_touch(Reader& reader, const Config& config);

}  // namespace fatc::reading
