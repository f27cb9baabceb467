#pragma once

#include <map>
#include <optional>
#include <string>

#include "core/config.hpp"
#include "core/geometry.hpp"

namespace fatc::io {

/// A LinuxCNC INI file: [SECTION] then KEY = VALUE; '#' and ';' start comments.
class IniFile {
 public:
  /// nullopt and `error` set when the file cannot be read.
  static std::optional<IniFile> read(const std::string& path, std::string& error);
  std::optional<std::string> get(const std::string& section, const std::string& key) const;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::map<std::string, std::map<std::string, std::string>> values_;
};

/// The soft limits of axes X, Y and Z ([AXIS_n] MIN_LIMIT/MAX_LIMIT), converted
/// from [TRAJ]LINEAR_UNITS into `units`. nullopt and `error` when any is missing.
std::optional<SoftLimits> soft_limits(const IniFile& ini, Units units, std::string& error);

}  // namespace fatc::io
