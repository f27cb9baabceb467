#include "ini.hpp"

#include <strings.h>
#include <sys/stat.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <inifile.hh>
#include <limits>

#include "core/config/quote.hpp"
#include "core/dry_run/simulator.hpp"
#include "io/files.hpp"

#if FATC_LINUXCNC_INI_CLASS
#include <fcntl.h>
#include <sys/stat.h>

#include <atomic>
#endif

namespace fatc::io {
namespace {

#if FATC_LINUXCNC_INI_CLASS
// LinuxCNC 2.10 (master) replaced 2.9's ::IniFile (read from a FILE at each
// lookup) by linuxcnc::IniFile: read from a path once, and kept by that path
// for the whole process, never read again. So each text goes into a file of
// a name this process never used before and nobody can plant beforehand
// (mkostemps' random part; pid and counter say whose it is), owner-only,
// which the reader reads once; then the file is removed.
std::shared_ptr<const linuxcnc::IniFile> read_with_linuxcnc(const std::string& text,
                                                           std::string& error) {
  static std::atomic<unsigned long> count{0};
  const auto folder = scratch_root(PATH_MAX, error);
  if (!folder) return nullptr;
  std::string path = *folder + "/fixed_atc_probe-ini-" + std::to_string(::getpid()) + "-" +
                     std::to_string(++count) + "-XXXXXX.ini";
  const int fd = ::mkostemps(path.data(), 4, O_CLOEXEC);
  if (fd < 0) {
    error = "cannot make a private copy to read: " + path + ": " + std::strerror(errno);
    return nullptr;
  }
  const bool written = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  ::close(fd);
  std::shared_ptr<const linuxcnc::IniFile> reader;
  if (written) reader = std::make_shared<const linuxcnc::IniFile>(path);
  ::unlink(path.c_str());
  if (!written) error = "cannot make a private copy to read: " + path;
  return reader;
}

const linuxcnc::IniFile* reader_of(const std::shared_ptr<const void>& reader) {
  const auto* ini = static_cast<const linuxcnc::IniFile*>(reader.get());
  return ini != nullptr && ini->isOpen() ? ini : nullptr;
}
#endif

/// LinuxCNC's reader, with the protected lookup EmcIniFile::FindLinearUnits uses.
#if FATC_LINUXCNC_INI_CLASS
class LinuxCncIni {
 public:
#else
class LinuxCncIni : public ::IniFile {
 public:
  explicit LinuxCncIni(std::FILE* file) : ::IniFile(0, file) {}
  ErrorCode linear_units(double* result) {
    return Find(result, kLinearUnits, "LINEAR_UNITS", "TRAJ");
  }
#endif
  static bool is_unit_name(const std::string& text) {
    for (const StrDoublePair* unit = kLinearUnits; unit->pStr != nullptr; ++unit) {
      if (::strcasecmp(text.c_str(), unit->pStr) == 0) return true;
    }
    return false;
  }

 private:
  // The table of EmcIniFile::linearUnitsMap (emcIniFile.cc, LinuxCNC 2.9;
  // IniFile::mapLinearUnits in 2.10).
#if FATC_LINUXCNC_INI_CLASS
  struct StrDoublePair {
    const char* pStr;
    double value;
  };
#endif
  static inline StrDoublePair kLinearUnits[] = {
      {"mm", 1.0},        {"metric", 1.0},        {"in", 1 / 25.4},
      {"inch", 1 / 25.4}, {"imperial", 1 / 25.4}, {nullptr, 0.0}};
};

/// A file holding `text` that nobody else can change: an anonymous memfd,
/// or an unlinked temporary file where memfds are not allowed.
std::FILE* private_copy(const std::string& text) {
  int fd = ::memfd_create("fixed_atc_probe.ini", MFD_CLOEXEC);
  std::FILE* file = fd >= 0 ? ::fdopen(fd, "w+") : std::tmpfile();
  if (file == nullptr) {
    if (fd >= 0) ::close(fd);
    return nullptr;
  }
  if (std::fwrite(text.data(), 1, text.size(), file) != text.size() || std::fflush(file) != 0) {
    std::fclose(file);
    return nullptr;
  }
  std::rewind(file);
  return file;
}

/// Where a carriage return is not part of a line ending: LinuxCNC refuses the
/// whole file then ("ambiguous carriage returns") and every key reads as missing.
std::string lone_carriage_return(const std::string& text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] != '\n') {
      return describe(position_of(text, i)) +
             ": expected a line ending, found a carriage return inside a line (LinuxCNC refuses "
             "the file)";
    }
  }
  return "";
}

