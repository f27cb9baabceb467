#pragma once

// The man page's text, shared by what writes its sections: the command line
// (cli/usage.cpp) and the pins (linuxcnc/live/pin_reference.cpp).

#include <string>

namespace fatc::io {

/// `text` for the man page: a backslash escaped, `code` in bold.
std::string man_text(const std::string& text);

}  // namespace fatc::io
