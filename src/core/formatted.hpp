#pragma once

#include <cstdio>
#include <string>

namespace fatc {

/// printf's `pattern` with `values` (at least one) into a string as long as
/// it takes: a number as big as a double holds (a tool table's Z1e300, soft
/// limits of 1e99) is printed in full, never cut short by a buffer.
template <class... Values>
std::string formatted(const char* pattern, Values... values) {
  static_assert(sizeof...(Values) > 0, "a pattern without values is a string");
  const int length = std::snprintf(nullptr, 0, pattern, values...);
  if (length <= 0) return "";
  std::string text(static_cast<std::size_t>(length), '\0');
  std::snprintf(text.data(), text.size() + 1, pattern, values...);
  return text;
}

}  // namespace fatc
