#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>

#include "core/dry_run/dry_run.hpp"
#include "core/machine/changer.hpp"
#include "io/files.hpp"

namespace fatc::linuxcnc {

class NmlLink;

/// The tool lengths the keep-out counts, from LinuxCNC's tool table: the
/// file the INI names ([EMCIO]TOOL_TABLE), read again whenever LinuxCNC
/// rewrites it (G10 L1, a GUI's tool page), and the spindle tool's Z from
/// task's status (its memory, fresher than the file). A tool whose Z is no
/// length below the nose counts as its measured length or the longest tool
/// the config allows (ToolLengths::of), and the operator is told so once.
/// The changer gets them for its own moves and its rehearsals; the realtime
/// guard gets the spindle tool's.
class KeepoutLengths {
 public:
  /// `table_path`: none where the INI names no tool table file (a tool
  /// database): only the spindle tool's length is then known.
  explicit KeepoutLengths(std::optional<std::string> table_path) : path_(std::move(table_path)) {}
  KeepoutLengths(const KeepoutLengths&) = delete;
  KeepoutLengths& operator=(const KeepoutLengths&) = delete;

  /// The running machine's soft limits, which the rehearsals and `longest` plan within.
  void soft_limits(std::optional<SoftLimits> limits);
  /// Reads what changed, gives the changer its lengths and rehearsal, and
  /// says once per tool what the spindle tool counts as where it is not the table's.
  void poll(Changer& changer, const NmlLink* nml, Ports& ports);
  /// The spindle tool's length as the keep-out counts it, in the config's units.
  double spindle_length() const { return spindle_length_; }

 private:
  void read_table(const Config& config, double per_mm);

  std::optional<std::string> path_;
  std::optional<SoftLimits> limits_;
  DryRun dry_run_;
  bool rehearsing_ = false;
  std::optional<io::FileStamp> table_read_;  ///< the file's stamp when last read
  std::optional<unsigned> configs_taken_;    ///< the config `longest` is of
  ToolLengths lengths_;                      ///< in the config's units
  std::optional<ToolLengths> given_;         ///< what the changer has
  double spindle_length_ = 0.0;
  std::set<int> told_;
};

}  // namespace fatc::linuxcnc
