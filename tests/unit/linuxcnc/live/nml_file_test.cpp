// The LinuxCNC adapters against the LinuxCNC they were built for: Debian's
// linuxcnc-uspace, or a run-in-place tree built from source (LINUXCNC_ROOT,
// scripts/test_on_linuxcnc.sh), whose files are elsewhere.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "linuxcnc/live/nml_link.hpp"
#include "temp_folder.hpp"

namespace fatc::linuxcnc {
namespace {

using NmlFile = test::TempFolder;

// Without [EMC]NML_FILE the component talks to LinuxCNC through the NML file
// LinuxCNC itself uses then: Debian's in /usr/share, a run-in-place tree's in
// its configs/common (the NML file of another LinuxCNC may not be there, or
// may name other buffers).
TEST_F(NmlFile, DefaultIsTheLinuxCncBuiltAgainst) {
  const std::string ini = folder_ + "/machine.ini";
  std::ofstream(ini) << "[EMC]\nMACHINE = test\n";
#ifdef FATC_LINUXCNC_ROOT
  EXPECT_EQ(nml_file_of(ini), std::string(FATC_LINUXCNC_ROOT) + "/configs/common/linuxcnc.nml");
#else
  EXPECT_EQ(nml_file_of(ini), "/usr/share/linuxcnc/linuxcnc.nml");
#endif
  EXPECT_EQ(::access(nml_file_of(ini).c_str(), R_OK), 0) << nml_file_of(ini);
}

TEST_F(NmlFile, TheInisWins) {
  const std::string ini = folder_ + "/machine.ini";
  std::ofstream(ini) << "[EMC]\nNML_FILE = /etc/my.nml\n";
  EXPECT_EQ(nml_file_of(ini), "/etc/my.nml");
}

}  // namespace
}  // namespace fatc::linuxcnc
