// Any bytes as the machine INI, read by LinuxCNC's own reader: either soft
// limits that are finite with MIN not above MAX, or one printable line. Never
// a crash, an exception, a leak or undefined behaviour.
#include <cmath>
#include <cstdint>
#include <string>

#include "invariants.hpp"
#include "io/ini.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string error;
  const auto ini = fatc::io::IniFile::from_text(text, "fuzz.ini", error);
  if (!ini) {
    fatc::fuzz::check_messages({error});
    return 0;
  }
  for (const fatc::Units units : {fatc::Units::mm, fatc::Units::inch}) {
    const auto limits = fatc::io::soft_limits(*ini, units, error);
    if (!limits) {
      fatc::fuzz::check_messages({error});
      continue;
    }
    for (const fatc::AxisLimits& axis : {limits->x, limits->y, limits->z}) {
      if (!std::isfinite(axis.min) || !std::isfinite(axis.max) || axis.min > axis.max) {
        fatc::fuzz::broken("soft limits are finite, MIN not above MAX", text.substr(0, 200));
      }
    }
  }
  ini->get("EMC", "NML_FILE");  // what the component asks for
  return 0;
}
