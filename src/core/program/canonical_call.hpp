#pragma once

#include <string_view>
#include <vector>

namespace fatc::program {

/// Whether rs274's canonical call (or any text) begins with `start`.
inline bool starts_with(std::string_view text, std::string_view start) {
  return text.substr(0, start.size()) == start;
}

/// The numbers between the parentheses of a canonical call, in order:
/// `STRAIGHT_FEED(1.0000, 2.0000, ...)`.
std::vector<double> call_numbers(std::string_view call);

}  // namespace fatc::program
