// fixed_atc_probe: a fixed-rack tool changer for LinuxCNC, as a userspace HAL
// component (default), or a config checker and planner (--check, --plan, --dot).
#include <hal.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/config/quote.hpp"
#include "core/machine/changer.hpp"
#include "io/cli.hpp"
#include "io/files.hpp"
#include "io/ini.hpp"
#include "io/message_log.hpp"
#include "linuxcnc/component.hpp"
#include "linuxcnc/hal_pins.hpp"
#include "linuxcnc/nml_link.hpp"

namespace {

volatile std::sig_atomic_t stop_requested = 0;

void request_stop(int) { stop_requested = 1; }

int fail(const std::string& message) {
  std::cerr << "fixed_atc_probe: " << message << std::endl;
  return 1;
}

int run_component(const fatc::io::Options& options) {
  if (const std::string refused = fatc::io::written_onto_input(options); !refused.empty()) {
    return fail(refused);
  }
  const std::string state_path =
      options.state_path.empty() ? options.config_path + ".state" : options.state_path;
  // Every line on stderr from here on also goes to STATE.log.
  fatc::io::MessageLog log(state_path + ".log", std::cerr.rdbuf());
  struct Restore {
    std::streambuf* before;
    ~Restore() { std::cerr.rdbuf(before); }
  } restore{std::cerr.rdbuf(&log)};
  log.note("fixed_atc_probe: started with " + options.config_path);
  const auto loaded = fatc::io::load_config_file(options.config_path);
  if (!loaded.config) {
    for (const auto& error : loaded.errors) std::cerr << "fixed_atc_probe: " << error << "\n";
    return 1;
  }
  const fatc::Config config = *loaded.config;
  const auto tools = fatc::io::load_state_file(state_path, config);
  if (!tools.state) return fail(tools.error);
  if (::access(state_path.c_str(), F_OK) != 0) {
    // A first start writes what it assumes (every pocket full, the spindle
    // empty) at once: panels can show it, and an unwritable path fails now.
    try {
      fatc::io::save_state_file(state_path, *tools.state, fatc::io::kComponentWait);
    } catch (const std::exception& e) {
      return fail(e.what());
    }
  }

  // Under LinuxCNC (INI_FILE_NAME set) the status channel must open; under a
  // bare halrun there is none: aborts are only seen on the abort pin and
  // messages only on stderr.
  // Its soft limits are the second check of every move, behind --check.
  std::unique_ptr<fatc::linuxcnc::NmlLink> nml;
  std::optional<fatc::SoftLimits> limits;
  if (const char* ini_path = std::getenv("INI_FILE_NAME")) {
    std::string error;
    const auto ini = fatc::io::IniFile::read(ini_path, error);
    if (!ini) return fail(error);
    limits = fatc::io::soft_limits(*ini, config.units, error);
    if (!limits) return fail(error);
    nml = fatc::linuxcnc::NmlLink::open(fatc::linuxcnc::nml_file_of(ini_path), error);
    if (!nml) return fail(error);
  }

  int id = -1;
  fatc::linuxcnc::HalPins* pins = nullptr;
  try {
    std::vector<int> pockets;
    for (const auto& pocket : config.pockets) pockets.push_back(pocket.first);
    pins = fatc::linuxcnc::create_pins("fixed_atc_probe", id, pockets);
  } catch (const std::exception& e) {
    if (id >= 0) hal_exit(id);
    return fail(e.what());
  }
  std::signal(SIGTERM, request_stop);
  std::signal(SIGINT, request_stop);

  fatc::linuxcnc::Component component(pins, config, options.config_path, state_path, nml.get());
  component.soft_limits(limits);
  fatc::Changer changer(config, component, *tools.state);
  changer.soft_limits(limits);
  component.attach(&changer);
  auto interpreter_idle = [&]() -> std::optional<bool> {
    if (!nml || !nml->poll()) return std::nullopt;
    return nml->interpreter_idle();
  };
  component.poll(std::chrono::steady_clock::now(), interpreter_idle());
  hal_ready(id);

  try {
    while (!stop_requested) {
      component.poll(std::chrono::steady_clock::now(), interpreter_idle());
      // Quick turns while a handshake is open; otherwise sleep, don't spin.
      std::this_thread::sleep_for(std::chrono::milliseconds(component.active() ? 1 : 20));
    }
  } catch (const std::exception& e) {
    std::cerr << "fixed_atc_probe: " << e.what() << std::endl;
    hal_exit(id);
    return 1;
  }
  hal_exit(id);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string error;
  const auto options =
      fatc::io::parse_options(std::vector<std::string>(argv + 1, argv + argc), error);
  if (!options) {
    // One line: the mistake stays in sight, the usage is a --help away.
    std::cerr << "fixed_atc_probe: " << fatc::capped_lines(error) << " (see --help)\n";
    return 2;
  }
  if (options->mode == fatc::io::Options::Mode::component) return run_component(*options);
  return fatc::io::run_tool_mode(*options, std::cout, std::cerr);
}
