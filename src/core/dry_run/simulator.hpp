#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "../machine/changer.hpp"

namespace fatc {

/// One thing the changer did, in order: a step, a chuck, rack cover or air
/// blast change, a dwell, a message.
struct Record {
  enum class Kind { step, chuck, cover, blast, dwell, message, save } kind = Kind::step;
  Step step;
  bool chuck_open = false;
  bool on = false;  ///< the cover opened, the blast on
  double seconds = 0.0;
  MessageKind message_kind = MessageKind::info;
  std::string text;
  ToolState saved;  ///< for a save
};

std::string describe(const Record& record);

/// The rack the Simulator models when sensors are wired: the tool follows
/// the chuck (a closing chuck at a full pocket takes its tool, an opening one
/// lets go of it, into the pocket it is at or out of the machine), and the
/// sensors read what is there. Tests inject faults through its fields.
struct Rack {
  bool modelled = false;
  int spindle = 0;              ///< the tool the spindle clamps, 0 none
  std::map<int, int> pockets;   ///< pocket number -> the tool in it, 0 empty
  bool air = true;              ///< the drawbar has its air
  bool spindle_still = true;    ///< the spindle stands still
  int grips_failing = 0;        ///< this many closings at a pocket do not take its tool
  bool tool_sticks = false;     ///< a released tool stays in the spindle
  bool drawbar_jammed = false;  ///< the drawbar does not move (its feedback stays)
  bool drawbar_released = false;  ///< where the drawbar is
  bool cover_open = false;      ///< where the rack cover is
  bool cover_jammed = false;    ///< the rack cover does not move (its feedback stays)
  /// The rack cover's feedback follows its command only at run()'s next
  /// event, not at once: the changer hears of it while it is still moving.
  bool cover_slow = false;
  Point at;                     ///< where the spindle is (known_axes of it)
  unsigned known_axes = 0;
  // A collet-nut magazine (`chuck.kind`): the spindle screws the nuts.
  double spindle_rpm = 0.0;     ///< what the changer turns it at: reverse < 0, forward > 0
  bool stalled = false;         ///< the spindle never comes up to speed, and screws nothing
  int screwings_failing = 0;    ///< this many screwings off or on leave the nut where it was
  bool screwed = false;         ///< the spindle's start under way has screwed (or failed to) once
  bool nut_hangs_low = false;   ///< a nut screwed on is not screwed home (zone 2 sees it)
  bool seated = true;           ///< the spindle's nut is screwed home
  std::optional<Recognition> zones;  ///< where the tool-recognition beam is read

  /// The pocket the spindle is in (its nose at the pocket's XYZ), 0 none.
  int pocket_at(const Config& config) const;
  /// The spindle turning at a pocket's engage Z screws its nut: off into the
  /// empty pocket in reverse, on from the full pocket forward.
  void screw(const Config& config);
  /// Whether `fact` holds: what the sensors that watch it read.
  bool holds(Fact fact) const;
};

/// Ports that record everything and an executor that finishes every step at
/// once: what `--plan` prints and what the unit tests read. Probe moves touch
/// at `sensor_z` (or miss when it is unset); operator waits are answered by
/// the caller.
class Simulator : public Ports {
 public:
  /// With sensors in `config`, models the rack as `tools` says it is, so the
  /// sensors read true; run() then reports every change of them.
  void model_rack(const Config& config, const ToolState& tools);
  Rack rack;
  /// What the sensors read in the modelled rack.
  SensorReadings readings() const;
  /// Reports the readings to the changer if they changed since the last
  /// report; from then on chuck changes are reported as they happen.
  bool report_sensors(Changer& changer);
  /// The operator does what the changer waits for: inserts or removes the tool `asked` names.
  void operator_obeys(const Changer& changer);
  std::optional<Prompt> asked;  ///< the last question put to the operator

  std::vector<Record> records;
  /// false: a save is recorded without the state it saved (a copy of the
  /// whole rack each time, most of a long program's preflight).
  bool keeps_saved_states = true;
  std::optional<double> sensor_z;
  /// Where a probe move touches, where set (the rack found by touch): the
  /// coordinate on the move's axis, nullopt where it touches nothing. Unset:
  /// `sensor_z` answers.
  std::function<std::optional<double>(const Step& probe)> touches;
  /// What touching found and the operator accepted (write_found), in order.
  std::vector<Found> written;
  bool written_datum = false;
  bool chuck_open = false;
  bool timer_armed = false;
  std::optional<Step> pending;  ///< last published step not yet finished
  std::vector<std::string> unexpected_events;

