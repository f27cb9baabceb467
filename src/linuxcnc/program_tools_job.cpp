#include "program_tools_job.hpp"

#include <cstdlib>
#include <new>

#include "core/machine/changer.hpp"
#include "core/machine/flows/measure_which.hpp"
#include "io/lint.hpp"

namespace fatc::linuxcnc {

ProgramToolsJob::~ProgramToolsJob() {
  if (thread_.joinable()) thread_.join();
}

bool ProgramToolsJob::start(const std::string& program, const std::string& ini_path,
                            const Config& config) {
  if (thread_.joinable()) return false;
  done_ = false;
  thread_ = std::thread([this, program, ini_path, config] {
    Result result;
    // An exception would end the component (std::terminate): it is the job's error.
    try {
      result.tools = io::program_tools(program, ini_path, config, result.error);
    } catch (const std::bad_alloc&) {
      result.error = "out of memory reading the program";
    } catch (const std::exception& e) {
      result.error = e.what();
    }
    result_ = std::move(result);
    done_ = true;
  });
  return true;
}

std::optional<ProgramToolsJob::Result> ProgramToolsJob::take() {
  if (!thread_.joinable() || !done_) return std::nullopt;
  thread_.join();
  return std::move(result_);
}

void MeasureAllPress::press(int which, const std::string& program, Changer& changer,
                            const Refuse& refuse) {
  const MeasureChoice choice = measure_which(which, changer.tools());
  if (choice.kind == MeasureChoice::Kind::tools) changer.measure_all(choice.tools);
  if (choice.kind == MeasureChoice::Kind::refused) refuse(choice.refusal);
  if (choice.kind != MeasureChoice::Kind::program_tools) return;
  const char* ini = std::getenv("INI_FILE_NAME");
  if (program.empty()) {
    refuse(measure_refused("no program is loaded in LinuxCNC"));
  } else if (!job_.start(program, ini ? ini : "", changer.config())) {
    refuse(measure_refused("the program's tools are being worked out"));
  }  // else poll() goes on once the interpreter has them
}

void MeasureAllPress::poll(Changer& changer, const Refuse& refuse) {
  auto done = job_.take();
  if (!done) return;
  if (done->tools) {
    changer.measure_all(*done->tools);
  } else {
    refuse(measure_refused(done->error));
  }
}

}  // namespace fatc::linuxcnc
