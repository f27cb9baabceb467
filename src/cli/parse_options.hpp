#pragma once

#include <optional>
#include <string>
#include <vector>

#include "options.hpp"

namespace fatc::io {

/// Parses argv; nullopt and one line in `error` on a usage mistake: an
/// unknown, repeated or empty option, two modes at once, an option the mode
/// does not use.
std::optional<Options> parse_options(const std::vector<std::string>& args, std::string& error);

}  // namespace fatc::io
