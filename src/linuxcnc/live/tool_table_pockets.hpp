#pragma once

#include <map>
#include <optional>
#include <string>

#include "core/machine/base/ports.hpp"
#include "core/rack/tool_state.hpp"
#include "io/files.hpp"

namespace fatc::linuxcnc {

class NmlLink;

/// The rack map in LinuxCNC's tool table (issue 34): each rack tool's pocket
/// in the P column of the file the INI names ([EMCIO]TOOL_TABLE), which
/// LinuxCNC is then told to read again, so that its memory holds the same P
/// and the next G10 L1, which saves that memory, keeps it. The file is read
/// and rewritten under the component's writer lock only while no flow runs
/// and task is free (no program, no MDI: nothing of LinuxCNC's writes the
/// file then), so a length LinuxCNC saved is in the text rewritten. The
/// changer's map wins: a P edited in a GUI is written back and the operator
/// told where the changer has the tool.
class ToolTablePockets {
 public:
  /// `path`: none where the INI names no tool table file (a tool database).
  explicit ToolTablePockets(std::optional<std::string> path) : path_(std::move(path)) {}

  /// Only while no flow runs and task is free: brings the file in line
  /// when the rack or the file changed since the last time.
  void poll(const ToolState& tools, NmlLink& nml, Ports& ports);

 private:
  std::optional<std::string> path_;
  std::optional<std::map<int, PocketState>>
      rack_;                                ///< the rack the file was last brought in line with
  std::optional<io::FileStamp> changed_;    ///< the file's stamp then
  std::map<int, std::optional<int>> left_;  ///< each tool's P as the file was left then
  bool reload_ = false;                     ///< written, LinuxCNC not yet told to read it
  bool failed_said_ = false;
};

}  // namespace fatc::linuxcnc