/// The largest limit that means something: LinuxCNC's own "no limit" default.
constexpr double kNoLimit = 1e99;

}  // namespace


std::optional<IniFile> IniFile::read(const std::string& path, std::string& error) {
  const auto text = read_small_file(path, error);
  if (!text) return std::nullopt;
  const std::string name = shown_path(path);
  // The script works in the INI's folder: a relative name is from there.
  const ExpandedIni expanded = expand_includes(
      *text, name, folder_of(path),
      [](const std::string& file, std::string& why) { return read_small_file(file, why); });
  if (expanded.too_big) {
    error = name + ": over " + std::to_string(kMaxFileBytes / (1024 * 1024)) +
            " MiB with the files its #INCLUDE lines name";
    return std::nullopt;
  }
  auto ini = from_text(expanded.text, name, error);
  if (!ini) return std::nullopt;
  ini->files_ = expanded.files;
  ini->origins_ = expanded.origins;
  ini->include_problems_ = expanded.problems;
  return ini;
}

std::string IniFile::line_name(int line) const {
  if (line < 1 || static_cast<std::size_t>(line) > origins_.size()) {
    return "line " + std::to_string(line);
  }
  const ExpandedIni::Origin& origin = origins_[static_cast<std::size_t>(line) - 1];
  return "line " + std::to_string(origin.line) +
         (origin.file == 0 ? std::string() : " of " + files_[origin.file]);
}

std::optional<IniFile> IniFile::from_text(const std::string& text, const std::string& name,
                                          std::string& error) {
  for (const std::string& problem : {nul_byte_problem(text), lone_carriage_return(text)}) {
    if (!problem.empty()) {
      error = name + ": " + problem;
      return std::nullopt;
    }
  }
  std::FILE* file = private_copy(text);
  if (file == nullptr) {
    error = name + ": cannot make a private copy to read (" + std::strerror(errno) + ")";
    return std::nullopt;
  }
  IniFile ini;
  ini.path_ = name;
  ini.text_ = text;
  ini.file_.reset(file, [](std::FILE* f) { std::fclose(f); });
#if FATC_LINUXCNC_INI_CLASS
  ini.reader_ = read_with_linuxcnc(text, error);
  if (ini.reader_ == nullptr) {
    error = name + ": " + error;
    return std::nullopt;
  }
#endif
  return ini;
}

std::optional<std::string> IniFile::get(const std::string& section, const std::string& key,
                                        int& line) const {
  line = 0;
#if FATC_LINUXCNC_INI_CLASS
  const auto* reader = reader_of(reader_);
  if (reader == nullptr) return std::nullopt;
  auto value = reader->findString(1, key, section);
  if (value) line = std::max(0, reader->lineOf(1, key, section).second);
  return value;
#else
  LinuxCncIni reader(file_.get());
  if (!reader.IsOpen()) return std::nullopt;
  const char* value = reader.Find(key.c_str(), section.c_str(), 1, &line);
  if (value == nullptr) {
    line = 0;
    return std::nullopt;
  }
  return std::string(value);
#endif
}

std::optional<std::string> IniFile::get(const std::string& section, const std::string& key) const {
  int line = 0;
  return get(section, key, line);
}