  void publish(const Step& step) override;
  void set_chuck_open(bool open) override;
  void set_rack_cover_open(bool open) override;
  void set_air_blast(bool on) override;
  bool cover_open = false;
  bool blowing = false;
  void start_timer(double seconds) override;
  void cancel_timer() override;
  void tell(MessageKind kind, const std::string& text) override;
  /// Recorded as a prompt message in its words, and kept typed in `asked`.
  void ask(const Prompt& prompt) override;
  void save(const ToolState& state) override;
  void write_found(const std::vector<Found>& found, bool datum) override;
  void unexpected(const std::string& state, const std::string& event) override;

  /// Finishes steps and runs out timers until the changer waits for something
  /// else (operator, spindle) or a sequence ends. Returns how many events it fed.
  int run(Changer& changer, int limit = 1000);

  /// The executor's worst case (model_rack first): the spindle still turns
  /// at the request, the air dips during every move, and every sensor the
  /// changer waits for answers only as its time runs out.
  void answer_late(Changer& changer);
  bool answers_late = false;
  double clock = 0.0;         ///< seconds of timers run out since the start
  double longest_wait = 0.0;  ///< the longest stretch the executor waited for a step

  std::vector<Step> steps() const;
  std::vector<Step> motion_steps() const;
  std::vector<std::string> messages(MessageKind kind) const;
  int saves = 0;
  std::size_t spindle_stood = 0;  ///< plan_change_running_down: the record where the spindle stood

 private:
  /// Records a change of the chuck, the rack cover or the air blast.
  void record_output(Record::Kind kind, bool on);
  /// Runs out the armed timer; answering late, the sensors a sensor wait
  /// awaits answer just before.
  void run_out_timer(Changer& changer, bool awaits_sensor);
  /// Answering late, the sensors that watch `fact` show its change at once.
  void show(Fact fact);
  const Config* config_ = nullptr;
  double armed_seconds_ = 0.0;
  int timers_started_ = 0;
  bool spindle_turning_ = false;
  double waiting_since_ = 0.0;  ///< when the executor finished its last step
  Changer* changer_ = nullptr;
  std::optional<SensorReadings> reported_;
  /// Answering late: what the sensors have told so far, not what they read.
  SensorReadings shown_;
};

}  // namespace fatc

namespace fatc {

/// The first-start rack (ToolState::fresh) with `tool` taken from its pocket
/// into the spindle (0: the spindle empty).
ToolState with_in_spindle(const Config& config, int tool);

/// The records of M6 T`to` with `from` in the spindle, every other pocket full;
/// the operator continues at every wait (manual tools) and the sensor, when
/// `probe_after_change` asks for it, touches at `sensor_z`.
Simulator plan_change(const Config& config, int from, int to, double sensor_z);
/// The same from the tools as `tools` has them (a saved state).
Simulator plan_change(const Config& config, const ToolState& tools, int to, double sensor_z);
/// The same for its time alone (change_time, the preflight's estimate): the
/// saves recorded without their states.
Simulator plan_change_timed(const Config& config, const ToolState& tools, int to,
                            double sensor_z);
/// The same with the spindle turning at the request, standing once the changer
/// waits for it: the records before `spindle_stood` are what M6 did while it
/// ran down (move_while_spindle_stops), without the wait itself.
Simulator plan_change_running_down(const Config& config, const ToolState& tools, int to,
                                   double sensor_z);
/// The records of loading `tool` by hand with `from` in the spindle; the operator
/// continues at every wait and the sensor touches at `sensor_z`.
Simulator plan_load(const Config& config, int tool, int from, double sensor_z);
/// The same into pocket `pocket` (0: the one the changer chooses), from `tools`.
Simulator plan_load(const Config& config, const ToolState& tools, int tool, int pocket,
                    double sensor_z);
/// The records of unloading `tool` with `from` in the spindle; the operator continues.
Simulator plan_unload(const Config& config, int tool, int from);
/// The same from `tools`.
Simulator plan_unload(const Config& config, const ToolState& tools, int tool);

/// The records of `request` made of a changer with `tools` standing at `at`
/// (on the axes `known`): the operator continues at every wait and the
/// sensor touches as low as `probe_limit` lets it.
Simulator plan_from(const Config& config, const ToolState& tools, const Point& at, unsigned known,
                    const std::function<void(Changer&)>& request);

/// The longest the changer may keep the executor waiting between two steps,
/// in seconds: the most of every change, load and unload planned with the
/// Simulator answering late, of a change whose first grip fails, and of a
/// change that comes while the rack cover the last one closed is moving.
double longest_executor_wait(const Config& config);

}  // namespace fatc
