#include "canonical_call.hpp"

#include <charconv>

namespace fatc::program {

std::vector<double> call_numbers(std::string_view call) {
  std::vector<double> values;
  const auto open = call.find('(');
  if (open == std::string_view::npos) return values;
  const char* p = call.data() + open + 1;
  const char* const end = call.data() + call.size();
  while (p < end) {
    if (*p == '-' || *p == '.' || (*p >= '0' && *p <= '9')) {
      double value = 0.0;
      const auto [next, failed] = std::from_chars(p, end, value);
      if (failed != std::errc()) break;
      values.push_back(value);
      p = next;
    } else {
      ++p;
    }
  }
  return values;
}

}  // namespace fatc::program
