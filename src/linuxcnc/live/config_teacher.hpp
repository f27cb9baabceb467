#pragma once

#include <functional>
#include <optional>
#include <vector>
#include <string>

#include "core/machine/changer.hpp"
#include "core/dry_run/teach.hpp"

namespace fatc::linuxcnc {

/// Teaching (teach-pocket, teach-loading, teach-safe, teach-sensor): the
/// machine position into config.json and into the changer. The changer takes
/// the new config first (only while idle) and the file is written after, so a
/// refusal writes nothing and a failed write is handed back.
class ConfigTeacher {
 public:
  /// Messages go to `ports` (the component's tell).
  ConfigTeacher(std::string config_path, Ports& ports)
      : config_path_(std::move(config_path)), ports_(ports) {}
  /// The machine's soft limits, which a taught position must respect.
  void soft_limits(std::optional<SoftLimits> limits) { limits_ = std::move(limits); }
  /// `linuxcnc_status`: LinuxCNC's status is read (NML); `at`: the machine
  /// position it gives (machine coordinates, config units).
  void teach(Changer& changer, const TeachTarget& target, bool linuxcnc_status,
             const std::optional<Point>& at);
  /// What touching found and the operator accepted (Ports::write_found): the
  /// pockets' positions, or the rack datum's (`datum`), all or nothing.
  void write_found(Changer& changer, const std::vector<Found>& found, bool datum);

 private:
  /// config.json as `make` changes its text, taken by the changer, then written.
  void write(Changer& changer, const std::string& request,
             const std::function<TeachResult(const std::string&)>& make);
  std::string config_path_;
  Ports& ports_;
  std::optional<SoftLimits> limits_;
};

}  // namespace fatc::linuxcnc