std::vector<std::string> IniFile::get_all(const std::string& section,
                                          const std::string& key) const {
  std::vector<std::string> values;
#if FATC_LINUXCNC_INI_CLASS
  const auto* reader = reader_of(reader_);
  if (reader == nullptr) return values;
  for (int n = 1; n <= kMaxRepeatedKeys; ++n) {
    auto value = reader->findString(n, key, section);
    if (!value) break;
    values.push_back(std::move(*value));
  }
#else
  LinuxCncIni reader(file_.get());
  if (!reader.IsOpen()) return values;
  // LinuxCNC's reader numbers repeated keys from 1 and reads the file from its
  // start for each: a bound keeps a hostile INI from taking minutes.
  for (int n = 1; n <= kMaxRepeatedKeys; ++n) {
    const char* value = reader.Find(key.c_str(), section.c_str(), n);
    if (value == nullptr) break;
    values.emplace_back(value);
  }
#endif
  return values;
}

std::optional<double> IniFile::number(const std::string& section, const std::string& key) const {
#if FATC_LINUXCNC_INI_CLASS
  // 2.10 reads a number with strtod: trailing characters only warned about.
  const auto* reader = reader_of(reader_);
  if (reader == nullptr) return std::nullopt;
  return reader->findReal(1, key, section);
#else
  LinuxCncIni reader(file_.get());
  double value = 0.0;
  if (reader.Find(&value, key.c_str(), section.c_str()) != ::IniFile::ERR_NONE) return std::nullopt;
  return value;
#endif
}

std::optional<double> IniFile::linear_units() const {
#if FATC_LINUXCNC_INI_CLASS
  // 2.10 takes a unit's name only (IniFile::findLinearUnits), no number.
  const auto* reader = reader_of(reader_);
  if (reader == nullptr) return std::nullopt;
  return reader->findLinearUnits(1, "LINEAR_UNITS", "TRAJ");
#else
  LinuxCncIni reader(file_.get());
  double value = 0.0;
  if (reader.linear_units(&value) != ::IniFile::ERR_NONE) return std::nullopt;
  return value;
#endif
}

std::optional<SoftLimits> soft_limits(const IniFile& ini, Units units, std::string& error) {
  int line = 0;
  const auto unit_text = ini.get("TRAJ", "LINEAR_UNITS", line);
  const std::string unit_key = ini.path() + ": " + key_name(ini, "TRAJ", "LINEAR_UNITS", line);
  if (!unit_text) {
    error = unit_key + ": missing (LinuxCNC does not start without it: mm, inch, ...)";
    return std::nullopt;
  }
  // LinuxCNC takes a number of machine units per mm (sscanf: "1.0 mm" is 1)
  // or one of its unit names; anything else stops it.
  const auto per_mm = ini.linear_units();
  char* end = nullptr;
  std::strtod(unit_text->c_str(), &end);
  const bool clean_number = !unit_text->empty() && end != nullptr && *end == '\0';
  if (!per_mm || !(clean_number || LinuxCncIni::is_unit_name(*unit_text))) {
    error = unit_key + ": expected mm, metric, in, inch, imperial or machine units per mm, got " +
            quote(*unit_text);
    return std::nullopt;
  }
  if (!std::isfinite(*per_mm) || *per_mm < 0.001 || *per_mm > 1000.0) {
    error =
        unit_key + ": expected machine units per mm from 0.001 to 1000, got " + quote(*unit_text);
    return std::nullopt;
  }
  const double to_config = (units == Units::inch ? 1.0 / 25.4 : 1.0) / *per_mm;

  SoftLimits limits;
  AxisLimits* axes[] = {&limits.x, &limits.y, &limits.z};
  const char* names[] = {"AXIS_X", "AXIS_Y", "AXIS_Z"};
  for (int i = 0; i < 3; ++i) {
    double found[2] = {0.0, 0.0};
    int lines[2] = {0, 0};
    const char* keys[] = {"MIN_LIMIT", "MAX_LIMIT"};
    for (int k = 0; k < 2; ++k) {
      const auto text = ini.get(names[i], keys[k], lines[k]);
      const std::string where = ini.path() + ": " + key_name(ini, names[i], keys[k], lines[k]);
      if (!text) {
        error = where + ": missing or empty (LinuxCNC would take no limit there)";
        return std::nullopt;
      }
      const auto value = ini.number(names[i], keys[k]);
      if (!value) {
        error = where + ": expected a number, got " + quote(*text);
        return std::nullopt;
      }
      if (!std::isfinite(*value) || std::fabs(*value) > kNoLimit) {
        error = where + ": expected a finite number from -1e99 to 1e99, got " + quote(*text);
        return std::nullopt;
      }
      found[k] = *value;
    }
    if (found[0] > found[1]) {
      error = ini.path() + ": " + key_name(ini, names[i], "MIN_LIMIT", lines[0]) +
              ": must not be above MAX_LIMIT (" + escape(*ini.get(names[i], "MAX_LIMIT")) +
              "), got " + escape(*ini.get(names[i], "MIN_LIMIT"));
      return std::nullopt;
    }
    axes[i]->min = found[0] * to_config;
    axes[i]->max = found[1] * to_config;
  }
  return limits;
}

