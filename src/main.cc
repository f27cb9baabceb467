// fixed_atc_probe: a fixed-rack tool changer for LinuxCNC, as a userspace HAL
// component (default), or a config checker and planner (--check, --plan, --dot),
// or its operator without a GUI (--operator).
#include <hal.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cli/cli.hpp"
#include "cli/operator_command.hpp"
#include "cli/parse_options.hpp"
#include "core/config/quote.hpp"
#include "core/machine/changer.hpp"
#include "io/files.hpp"
#include "io/interruption.hpp"
#include "io/message_log.hpp"
#include "io/standard_output.hpp"
#include "io/version.hpp"
#include "linuxcnc/live/component.hpp"
#include "linuxcnc/live/hal_pins.hpp"
#include "linuxcnc/live/nml_link.hpp"
#include "linuxcnc/offline/ini.hpp"

namespace {

/// The last resort behind main's own catch: what escapes it - a throw while
/// the program starts, before main (the memory left by a low `ulimit -v`),
/// or out of a noexcept function - ends on one line and exit 2, never on
/// abort()'s signal.
[[noreturn]] void one_line_terminate() {
  const char* what = "stopped on an error it did not expect";
  try {
    if (const auto thrown = std::current_exception()) std::rethrow_exception(thrown);
  } catch (const std::bad_alloc&) {
    what = "out of memory";
  } catch (const std::exception& e) {
    what = e.what();
  } catch (...) {
  }
  std::fputs("fixed_atc_probe: ", stderr);
  std::fputs(what, stderr);
  std::fputs("\n", stderr);
  std::_Exit(2);
}

/// Before every other initializer of the program (101: the first priority
/// after the implementation's own).
__attribute__((constructor(101))) void install_terminate() {
  std::set_terminate(one_line_terminate);
}

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
  const auto loaded = fatc::io::load_config_file(options.config_path);
  if (!loaded.config) {
    for (const auto& error : loaded.errors) std::cerr << "fixed_atc_probe: " << error << "\n";
    return 1;
  }
  const fatc::Config config = *loaded.config;
  const auto tools = fatc::io::load_state_file(state_path, config);
  if (!tools.state) return fail(tools.error);
  // Which build runs and on what, in the terminal LinuxCNC was started from
  // (docs/setup.md step 8) and STATE.log; after the inputs are read, so that
  // a bad one stays the one line it is.
  std::cerr << "fixed_atc_probe: info: " << fatc::io::version() << " started with "
            << options.config_path << ", state " << state_path << std::endl;
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
  std::optional<std::string> tool_table;
  if (const char* ini_path = std::getenv("INI_FILE_NAME")) {
    std::string error;
    const auto ini = fatc::io::IniFile::read(ini_path, error);
    if (!ini) return fail(error);
    if (const auto table = ini->get("EMCIO", "TOOL_TABLE")) {
      tool_table = fatc::io::beside(ini_path, *table);
    }
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
  // Whatever signal a terminal session ends it with, it leaves HAL first; one
  // ignored when it started (nohup's SIGHUP) stays ignored.
  for (const int signal : fatc::io::kEndingSignals) {
    if (std::signal(signal, request_stop) == SIG_IGN) std::signal(signal, SIG_IGN);
  }

  // From here on, whatever fails leaves HAL as it found it.
  try {
    fatc::linuxcnc::Component component(pins, config, options.config_path, state_path, nml.get(),
                                        tool_table);
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
    while (!stop_requested) {
      component.poll(std::chrono::steady_clock::now(), interpreter_idle());
      // Quick turns while a handshake is open; otherwise sleep, don't spin.
      std::this_thread::sleep_for(std::chrono::milliseconds(component.active() ? 1 : 20));
    }
  } catch (const std::bad_alloc&) {
    hal_exit(id);
    return fail("out of memory");
  } catch (const std::exception& e) {
    hal_exit(id);
    return fail(e.what());
  }
  hal_exit(id);
  return 0;
}

/// Runs a mode that prints, its standard output through StandardOutput: a
/// write that fails (a full disk, > /dev/full, a closed pipe) is kept, said
/// once at the end, and ends it with exit 2, whatever the mode returned.
template <class Mode>
int printing(Mode mode) {
  fatc::io::StandardOutput written(STDOUT_FILENO);
  std::ostream out(&written);
  const int code = mode(out);
  out.flush();
  if (written.error() != 0) {
    std::cerr << "fixed_atc_probe: cannot write to standard output ("
              << std::strerror(written.error()) << "): what it printed is lost" << std::endl;
    return 2;
  }
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  // Every mode ends in one line, whatever fails (memory included): never on
  // std::terminate's abort.
  try {
    std::string error;
    const auto options =
        fatc::io::parse_options(std::vector<std::string>(argv + 1, argv + argc), error);
    if (!options) {
      // One line: the mistake stays in sight, the usage is a --help away.
      std::cerr << "fixed_atc_probe: " << fatc::capped_lines(error) << " (see --help)\n";
      return 2;
    }
    if (options->mode == fatc::io::Options::Mode::component) return run_component(*options);
    if (options->mode == fatc::io::Options::Mode::operator_request) {
      // A terminal session's signal (a dropped SSH session's SIGHUP, Ctrl-C, a
      // closed pipe ...) stops the waiting: it leaves HAL, then ends by that signal.
      const fatc::io::Interruptible interruptible;
      return printing([&](std::ostream& out) {
        return fatc::linuxcnc::run_operator(fatc::io::with_state_of_ini(*options), out, std::cerr);
      });
    }
    return printing([&](std::ostream& out) {
      if (options->mode != fatc::io::Options::Mode::version) {
        return fatc::io::run_tool_mode(*options, out, std::cerr);
      }
      out << "fixed_atc_probe " << fatc::io::version() << "\n";
      return 0;
    });
  } catch (const std::bad_alloc&) {
    std::cerr << "fixed_atc_probe: out of memory" << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "fixed_atc_probe: " << fatc::capped_lines(e.what()) << std::endl;
  }
  return 2;
}
