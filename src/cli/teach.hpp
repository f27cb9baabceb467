#pragma once

#include <iosfwd>

#include "options.hpp"

namespace fatc::io {

/// --teach: the machine position into config.json, the file as it was kept as PATH.bak.
/// The config is taken before it is read: a teach at the same time (here or
/// in the component) waits its turn and then reads what this one wrote.
/// 0 written, 1 refused (nothing written), 2 the config or INI cannot be read
/// or the config cannot be written.
int teach_position(const Options& options, std::ostream& out, std::ostream& err);

}  // namespace fatc::io