std::optional<MotionLimits> motion_limits(const IniFile& ini, Units units, std::string& error) {
  const auto per_mm = ini.linear_units();
  if (!per_mm || !std::isfinite(*per_mm) || *per_mm <= 0.0) {
    error = ini.path() + ": [TRAJ]LINEAR_UNITS: expected mm, inch or machine units per mm";
    return std::nullopt;
  }
  const double to_config = (units == Units::inch ? 1.0 / 25.4 : 1.0) / *per_mm;
  // One value: a positive finite number, in the config's units; `required`
  // false: a missing one is no limit.
  auto value = [&](const char* section, const char* key, bool required) -> std::optional<double> {
    int line = 0;
    const auto text = ini.get(section, key, line);
    const std::string where = ini.path() + ": " + key_name(ini, section, key, line);
    if (!text) {
      if (!required) return std::numeric_limits<double>::infinity();
      error = where + ": missing (the bound needs every axis' velocity and acceleration)";
      return std::nullopt;
    }
    const auto number = ini.number(section, key);
    // Below a millionth of a unit a second no machine moves: a typing mistake.
    if (!number || !std::isfinite(*number) || !(*number * to_config >= 1e-6) ||
        !std::isfinite(*number * to_config)) {
      error = where + ": expected a positive number (at least 1e-6), got " + quote(*text);
      return std::nullopt;
    }
    return *number * to_config;
  };
  MotionLimits limits;
  double* velocity[] = {&limits.velocity.x, &limits.velocity.y, &limits.velocity.z};
  double* acceleration[] = {&limits.acceleration.x, &limits.acceleration.y, &limits.acceleration.z};
  const char* names[] = {"AXIS_X", "AXIS_Y", "AXIS_Z"};
  for (int i = 0; i < 3; ++i) {
    const auto v = value(names[i], "MAX_VELOCITY", true);
    const auto a = v ? value(names[i], "MAX_ACCELERATION", true) : std::nullopt;
    if (!a) return std::nullopt;
    *velocity[i] = *v;
    *acceleration[i] = *a;
  }
  const auto linear_velocity = value("TRAJ", "MAX_LINEAR_VELOCITY", false);
  const auto linear_acceleration =
      linear_velocity ? value("TRAJ", "MAX_LINEAR_ACCELERATION", false) : std::nullopt;
  if (!linear_acceleration) return std::nullopt;
  limits.linear_velocity = *linear_velocity;
  limits.linear_acceleration = *linear_acceleration;
  return limits;
}

std::string key_name(const IniFile& ini, const std::string& section, const std::string& key,
                     int line) {
  return "[" + section + "]" + key + (line > 0 ? " (" + ini.line_name(line) + ")" : "");
}

}  // namespace fatc::io
