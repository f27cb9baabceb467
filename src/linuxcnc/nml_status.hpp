#pragma once

#include <memory>
#include <optional>
#include <string>

namespace fatc::linuxcnc {

/// LinuxCNC's status channel (NML), read-only: whether the interpreter is
/// idle, which is how the component learns that a program was aborted.
class NmlStatus {
 public:
  /// Connects to emcStatus through `nml_file`; nullptr and `error` on failure.
  static std::unique_ptr<NmlStatus> open(const std::string& nml_file, std::string& error);
  ~NmlStatus();

  /// Reads the newest status; false when the channel fails.
  bool poll();
  bool interpreter_idle() const { return interpreter_idle_; }

 private:
  struct Channel;
  explicit NmlStatus(std::unique_ptr<Channel> channel);
  std::unique_ptr<Channel> channel_;
  bool interpreter_idle_ = true;
};

/// The NML file LinuxCNC uses: [EMC]NML_FILE of the INI, or the default.
std::string nml_file_of(const std::string& ini_path);

}  // namespace fatc::linuxcnc
