#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "../motion/step.hpp"

namespace fatc {

/// How the step executor was called: the value of the `executor-call` pin,
/// which nc_files/fixed_atc_probe_execute.ngc sets from its argument before
/// its first request.
enum class ExecutorCall { tool_change = 1, operator_flow = 2, chuck_release = 3, chuck_clamp = 4 };

/// What the link reads each turn: pin values and LinuxCNC's interpreter state.
struct LinkInputs {
  bool step_request = false;             ///< step-request: the executor asks for its next step
  int call = 0;                          ///< executor-call: read at the first request of a run
  int number = 0;                        ///< number: the tool an M6 is for
  double probe_result = 0.0;             ///< 1 touched, 0 missed, -1 the probe input was already tripped
  double probe_z = 0.0;                  ///< machine coordinate where the probe stopped, on its axis
  bool tool_prepare = false;             ///< iocontrol's tool-prepare
  bool tool_change = false;              ///< iocontrol's tool-change
  std::optional<bool> interpreter_idle;  ///< nothing when there is no NML status
};

/// What the link writes each turn.
struct LinkOutputs {
  bool step_ready = false;    ///< a step is on the step pins
  Step step = resync_step();  ///< the step pins' values; nothing to do until a step is offered
  bool prepared = false;      ///< iocontrol's tool-prepared
  bool changed = false;       ///< iocontrol's tool-changed: tool-change while the changer is idle
};

/// What the link tells the changer, in the order it happened.
struct LinkEvent {
  enum class Kind {
    tool_change,    ///< M6 started its executor: `tool` is the tool it asks for
    chuck_release,  ///< a chuck atom started its executor: release the chuck
    chuck_clamp,    ///< a chuck atom started its executor: clamp the chuck
    in_position,    ///< the executor finished a move
    command_done,   ///< the executor finished a command (M61, G10)
    probe_result,   ///< the executor finished a probe move: touched, z, tripped_before
    executor_lost,  ///< the executor is gone (program aborted): `reason`
    refused_call,   ///< the link failed the run (an unknown code, a busy link): `reason`
  };
  Kind kind = Kind::in_position;
  int tool = 0;
  bool touched = false;
  double z = 0.0;
  bool tripped_before = false;
  std::string reason;
};

/// The four-phase handshake with the NGC step executor (request↑ ready↑
/// request↓ ready↓), and iocontrol's prepare/change levels. Pure: pin values
/// and time in, pin values and events out; the caller owns pins and clock.
///
/// One turn: read() the pins and hand its events to the changer; what the
/// changer publishes meanwhile is only stored; write() then puts it on the
/// pins. So nothing here re-enters the changer.
class ExecutorLink {
 public:
  using Time = std::chrono::steady_clock::time_point;
  /// An idle interpreter this long, while the executor expects steps, means
  /// the program (or MDI) was aborted.
  static constexpr std::chrono::milliseconds kAbortGrace{200};
  /// How long an MDI run of the executor may take to send its first request
  /// before it is asked for again.
  static constexpr std::chrono::seconds kRunStartGrace{5};

  /// Reads one turn's inputs. After an `executor_lost` event (reported once)
  /// the caller aborts the changer, then drop()s.
  std::vector<LinkEvent> read(const LinkInputs& in, Time now);
  /// The changer's next step: stored, offered by write() once the executor asks.
  void publish(const Step& step);
  /// This turn's outputs; offers the published step if the executor asks.
  /// `changer_idle`: the changer has finished (or never started) a sequence.
  LinkOutputs write(bool changer_idle);

  /// The executor is gone with its program: forget its steps. A request it
  /// left high (motion keeps the output) gets a resync step, which the next
  /// executor takes before it asks afresh.
  void drop();

  /// A published step waits and no executor run is attached to take it: an
  /// operator flow needs the executor started over MDI (not again within
  /// kRunStartGrace). Steps go only to an attached run.
  bool needs_run(Time now) const;
  void run_started(Time now);

  /// An executor run is attached and expects more steps.
  bool attached() const { return attached_; }
  /// Whether the next turn should come soon: a handshake is open or a step waits.
  bool active() const;

 private:
  void offer(const Step& step);
  LinkEvent finished(const Step& step, const LinkInputs& in) const;

  bool request_ = false;      ///< step-request at the last read, as counted
  bool pin_request_ = false;  ///< step-request at the last read, as on the pin
  bool attached_ = false;
  std::optional<Step> pending_;          ///< published, not yet on the pins
  std::optional<Step> refusal_;          ///< fails a run that was called wrongly
  std::optional<Step> offered_;          ///< on the pins, step-ready high
  std::optional<Step> executing_;        ///< taken by the executor, not yet finished
  std::optional<Time> idle_since_;       ///< interpreter idle while attached
  std::optional<Time> run_asked_until_;  ///< an MDI run was asked for
  LinkOutputs out_;
  bool tool_prepare_ = false;
  bool tool_change_ = false;
};

}  // namespace fatc
