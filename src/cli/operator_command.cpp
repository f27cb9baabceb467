#include "operator_command.hpp"

#include <hal.h>
#include <sys/ipc.h>
#include <sys/shm.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "core/formatted.hpp"
#include "io/capped_lines.hpp"
#include "io/files.hpp"
#include "io/interruption.hpp"
#include "linuxcnc/offline/ini.hpp"
#include "operator_watch.hpp"

namespace fatc::linuxcnc {
namespace {

using Clock = std::chrono::steady_clock;
using io::OperatorOutcome;

/// HAL's shared memory key (LinuxCNC's hal_priv.h, "HAL" and its version):
/// looked for before hal_init, which would otherwise make a HAL of its own
/// where none runs.
constexpr key_t kHalKey = 0x48414c32;
/// The panel's pulse (hal/fixed_atc_probe_panel.py): down this long, then up
/// as long before anything else, so the component's 20 ms poll sees each edge.
constexpr auto kPulse = std::chrono::milliseconds(100);
constexpr auto kPoll = std::chrono::milliseconds(20);
/// A request the component neither started nor answered by then was not seen.
constexpr auto kAnswerWithin = std::chrono::seconds(10);

/// A pin of the running fixed_atc_probe, found by HAL's own lookup: its value
/// where HAL keeps it, the pin's own or, when netted, its signal's.
struct ComponentPin {
  hal_type_t type = HAL_BIT;
  hal_data_u* data = nullptr;
  bool netted = false;
};

std::optional<ComponentPin> find(const std::string& name) {
  ComponentPin pin;
  if (hal_get_pin_value_by_name(("fixed_atc_probe." + name).c_str(), &pin.type, &pin.data,
                                &pin.netted) != 0) {
    return std::nullopt;
  }
  return pin;
}

int value_of(const ComponentPin& pin) { return pin.type == HAL_S32 ? pin.data->s : pin.data->b; }

void write(const ComponentPin& pin, int value) {
  if (pin.type == HAL_S32) {
    pin.data->s = value;
  } else {
    pin.data->b = value != 0;
  }
}

/// What went wrong, with the outcome it ends in.
struct Failure {
  OperatorOutcome outcome;
  std::string line;
};

std::optional<io::ComponentPins> read_pins(Failure& failure) {
  const auto state = find("state");
  const auto waiting = find("waiting-for-operator");
  const auto can_cancel = find("can-cancel");
  const auto fault = find("fault");
  if (!state || !waiting || !can_cancel || !fault) {
    failure = {OperatorOutcome::not_running,
               "the component is not running: HAL has no pin fixed_atc_probe.state (is it in "
               "the INI's HAL files?)"};
    return std::nullopt;
  }
  return io::ComponentPins{value_of(*state), value_of(*waiting) != 0, value_of(*can_cancel) != 0,
                           value_of(*fault) != 0};
}

std::optional<io::StatusWords> read_status(const std::string& path) {
  std::string error;
  const auto text = io::read_small_file(path, error);
  return text ? io::parse_status_words(*text) : std::nullopt;
}

/// Sets `name` to `value` and checks that it holds: a pin another writer
/// drives all the time (not a panel's button, which writes only when clicked)
/// would undo it.
bool set_and_hold(const std::string& name, int value, Failure& failure) {
  const auto pin = find(name);
  if (!pin) {
    failure = {OperatorOutcome::not_running, "the component is not running: HAL has no pin "
                                             "fixed_atc_probe." + name};
    return false;
  }
  write(*pin, value);
  std::this_thread::sleep_for(kPulse);
  if (value_of(*pin) == value) return true;
  failure = {OperatorOutcome::refused,
             "fixed_atc_probe." + name + " is held by another writer (" +
                 (pin->netted ? "its signal's" : "its own") + " value went back to " +
                 std::to_string(value_of(*pin)) + "): drive it from there, or unnet it"};
  return false;
}

/// A button's press: the values first, then a pulse, as the panel does.
bool press(const io::Press& request, Failure& failure) {
  for (const io::PinWrite& w : request.set) {
    if (!set_and_hold(w.pin, w.value, failure)) return false;
  }
  return set_and_hold(request.pulse, 1, failure) && set_and_hold(request.pulse, 0, failure);
}

/// "load of tool 3 into pocket 5": the first line, what is asked.
std::string asked(const io::Options& options) {
  using Action = io::OperatorRequest::Action;
  const io::OperatorRequest& r = *options.request;
  const std::string n = std::to_string(r.number);
  switch (r.action) {
    case Action::load:
      return "load of tool " + n +
             (options.into_pocket.value_or(0) ? " into pocket " + std::to_string(*options.into_pocket)
                                              : "");
    case Action::unload:
      return "unload of tool " + n;
    case Action::continue_prompt:
      return "Continue";
    case Action::cancel:
      return "Cancel";
    case Action::clear_fault:
      return "clear fault";
    case Action::measure_all:
      return r.number == 0 ? "measure all" : r.number == 1 ? "measure all never measured"
                                                             : "measure all of the program";
    case Action::verify:
      return "verify of pocket " + n;
    case Action::touch:
      return r.number == 0 ? "teaching every pocket by touch" : "teaching pocket " + n + " by touch";
    case Action::teach_datum:
      return "teaching the rack datum by touch";
    case Action::check_datum:
      return "checking the rack datum";
    case Action::clear_datum_drift:
      return "clearing the rack datum's drift";
    case Action::io:
      return r.io ? std::string("I/O check: ") + io_action_name(*r.io) +
                        (options.holding_tool ? " (the operator holds the tool)" : "")
                  : "I/O check: the sensors, live (Ctrl-C or --timeout ends it)";
  }
  return "";
}

/// How long an output's answer may take: longer than any sensor timeout a
/// config sensibly has; the component says when its own timeout passed.
constexpr auto kIoAnswerWithin = std::chrono::seconds(60);

bool timed_out(const io::Options& options, Clock::duration waited) {
  return options.timeout_seconds && waited > std::chrono::duration<double>(*options.timeout_seconds);
}

/// --operator io: each sensor's line and each output's refusal, printed
/// again whenever it changes, until a signal or --timeout.
OperatorOutcome watch_io(const io::Options& options, const std::string& status_path,
                         std::ostream& out, Failure& failure) {
  const auto began = Clock::now();
  std::vector<std::string> shown;
  for (;;) {
    if (!read_pins(failure)) return failure.outcome;
    if (const auto status = read_status(status_path)) {
      std::vector<std::string> lines = status->io_sensors;
      // In the order of the buttons (the file's object sorts its keys).
      for (const IoActionDeclaration& a : kIoActions) {
        for (const auto& [action, why] : status->io_refusals) {
          if (action != a.name) continue;
          lines.push_back(action + ": " + (why.empty() ? "allowed" : "refused: " + why));
        }
      }
      if (lines != shown) {
        const double seconds = std::chrono::duration<double>(Clock::now() - began).count();
        out << formatted("at %.2f s:", seconds) << std::endl;
        for (const std::string& line : lines) out << "  " << line << std::endl;
        shown = std::move(lines);
      }
    }
    if (timed_out(options, Clock::now() - began)) return OperatorOutcome::done;
    if (io::Interruptible::signal() != 0) return OperatorOutcome::timeout;  // run_operator says it
    std::this_thread::sleep_for(kPoll);
  }
}

/// --operator io:OUTPUT: its button pressed once (with --holding-tool's pin
/// up meanwhile), the component's answer printed: refused, or how long its
/// sensor took.
OperatorOutcome drive_io(const io::Options& options, const std::string& status_path,
                         long seen_serial, std::ostream& out, Failure& failure) {
  const char* holding = "io-check-holding-tool";
  if (options.holding_tool && !set_and_hold(holding, 1, failure)) return failure.outcome;
  const bool pressed = press(io::press_of(*options.request, {}, {}, {}), failure);
  if (options.holding_tool) {
    Failure dropped{OperatorOutcome::done, ""};
    set_and_hold(holding, 0, dropped);
  }
  if (!pressed) return failure.outcome;
  const auto pressed_at = Clock::now();
  for (;;) {
    if (!read_pins(failure)) return failure.outcome;
    if (const auto status = read_status(status_path); status && status->serial > seen_serial) {
      const long fresh = status->serial - seen_serial;
      const std::size_t count = std::min<std::size_t>(fresh, status->messages.size());
      for (std::size_t i = status->messages.size() - count; i < status->messages.size(); ++i) {
        const auto& [kind, text] = status->messages[i];
        out << kind << ": " << text << std::endl;
        if (text.rfind("I/O check: ", 0) != 0) continue;
        if (kind != "error") return OperatorOutcome::done;
        return text.find(" refused: ") != std::string::npos ? OperatorOutcome::refused
                                                            : OperatorOutcome::failed;
      }
      seen_serial = status->serial;
    }
    const auto waited = Clock::now() - pressed_at;
    if (waited > kIoAnswerWithin || timed_out(options, waited)) {
      failure = {OperatorOutcome::timeout, "fixed_atc_probe did not answer the I/O check in time"};
      return failure.outcome;
    }
    if (io::Interruptible::signal() != 0) return OperatorOutcome::timeout;  // run_operator says it
    std::this_thread::sleep_for(kPoll);
  }
}

/// The request from its press to its end, once connected to HAL; `pressed`:
/// its button was pressed (a signal before that presses nothing).
OperatorOutcome follow(const io::Options& options, const std::string& status_path,
                       std::ostream& out, Failure& failure, bool& pressed) {
  const auto pins = read_pins(failure);
  if (!pins) return failure.outcome;
  const auto before = read_status(status_path);
  if (!before) {
    failure = {OperatorOutcome::not_running,
               "no status file " + io::shown_path(status_path) +
                   " to read the component's words from: is " +
                   io::shown_path(options.state_path) + " the state file it was given?"};
    return failure.outcome;
  }
  if (options.request->action == io::OperatorRequest::Action::io) {
    out << "fixed_atc_probe: " << asked(options) << std::endl;
    if (!options.request->io) return watch_io(options, status_path, out, failure);
    pressed = true;
    return drive_io(options, status_path, before->serial, out, failure);
  }
  if (const std::string nothing = io::nothing_to_act_on(*options.request, *pins); !nothing.empty()) {
    failure = {OperatorOutcome::refused, nothing};
    return failure.outcome;
  }
  out << "fixed_atc_probe: " << asked(options) << std::endl;
  // Ended before the press (a reader gone from the pipe that line went to among them): nothing asked.
  if (io::Interruptible::signal() != 0) return OperatorOutcome::timeout;  // run_operator says it
  io::OperatorWatch watch(*options.request, options.answer_yes, before->serial);
  const auto pressed_at = Clock::now();
  pressed = true;
  io::Press button = io::press_of(*options.request, options.into_pocket, options.spindle_tool,
                                  options.pocket_holds_tool);
  // The sequence takes the switch at its start: run_operator puts it back after.
  if (options.step_by_step) button.set.push_back({"step-by-step", 1});
  if (!press(button, failure)) {
    return failure.outcome;
  }
  for (;;) {
    const auto now_pins = read_pins(failure);
    if (!now_pins) return failure.outcome;
    const io::OperatorWatch::Turn turn = watch.observe(read_status(status_path), *now_pins);
    for (const std::string& line : turn.lines) out << line << std::endl;
    if (turn.outcome) return *turn.outcome;
    if (turn.press_continue && !press({{}, "continue"}, failure)) return failure.outcome;
    const auto waited = Clock::now() - pressed_at;
    if (!watch.answered() && waited > kAnswerWithin) {
      failure = {OperatorOutcome::timeout,
                 "fixed_atc_probe did not take the request up within 10 s"};
      return failure.outcome;
    }
    if (options.timeout_seconds && waited > std::chrono::duration<double>(*options.timeout_seconds)) {
      failure = {OperatorOutcome::timeout, "stopped waiting after --timeout; the request goes on"};
      return failure.outcome;
    }
    if (io::Interruptible::signal() != 0) return OperatorOutcome::timeout;  // run_operator says it
    std::this_thread::sleep_for(kPoll);
  }
}

}  // namespace

int run_operator(const io::Options& options, std::ostream& given_out, std::ostream& given_err) {
  // The status file's words and the INI's path are a file's text: each line terminal_safe.
  io::CappedLines out_lines(given_out), err_lines(given_err);
  std::ostream out(&out_lines), err(&err_lines);
  if (options.state_path.empty()) {
    std::string error;
    // The INI gave no state file: it cannot be read (missing, a folder ...), or names none.
    if (io::IniFile::read(*options.ini_path, error)) {
      const auto stamp = io::stamp_of(*options.ini_path);
      error = io::shown_path(*options.ini_path) +
              (stamp && stamp->size == 0 ? " is empty, so it" : "") +
              " names no [FIXED_ATC_PROBE]STATE: give --state FILE";
    }
    err << "fixed_atc_probe: " << error << std::endl;
    return 2;
  }
  const std::string status_path = options.state_path + ".status";
  if (::shmget(kHalKey, 0, 0) < 0) {
    err << "fixed_atc_probe: the component is not running: no HAL (LinuxCNC is not started, or "
           "runs as another user)"
        << std::endl;
    return io::operator_exit_status(OperatorOutcome::not_running);
  }
  // Its own name: a second invocation may answer a prompt this one waits at.
  const std::string name = "fatc-operator-" + std::to_string(::getpid());
  const int id = hal_init(name.c_str());
  if (id < 0) {
    err << "fixed_atc_probe: the component is not running: cannot join HAL (" << id << ")"
        << std::endl;
    return io::operator_exit_status(OperatorOutcome::not_running);
  }
  hal_ready(id);
  Failure failure{OperatorOutcome::done, ""};
  bool pressed = false;
  int step_switch_was = 0;
  if (const auto pin = find("step-by-step"); pin && options.step_by_step) {
    step_switch_was = value_of(*pin);
  }
  const OperatorOutcome outcome = follow(options, status_path, out, failure, pressed);
  if (const auto pin = find("step-by-step"); pin && options.step_by_step && pressed) {
    write(*pin, step_switch_was);
  }
  hal_exit(id);
  if (const int signal = io::Interruptible::signal(); signal != 0) {
    // The caller's Interruptible ends the program by the signal, as the shell expects.
    err << "fixed_atc_probe: stopped " << (pressed ? "waiting" : "before asking") << " ("
        << io::signal_name(signal) << "), out of HAL; "
        << (pressed ? "the request goes on in the component" : "nothing was asked") << std::endl;
    return 128 + signal;
  }
  if (!failure.line.empty()) err << "fixed_atc_probe: " << failure.line << std::endl;
  const int status = io::operator_exit_status(outcome);
  out << "outcome: " << io::outcome_word(outcome) << " (exit " << status << ")" << std::endl;
  return status;
}

}  // namespace fatc::linuxcnc
