#pragma once

#include <string>
#include <vector>

namespace fatc::linuxcnc {

/// The pin table of docs/pins.md, from pin_list.hpp.
std::string pins_markdown();
/// The man page's PINS section, from pin_list.hpp.
std::string pins_man();
/// What `show pin fixed_atc_probe` lists right after `loadusr -W` with a
/// config of `pockets`: type, direction, value (the heartbeat's `*`) and name,
/// sorted by name as halcmd sorts them (tests/integration/pins/pins.golden).
std::string pins_golden(const std::vector<int>& pockets);

}  // namespace fatc::linuxcnc
