// fixed_atc_probe: a fixed-rack tool changer for LinuxCNC.
#include <iostream>
#include <string>
#include <vector>

#include "io/cli.hpp"

int main(int argc, char** argv) {
  std::string error;
  const auto options = fatc::io::parse_options(std::vector<std::string>(argv + 1, argv + argc), error);
  if (!options) {
    std::cerr << "fixed_atc_probe: " << error << "\n" << fatc::io::kUsage;
    return 2;
  }
  if (options->mode == fatc::io::Options::Mode::component) {
    std::cerr << "fixed_atc_probe: the HAL component mode is not built yet; use --check or --plan\n";
    return 2;
  }
  return fatc::io::run_tool_mode(*options, std::cout, std::cerr);
}
