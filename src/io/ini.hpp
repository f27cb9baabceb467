#pragma once

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/rack/geometry.hpp"
#include "core/dry_run/timing.hpp"

namespace fatc::io {

/// A LinuxCNC INI file, read by LinuxCNC's own reader (IniFile of
/// liblinuxcncini): what get() finds is what LinuxCNC finds, first of
/// repeated keys, comments only at the start of a line, and so on.
class IniFile {
 public:
  /// nullopt and one line in `error` when the file cannot be read, is no
  /// regular file, is over 1 MiB, or has a NUL byte or a lone carriage return.
  static std::optional<IniFile> read(const std::string& path, std::string& error);
  /// The same from text already in memory; `name` stands for the path in messages.
  static std::optional<IniFile> from_text(const std::string& text, const std::string& name,
                                          std::string& error);

  std::optional<std::string> get(const std::string& section, const std::string& key) const;
  /// get(), and the line the key is on (0 when it is not there).
  std::optional<std::string> get(const std::string& section, const std::string& key,
                                 int& line) const;
  /// At most this many values of a repeated key are read.
  static constexpr int kMaxRepeatedKeys = 200;
  /// Every value of a key given more than once (REMAP), in the file's order.
  std::vector<std::string> get_all(const std::string& section, const std::string& key) const;
  /// `[SECTION]KEY` as LinuxCNC parses a number from it (boost::lexical_cast<double>,
  /// as its IniFile::Find<double>): nullopt when missing or not a number.
  std::optional<double> number(const std::string& section, const std::string& key) const;
  /// [TRAJ]LINEAR_UNITS as LinuxCNC reads it (EmcIniFile::FindLinearUnits: a
  /// number, or mm, metric, in, inch, imperial): machine units per mm.
  std::optional<double> linear_units() const;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::shared_ptr<std::FILE> file_;  ///< a private copy of the text (memfd), never changed
  /// LinuxCNC 2.10's reader (linuxcnc::IniFile) of the same text, read once at
  /// from_text; empty with 2.9's, which reads file_ at each lookup.
  std::shared_ptr<const void> reader_;
};

/// The soft limits of axes X, Y and Z ([AXIS_n] MIN_LIMIT/MAX_LIMIT), converted
/// from [TRAJ]LINEAR_UNITS into `units`. nullopt and one line in `error`
/// ("PATH: [AXIS_X]MIN_LIMIT (line 12): expected a number, got \"nan\"") when
/// any is missing, is no number to LinuxCNC, or makes no sense as a limit
/// (not finite, beyond 1e99, MIN above MAX, LINEAR_UNITS unknown).
std::optional<SoftLimits> soft_limits(const IniFile& ini, Units units, std::string& error);

/// The velocities and accelerations of axes X, Y and Z ([AXIS_n]
/// MAX_VELOCITY, MAX_ACCELERATION) and [TRAJ]MAX_LINEAR_VELOCITY and
/// MAX_LINEAR_ACCELERATION (each optional: no limit of its own), converted
/// into `units`. nullopt and one line in `error` when an axis value is
/// missing, or any is no positive finite number.
std::optional<MotionLimits> motion_limits(const IniFile& ini, Units units, std::string& error);

/// [FIXED_ATC_PROBE] as hal/fixed_atc_probe.hal and the NGC step executor
/// read it, one line per problem: every key there, the motion pin numbers two
/// digits as in the pin names, the analog outputs different, RETURN_TO_XY 0
/// or 1, STEP_TIMEOUT a number of seconds longer than every wait of `config`
/// (when given) between two steps, which the executor would take for a
/// component that stopped answering. Nothing when the INI has no key of the
/// section at all (an INI checked for its limits only).
std::vector<std::string> executor_problems(const IniFile& ini, const Config* config);

/// The user M-codes (100-199) LinuxCNC's task finds for the INI, as it looks
/// for them when it starts: an executable named M1nn in [DISPLAY]PROGRAM_PREFIX
/// (else nc_files) or in one of the first five folders of
/// [RS274NGC]USER_M_PATH (':' between, `~/` for $HOME), each from `folder`
/// (the INI's, where LinuxCNC runs).
std::vector<int> user_m_codes(const IniFile& ini, const std::string& folder);

}  // namespace fatc::io
