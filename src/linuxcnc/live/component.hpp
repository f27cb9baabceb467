#pragma once

#include <chrono>
#include <optional>
#include <string>

#include "config_teacher.hpp"
#include "core/machine/changer.hpp"
#include "core/protocol/executor_link.hpp"
#include "core/machine/base/ports.hpp"
#include "core/dry_run/air_run.hpp"
#include "core/dry_run/teach.hpp"
#include "io/status_file.hpp"
#include "io_check_driver.hpp"
#include "program_tools_job.hpp"
#include "keepout_lengths.hpp"
#include "rack_keepout.hpp"
#include "spindle_tool_sync.hpp"
#include "tool_table_pockets.hpp"

namespace fatc::linuxcnc {

struct HalPins;
class NmlLink;

/// The adapter between LinuxCNC and the changer, shaped like halui: reads
/// pins, NML status and the clock into events; writes the changer's status,
/// the chuck and the executor link's outputs to pins. One poll() per turn.
class Component : public Ports {
 public:
  using Clock = std::chrono::steady_clock;

  /// `nml` may be null (no LinuxCNC task, as under halrun). `config` is the
  /// one the changer starts with; teaching writes `config_path` and hands the
  /// changer the new one.
  /// `tool_table`: the tool table file the INI names, if any.
  Component(HalPins* pins, const Config& config, std::string config_path, std::string state_path,
            NmlLink* nml, std::optional<std::string> tool_table = std::nullopt);
  // It hands out `this` (the changer's ports, refuse_): it stays where it was made.
  Component(const Component&) = delete;
  Component& operator=(const Component&) = delete;
  void attach(Changer* changer) { changer_ = changer; }
  /// The machine's soft limits, which a taught position must respect.
  void soft_limits(const std::optional<SoftLimits>& limits) {
    teacher_.soft_limits(limits);
    lengths_.soft_limits(limits);
  }
  /// `interpreter_idle`: LinuxCNC's interpreter state, when NML is available.
  void poll(Clock::time_point now, std::optional<bool> interpreter_idle);
  /// Whether the next poll should come soon: a sequence runs, a handshake is
  /// open or the I/O check times an answer.
  bool active() const;

  void publish(const Step& step) override { link_.publish(step); }
  void set_chuck_open(bool open) override;
  void set_rack_cover_open(bool open) override;
  void set_air_blast(bool on) override;
  void start_timer(double seconds) override;
  void cancel_timer() override { deadline_.reset(); }
  void tell(MessageKind kind, const std::string& text) override;
  void ask(const Prompt& prompt) override;
  void save(const ToolState& state) override;
  void write_found(const std::vector<Found>& found, bool datum) override {
    accepted_ = Accepted{found, datum};
  }
  void unexpected(const std::string& state, const std::string& event) override;

 private:
  /// A rising edge of a level input.
  struct Edge {
    bool last = false;
    bool rose(bool now) {
      const bool edge = now && !last;
      last = now;
      return edge;
    }
  };

  void read_machine(std::optional<bool> interpreter_idle);
  void read_executor(std::optional<bool> interpreter_idle);
  void read_operator();
  void teach(const TeachTarget& target);
  /// A touch press (touch-pockets, teach-datum, check-datum).
  void touch(TouchRequest::Goal goal);
  /// An air-run press: the sequence `what` flown, or refused in one message.
  void fly(AirAsk::What what);
  /// Where the machine stands, in machine coordinates and config units; nothing without NML.
  std::optional<Point> position() const;
  void abort(const std::string& reason);
  void start_executor_if_needed();
  /// The I/O check's buttons, with the changer's belief and the machine's facts.
  void poll_io_check();

  HalPins* pins_;
  NmlLink* nml_;
  ConfigTeacher teacher_;
  std::string state_path_;
  Changer* changer_ = nullptr;
  ExecutorLink link_;
  Clock::time_point now_;
  std::optional<Clock::time_point> deadline_;
  std::optional<bool> machine_ready_;
  std::optional<bool> spindle_stopped_;
  std::optional<SensorReadings> sensors_;
  SensorReadings raw_sensors_;  ///< as the pins read, before the I/O check hides any
  std::optional<std::string> task_busy_;  ///< why task cannot run the executor now
  bool task_free_ = false;
  SpindleToolSync spindle_tool_;
  RackKeepout keepout_;
  KeepoutLengths lengths_;
  ToolTablePockets table_pockets_;
  io::StatusFile status_file_;
  MeasureAllPress measure_all_press_;
  const MeasureAllPress::Refuse refuse_ = [this](const std::string& why) {
    tell(MessageKind::error, why);
  };
  Edge abort_, clear_, load_, unload_, continue_, cancel_, spindle_refused_;
  Edge teach_pocket_, teach_loading_, teach_safe_, teach_sensor_, measure_all_, verify_;
  Edge air_change_, air_load_, air_unload_, air_verify_;
  Edge touch_pockets_, teach_datum_, check_datum_, clear_datum_drift_;
  /// What touching found and the operator accepted, written once the changer is idle.
  struct Accepted {
    std::vector<Found> found;
    bool datum = false;
  };
  std::optional<Accepted> accepted_;
  IoCheckDriver io_check_;
};

}  // namespace fatc::linuxcnc
