#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/config/config.hpp"

namespace fatc {
class Changer;
}

namespace fatc::linuxcnc {

/// "The tools of the loaded program" for measure all (measure-which 2),
/// worked out by LinuxCNC's interpreter (io::program_tools) on a thread of
/// its own: rs274 may take seconds, and a poll loop that stalls half a second
/// is taken for a dead component by the chuck guard. The poll loop starts a
/// job and takes its result on a later turn.
class ProgramToolsJob {
 public:
  struct Result {
    std::optional<std::vector<int>> tools;  ///< nullopt: `error` says why
    std::string error;
  };

  ProgramToolsJob() = default;
  /// Waits for a job under way (rs274 is stopped after io::kInterpreterSeconds).
  ~ProgramToolsJob();
  ProgramToolsJob(const ProgramToolsJob&) = delete;
  ProgramToolsJob& operator=(const ProgramToolsJob&) = delete;

  /// Starts working out the tools of `program`; false while one is under way.
  bool start(const std::string& program, const std::string& ini_path, const Config& config);
  /// The result of a finished job, once; nullopt while it runs or when none was started.
  std::optional<Result> take();

 private:
  std::thread thread_;
  std::atomic<bool> done_{false};
  Result result_;  ///< written by the thread before done_, read after it
};

/// The panel's Measure all: measure-which as the core reads it
/// (measure_which), the loaded program's tools by a ProgramToolsJob.
class MeasureAllPress {
 public:
  using Refuse = std::function<void(const std::string&)>;
  /// A press: `which` from measure-which, `program` the one loaded in LinuxCNC.
  void press(int which, const std::string& program, Changer& changer, const Refuse& refuse);
  /// Gives the changer the program's tools once the job has them.
  void poll(Changer& changer, const Refuse& refuse);

 private:
  ProgramToolsJob job_;
};

}  // namespace fatc::linuxcnc
