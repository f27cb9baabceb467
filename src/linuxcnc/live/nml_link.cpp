#include "nml_link.hpp"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <emc.hh>
#include <emc_nml.hh>
#include <emcglb.h>
#include <rcs_print.hh>
#include <stat_msg.hh>
#include <thread>

#include "linuxcnc/offline/ini.hpp"

namespace fatc::linuxcnc {
namespace {
// LinuxCNC 2.10 made task's enums enum classes, with the same values.
#if FATC_LINUXCNC_SERIES >= 210
constexpr auto kInterpIdle = EMC_TASK_INTERP::IDLE;
constexpr auto kModeMdi = EMC_TASK_MODE::MDI;
constexpr auto kModeAuto = EMC_TASK_MODE::AUTO;
#else
constexpr auto kInterpIdle = EMC_TASK_INTERP_IDLE;
constexpr auto kModeMdi = EMC_TASK_MODE_MDI;
constexpr auto kModeAuto = EMC_TASK_MODE_AUTO;
#endif
}  // namespace

struct NmlLink::Channels {
  std::unique_ptr<RCS_STAT_CHANNEL> status;
  std::unique_ptr<RCS_CMD_CHANNEL> command;
};

std::unique_ptr<NmlLink> NmlLink::open(const std::string& nml_file, std::string& error) {
  // NML prints its own diagnostics; our one line says what failed.
  set_rcs_print_destination(RCS_PRINT_TO_NULL);
  auto channels = std::make_unique<Channels>();
  channels->status =
      std::make_unique<RCS_STAT_CHANNEL>(emcFormat, "emcStatus", "xemc", nml_file.c_str());
  channels->command =
      std::make_unique<RCS_CMD_CHANNEL>(emcFormat, "emcCommand", "xemc", nml_file.c_str());
  if (!channels->status->valid() || !channels->command->valid()) {
    error = "cannot reach LinuxCNC through " + nml_file + ": is LinuxCNC running?";
    return nullptr;
  }
  auto link = std::unique_ptr<NmlLink>(new NmlLink(std::move(channels)));
  link->poll();
  return link;
}

NmlLink::NmlLink(std::unique_ptr<Channels> channels) : channels_(std::move(channels)) {}
NmlLink::~NmlLink() = default;

bool NmlLink::poll() {
  // Checked again after the peek: a peek that timed out on the lock (10 s)
  // leaves the channel invalid, and what it read before is stale.
  if (channels_->status->valid()) {
    if (channels_->status->peek() == EMC_STAT_TYPE) {
      const auto* stat = static_cast<EMC_STAT*>(channels_->status->get_address());
      interpreter_idle_ = stat->task.interpState == kInterpIdle;
      // linearUnits: machine units per mm.
      const double per_mm = stat->motion.traj.linearUnits > 0 ? stat->motion.traj.linearUnits : 1.0;
      const EmcPose& at = stat->motion.traj.actualPosition;
      position_mm_ = Point{at.tran.x / per_mm, at.tran.y / per_mm, at.tran.z / per_mm};
      units_per_mm_ = per_mm;
      spindle_tool_ = stat->io.tool.toolInSpindle;
      spindle_tool_length_ = spindle_tool_ > 0 ? stat->io.tool.toolTableCurrent.offset.tran.z : 0.0;
      task_mode_ = static_cast<int>(stat->task.mode);
      motion_line_ = stat->task.motionLine;
      program_.assign(stat->task.file, strnlen(stat->task.file, sizeof stat->task.file));
      serial_ = std::max(serial_, stat->echo_serial_number);
    }
    if (channels_->status->valid()) return true;
  }
  if (!lost_said_) std::fprintf(stderr, "fixed_atc_probe: %s\n", kStatusLost.data());
  lost_said_ = true;
  position_mm_.reset();
  return false;
}

std::string NmlLink::what_moves() const {
  if (task_mode_ == static_cast<int>(kModeAuto)) return "program line " + std::to_string(motion_line_);
  if (task_mode_ == static_cast<int>(kModeMdi)) return "an MDI command";
  return "a jog";
}

void NmlLink::tell(MessageKind kind, const std::string& text) {
  // An operator message holds 255 characters: a longer one goes out in parts,
  // cut at a space, so that the GUI shows all of it.
  std::string rest = "fixed_atc_probe: " + text;
  while (!rest.empty()) {
    std::size_t cut = rest.size();
    if (cut > kMessagePart) {
      cut = rest.rfind(' ', kMessagePart);
      if (cut == std::string::npos || cut == 0) cut = kMessagePart;
    }
    send(kind, rest.substr(0, cut));
    rest.erase(0, cut);
    const std::size_t start = rest.find_first_not_of(' ');
    rest = start == std::string::npos ? std::string() : "... " + rest.substr(start);
  }
}

void NmlLink::send(MessageKind kind, const std::string& line) {
  if (kind == MessageKind::error) {
    EMC_OPERATOR_ERROR message;
    std::strncpy(message.error, line.c_str(), sizeof message.error - 1);
    message.error[sizeof message.error - 1] = '\0';
    write_received(message);
  } else {
    EMC_OPERATOR_DISPLAY message;
    std::strncpy(message.display, line.c_str(), sizeof message.display - 1);
    message.display[sizeof message.display - 1] = '\0';
    write_received(message);
  }
}

bool NmlLink::write_received(RCS_CMD_MSG& message) {
  // Task's command buffer holds one command: a second write before task read
  // the first replaces it (a mode change lost, then "can't do that in AUTO
  // mode"). So wait until task echoes this serial, as LinuxCNC's own shcom
  // does, but briefly: the component's loop keeps the chuck guard's heartbeat.
  // Each client counts its own serials: where task's echo already holds the
  // next one (a GUI's command), it would read as taken before task saw this
  // one, and the command after it would replace it unseen; so skip that one.
  message.serial_number = ++serial_;
  if (echo_serial() == message.serial_number) message.serial_number = ++serial_;
  if (channels_->command->write(&message) != 0) return false;
  const auto until = std::chrono::steady_clock::now() + kReceiveTimeout;
  do {
    if (echo_serial() == message.serial_number) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  } while (std::chrono::steady_clock::now() < until);
  return false;
}

std::optional<int> NmlLink::echo_serial() {
  if (channels_->status->peek() != EMC_STAT_TYPE) return std::nullopt;
  return static_cast<EMC_STAT*>(channels_->status->get_address())->echo_serial_number;
}

bool NmlLink::run_mdi(const std::string& line) {
  EMC_TASK_SET_MODE mode;
  mode.mode = kModeMdi;
  if (!write_received(mode)) return false;
  EMC_TASK_PLAN_EXECUTE execute;
  std::strncpy(execute.command, line.c_str(), sizeof execute.command - 1);
  execute.command[sizeof execute.command - 1] = '\0';
  return write_received(execute);
}

bool NmlLink::load_tool_table() {
  EMC_TOOL_LOAD_TOOL_TABLE load;
  load.file[0] = '\0';  // iocontrol's own file, the one the INI names
  return write_received(load);
}

void NmlLink::abort() {
  EMC_TASK_ABORT abort;
  write_received(abort);
}

std::string nml_file_of(const std::string& ini_path) {
  std::string error;
  const auto ini = io::IniFile::read(ini_path, error);
  if (ini) {
    if (const auto file = ini->get("EMC", "NML_FILE")) return *file;
  }
  // LinuxCNC's own default, compiled into the liblinuxcnc.a linked here:
  // /usr/share/linuxcnc/linuxcnc.nml for Debian's package, a run-in-place
  // tree's configs/common/linuxcnc.nml for one built from source.
  return emc_nmlfile;
}

}  // namespace fatc::linuxcnc
