#pragma once

// --operator: a request to the running component through its public channels
// (the operator pins a panel pulses, and the status file it reads for words),
// followed to its end. Nothing here touches HAL or a clock: the HAL side
// (operator_command.cpp) feeds each poll's readings in and does
// what comes back, so the judging can be tested without a machine.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/rack/io_check.hpp"

namespace fatc::io {

/// What --operator ACTION asks for: load:T, unload:T, continue, cancel,
/// clear-fault, measure-all[:never|:program], verify:P, io[:OUTPUT].
struct OperatorRequest {
  enum class Action {
    load,
    unload,
    continue_prompt,
    cancel,
    clear_fault,
    measure_all,
    verify,
    io,
    touch,  ///< touch-pockets: `number` the pocket, 0 every pocket
    teach_datum,
    check_datum,
    clear_datum_drift,
  };
  OperatorRequest() = default;
  OperatorRequest(Action action, int number, std::optional<IoAction> io = std::nullopt)
      : action(action), number(number), io(io) {}
  Action action = Action::continue_prompt;
  /// load, unload: the tool; verify: the pocket; measure-all: measure-which (0, 1, 2).
  int number = 0;
  /// io: the output the I/O check drives once; unset: its sensors shown live.
  std::optional<IoAction> io;
};

/// The request `text` names; nullopt and one line in `error` when it names none.
std::optional<OperatorRequest> parse_operator_action(const std::string& text, std::string& error);

/// How a request ended, each its own exit status (operator_exit_status).
enum class OperatorOutcome { done, refused, fault, cancelled, timeout, not_running, failed };
/// 0 done, 1 refused (nothing moved), 3 fault, 4 cancelled, 5 timeout, 6 the
/// component not running, 7 failed (ended without doing it: a probe missed);
/// 2 stays the command line's usage mistake.
int operator_exit_status(OperatorOutcome outcome);
/// "done", "refused", …: the last line's first word.
const char* outcome_word(OperatorOutcome outcome);

/// One pin of the component to set before the press, and its value.
struct PinWrite {
  const char* pin;  ///< without "fixed_atc_probe."
  int value;
};

/// What the panel's button does, as pins: the values it sets, then the pin
/// it pulses. `into` is load's pocket (0: the changer chooses); `spindle`
/// and `pocket_holds` are clear-fault's answers (unset: -1, "not said").
struct Press {
  std::vector<PinWrite> set;
  const char* pulse;
};
Press press_of(const OperatorRequest& request, std::optional<int> into,
               std::optional<int> spindle, std::optional<bool> pocket_holds);

/// The component's words at one moment: STATE.status (status_file.cpp).
struct StatusWords {
  int state = 0;     ///< the `state` pin's code: 1 idle, 5 fault, …
  int awaiting = 0;  ///< 5: the operator
  std::string activity;
  long serial = 0;  ///< messages said so far
  std::vector<std::pair<std::string, std::string>> messages;  ///< kind, text; the newest last
  /// The I/O check's `io_check`: each sensor's line, each output's refusal (empty: allowed).
  std::vector<std::string> io_sensors;
  std::vector<std::pair<std::string, std::string>> io_refusals;
};
/// nullopt when `text` is no status file (half written, or not one).
std::optional<StatusWords> parse_status_words(const std::string& text);

/// The component's output pins the command reads each poll.
struct ComponentPins {
  int state = 0;
  bool waiting_for_operator = false;
  bool can_cancel = false;
  bool fault = false;
};

/// Before the press: why the component would only answer that nothing is
/// there to act on (Continue, Cancel, Clear fault); empty when it may press.
std::string nothing_to_act_on(const OperatorRequest& request, const ComponentPins& pins);

/// Follows one request from its press to its end, one poll at a time.
class OperatorWatch {
 public:
  /// `answer_yes`: press Continue at each prompt. `seen_serial`: the status
  /// file's serial before the press (older messages are not this request's).
  OperatorWatch(OperatorRequest request, bool answer_yes, long seen_serial);

  struct Turn {
    std::vector<std::string> lines;  ///< to print, in order
    bool press_continue = false;
    std::optional<OperatorOutcome> outcome;  ///< set once the request has ended
  };
  /// One poll's readings. `status` is nullopt while the file cannot be read.
  Turn observe(const std::optional<StatusWords>& status, const ComponentPins& pins);
  /// Whether the component has taken the request up (it left idle, or said something).
  bool answered() const { return answered_; }

 private:
  OperatorRequest request_;
  bool answer_yes_;
  long seen_serial_;
  bool answered_ = false;
  bool started_ = false;
  /// A prompt said and not yet answered: the next prompt may come before a
  /// poll sees waiting-for-operator low between the two.
  bool prompt_pending_ = false;
  bool cancelled_ = false;        ///< a message of this request said so
  bool failed_ = false;           ///< an error that was no refusal (a probe missed)
  bool refused_ = false;
  /// Touching showed what it found: once accepted, the changer writes it
  /// after the flow ends, and the request is done only when that is said.
  bool awaits_write_ = false;
};

}  // namespace fatc::io
