#include "nml_status.hpp"

#include <emc.hh>
#include <emc_nml.hh>
#include <rcs_print.hh>
#include <stat_msg.hh>

#include "io/ini.hpp"

namespace fatc::linuxcnc {

struct NmlStatus::Channel {
  std::unique_ptr<RCS_STAT_CHANNEL> stat;
};

std::unique_ptr<NmlStatus> NmlStatus::open(const std::string& nml_file, std::string& error) {
  // NML prints its own diagnostics; our one line says what failed.
  set_rcs_print_destination(RCS_PRINT_TO_NULL);
  auto channel = std::make_unique<Channel>();
  channel->stat = std::make_unique<RCS_STAT_CHANNEL>(emcFormat, "emcStatus", "xemc", nml_file.c_str());
  if (!channel->stat->valid()) {
    error = "cannot read LinuxCNC's status through " + nml_file + ": is LinuxCNC running?";
    return nullptr;
  }
  auto status = std::unique_ptr<NmlStatus>(new NmlStatus(std::move(channel)));
  status->poll();
  return status;
}

NmlStatus::NmlStatus(std::unique_ptr<Channel> channel) : channel_(std::move(channel)) {}
NmlStatus::~NmlStatus() = default;

bool NmlStatus::poll() {
  if (!channel_->stat->valid()) return false;
  if (channel_->stat->peek() == EMC_STAT_TYPE) {
    const auto* stat = static_cast<EMC_STAT*>(channel_->stat->get_address());
    interpreter_idle_ = stat->task.interpState == EMC_TASK_INTERP_IDLE;
  }
  return true;
}

std::string nml_file_of(const std::string& ini_path) {
  std::string error;
  const auto ini = io::IniFile::read(ini_path, error);
  if (ini) {
    if (const auto file = ini->get("EMC", "NML_FILE")) return *file;
  }
  return "/usr/share/linuxcnc/linuxcnc.nml";
}

}  // namespace fatc::linuxcnc
