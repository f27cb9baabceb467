#pragma once

#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/rack/geometry.hpp"
#include "core/dry_run/timing.hpp"
#include "core/program/tool_use.hpp"

namespace fatc::io {

/// Reads the file an #INCLUDE names: its text, or nullopt and `error`.
using IncludeReader =
    std::function<std::optional<std::string>(const std::string& path, std::string& error)>;

/// An INI's text as the `linuxcnc` start script hands it to LinuxCNC
/// (handle_includes, the same in 2.9 and 2.10): unchanged unless a line
/// starts with #INCLUDE; then each line as bash's `read a b` and `echo "$a
/// $b"` give it back (spaces around the first word made one, backslashes
/// taken as escapes, a line ending in one joined with the next, a last line
/// without a line end dropped), and each #INCLUDE line replaced by the text
/// of the file it names as it is, between two marks; the name as `eval echo`
/// gives it (`~`, $NAME, ${NAME}), from the INI's `folder`. An included
/// file's own #INCLUDE lines are not expanded. Nothing is run.
struct ExpandedIni {
  std::string text;
  /// Shown names of the INI (first) and the files it includes.
  std::vector<std::string> files;
  /// Where each line of `text` came from (line n at [n - 1]): an index into
  /// `files` and the line there (0: a mark the script writes). Empty: `text`
  /// is the INI's own, line for line.
  struct Origin {
    std::size_t file = 0;
    int line = 0;
  };
  std::vector<Origin> origins;
  /// One each, at its file and line: an #INCLUDE that names no file, one that cannot be read,
  /// one the shell would have to evaluate, one the script does not expand,
  /// a line the script drops or joins with its mark.
  std::vector<program::Finding> problems;
  /// With the included files over kMaxFileBytes: nothing else is kept.
  bool too_big = false;
};
ExpandedIni expand_includes(const std::string& text, const std::string& name,
                            const std::string& folder, const IncludeReader& read);

/// A LinuxCNC INI file, read by LinuxCNC's own reader (IniFile of
/// liblinuxcncini): what get() finds is what LinuxCNC finds, first of
/// repeated keys, comments only at the start of a line, and so on.
class IniFile {
 public:
  /// nullopt and one line in `error` when the file cannot be read, is no
  /// regular file, is over 1 MiB (with the files it includes), or has a NUL
  /// byte or a lone carriage return. Its #INCLUDE lines are expanded as the
  /// `linuxcnc` script does (expand_includes): every reader of the user's INI
  /// sees what LinuxCNC will run with; include_problems() says what went wrong.
  static std::optional<IniFile> read(const std::string& path, std::string& error);
  /// The same from text already in memory, its #INCLUDE lines not expanded;
  /// `name` stands for the path in messages.
  static std::optional<IniFile> from_text(const std::string& text, const std::string& name,
                                          std::string& error);

  /// The text LinuxCNC reads: with the included files, as read() expanded it.
  const std::string& text() const { return text_; }
  /// ExpandedIni::problems.
  const std::vector<program::Finding>& include_problems() const { return include_problems_; }
  /// "line 12", or "line 3 of axes.inc" for a line of `text()` that an #INCLUDE brought in.
  std::string line_name(int line) const;

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
  std::string text_;
  std::vector<program::Finding> include_problems_;
  std::vector<std::string> files_;                 ///< ExpandedIni's
  std::vector<ExpandedIni::Origin> origins_;       ///< ExpandedIni's
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

/// "[AXIS_X]MIN_LIMIT (line 12)", or without the line when it is not there.
std::string key_name(const IniFile& ini, const std::string& section, const std::string& key,
                     int line);

}  // namespace fatc::io
