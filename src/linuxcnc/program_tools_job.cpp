#include "program_tools_job.hpp"

#include <new>

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

}  // namespace fatc::linuxcnc
