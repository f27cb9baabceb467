// Any bytes as the machine INI, read by LinuxCNC's own reader: either soft
// limits that are finite with MIN not above MAX, or one printable line. Its
// #INCLUDE lines expanded as the linuxcnc script does, with a.inc the same
// bytes again and any other name missing: one origin for each line, every
// problem one printable line. Never a crash, an exception, a leak or
// undefined behaviour.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "invariants.hpp"
#include "io/files.hpp"
#include "linuxcnc/offline/ini.hpp"
#include "linuxcnc/offline/machine_ini.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string error;
  const fatc::io::ExpandedIni expanded = fatc::io::expand_includes(
      text, "fuzz.ini", "/nonexistent",
      [&](const std::string& path, std::string& why) -> std::optional<std::string> {
        if (path == "/nonexistent/a.inc") return text;
        why = fatc::io::shown_path(path) + ": cannot open (No such file or directory)";
        return std::nullopt;
      });
  if (!expanded.origins.empty() &&
      expanded.origins.size() !=
          static_cast<std::size_t>(std::count(expanded.text.begin(), expanded.text.end(), '\n'))) {
    fatc::fuzz::broken("one origin for each line of the expanded INI",
                       std::to_string(expanded.origins.size()));
  }
  for (const fatc::program::Finding& problem : expanded.problems) {
    fatc::fuzz::check_messages({problem.where.file + ": line " +
                                std::to_string(problem.where.line) + ": " + problem.text});
  }
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
  fatc::fuzz::check_messages(fatc::io::builtin_m6_moves(*ini));
  ini->get("EMC", "NML_FILE");  // what the component asks for
  return 0;
}
