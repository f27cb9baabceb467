#include "ini.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>

namespace fatc::io {
namespace {

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

}  // namespace

std::optional<IniFile> IniFile::read(const std::string& path, std::string& error) {
  std::ifstream in(path);
  if (!in) {
    error = path + ": cannot open (" + std::strerror(errno) + ")";
    return std::nullopt;
  }
  IniFile ini;
  ini.path_ = path;
  std::string line;
  std::string section;
  while (std::getline(in, line)) {
    const std::string text = trim(line);
    if (text.empty() || text[0] == '#' || text[0] == ';') continue;
    if (text.front() == '[' && text.back() == ']') {
      section = text.substr(1, text.size() - 2);
      continue;
    }
    const auto equals = text.find('=');
    if (equals == std::string::npos) continue;
    const std::string key = trim(text.substr(0, equals));
    // LinuxCNC keeps the first of repeated keys for single values.
    ini.values_[section].emplace(key, trim(text.substr(equals + 1)));
  }
  return ini;
}

std::optional<std::string> IniFile::get(const std::string& section, const std::string& key) const {
  const auto s = values_.find(section);
  if (s == values_.end()) return std::nullopt;
  const auto k = s->second.find(key);
  if (k == s->second.end()) return std::nullopt;
  return k->second;
}

std::optional<SoftLimits> soft_limits(const IniFile& ini, Units units, std::string& error) {
  double scale = 1.0;
  const auto linear = ini.get("TRAJ", "LINEAR_UNITS").value_or("mm");
  const bool ini_in_inch = linear == "inch" || linear == "in" || linear == "imperial";
  if (ini_in_inch && units == Units::mm) scale = 25.4;
  if (!ini_in_inch && units == Units::inch) scale = 1.0 / 25.4;
  SoftLimits limits;
  AxisLimits* axes[] = {&limits.x, &limits.y, &limits.z};
  const char* names[] = {"AXIS_X", "AXIS_Y", "AXIS_Z"};
  for (int i = 0; i < 3; ++i) {
    for (const char* key : {"MIN_LIMIT", "MAX_LIMIT"}) {
      const auto text = ini.get(names[i], key);
      double value = 0.0;
      try {
        if (!text) throw std::invalid_argument("missing");
        value = std::stod(*text);
      } catch (const std::exception&) {
        error = ini.path() + ": [" + names[i] + "]" + key + ": expected a number, got " +
                (text ? "\"" + *text + "\"" : std::string("nothing"));
        return std::nullopt;
      }
      (std::string(key) == "MIN_LIMIT" ? axes[i]->min : axes[i]->max) = value * scale;
    }
  }
  return limits;
}

}  // namespace fatc::io
