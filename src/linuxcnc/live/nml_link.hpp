#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "core/machine/base/ports.hpp"

class RCS_CMD_MSG;

namespace fatc::linuxcnc {

/// Why nothing runs over NML once task's status stopped answering. Each NML
/// buffer's lock is a semaphore taken without undo: a reader that died
/// holding it (killed, crashed) leaves it taken, task blocks on every status
/// write, and only a restart of LinuxCNC frees it.
inline constexpr std::string_view kStatusLost =
    "LinuxCNC's status channel does not answer (its NML lock is held, by a program that died "
    "holding it, or LinuxCNC stopped): restart LinuxCNC";

/// LinuxCNC's NML channels: status (is the interpreter idle, which is how the
/// component learns that a program was aborted) and commands (operator
/// messages, which every GUI shows).
class NmlLink {
 public:
  /// Connects through `nml_file`; nullptr and `error` on failure.
  static std::unique_ptr<NmlLink> open(const std::string& nml_file, std::string& error);
  ~NmlLink();

  /// Reads the newest status; false when the channel fails, and then for
  /// good (kStatusLost, said once on stderr).
  bool poll();
  bool interpreter_idle() const { return interpreter_idle_; }
  /// Where the machine is (G53, actual position), in mm, as the newest status
  /// said; nothing before one was read or once the channel failed.
  std::optional<Point> machine_position_mm() const { return position_mm_; }
  /// Machine units per mm ([TRAJ]LINEAR_UNITS), once a status was read.
  std::optional<double> units_per_mm() const { return units_per_mm_; }
  /// LinuxCNC's tool in the spindle and its tool table length, machine units.
  int spindle_tool() const { return spindle_tool_; }
  double spindle_tool_length() const { return spindle_tool_length_; }
  /// What task runs motion from now, in words: "program line 12", "an MDI
  /// command", "a jog".
  std::string what_moves() const;
  /// The program loaded in LinuxCNC (task's file), empty if none.
  const std::string& loaded_program() const { return program_; }
  /// An operator message: errors as EMC_OPERATOR_ERROR, the rest as EMC_OPERATOR_DISPLAY.
  void tell(MessageKind kind, const std::string& text);
  /// Puts task in MDI mode and runs `line` there, as halui does for its MDI
  /// commands. False when task did not take the commands (the caller retries).
  bool run_mdi(const std::string& line);
  /// Makes LinuxCNC read its tool table file again ([EMCIO]TOOL_TABLE), as a
  /// GUI's tool editor does after it saved it. False when task did not take it.
  bool load_tool_table();
  /// Stops what task runs (program or MDI), as the GUI's Stop does.
  void abort();

 private:
  struct Channels;
  explicit NmlLink(std::unique_ptr<Channels> channels);
  void send(MessageKind kind, const std::string& line);
  /// Writes a command and waits (at most kReceiveTimeout) until task took it.
  bool write_received(RCS_CMD_MSG& message);
  /// The serial of the last command task took; none before its status came.
  std::optional<int> echo_serial();
  static constexpr std::chrono::milliseconds kReceiveTimeout{100};
  /// Characters of one operator message part (LinuxCNC's buffer holds 255).
  static constexpr std::size_t kMessagePart = 240;
  std::unique_ptr<Channels> channels_;
  bool interpreter_idle_ = true;
  std::optional<Point> position_mm_;
  std::optional<double> units_per_mm_;
  int spindle_tool_ = 0;
  double spindle_tool_length_ = 0.0;
  int task_mode_ = 0;
  int motion_line_ = 0;
  std::string program_;
  int serial_ = 0;
  bool lost_said_ = false;
};

/// The NML file LinuxCNC uses: [EMC]NML_FILE of the INI, or the default of
/// the LinuxCNC built against (Debian's package, or a run-in-place tree).
std::string nml_file_of(const std::string& ini_path);

}  // namespace fatc::linuxcnc
