#include "interpreter.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/program/interpreter_inputs.hpp"
#include "core/program/interpreter_output.hpp"
#include "core/program/numbered_program.hpp"
#include "files.hpp"
#include "ini.hpp"

namespace fatc::io {
namespace {

namespace fs = std::filesystem;
using program::finding;

/// `path` as seen from `base` (the INI's folder, where LinuxCNC runs).
std::string from_folder(const std::string& path, const std::string& base) {
  return path.empty() || path[0] == '/' ? path : base + "/" + path;
}

/// `path` from where rs274 starts (the INI's folder) as from here.
std::string absolute(const std::string& path) {
  if (path.empty() || path[0] == '/') return path;
  std::error_code failed;
  const fs::path here = fs::current_path(failed);
  return failed ? path : (here / path).lexically_normal().string();
}

/// The folders of a list with ':' between them, empty ones included.
std::vector<std::string> folders_of(const std::string& folders) {
  std::vector<std::string> result;
  std::size_t start = 0;
  while (start <= folders.size()) {
    auto colon = folders.find(':', start);
    if (colon == std::string::npos) colon = folders.size();
    result.push_back(folders.substr(start, colon - start));
    start = colon + 1;
  }
  return result;
}

/// A list of folders (':' between), each absolute.
std::string absolute_folders(const std::string& folders) {
  std::string result;
  for (const std::string& folder : folders_of(folders)) {
    if (folder.empty()) continue;
    result += (result.empty() ? "" : ":") + (folder[0] == '~' ? folder : absolute(folder));
  }
  return result;
}

/// A folder of its own for the interpreter's inputs, removed with it.
class ScratchFolder {
 public:
  explicit ScratchFolder(std::string& error) {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/fatc_preflight_XXXXXX";
    if (::mkdtemp(pattern.data()) == nullptr) {
      error = "cannot make a folder for the interpreter's files in " + folder_of(pattern) + " (" +
              std::strerror(errno) + ")";
      return;
    }
    path_ = pattern;
  }
  ~ScratchFolder() {
    std::error_code ignored;
    if (!path_.empty()) fs::remove_all(path_, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;

  bool made() const { return !path_.empty(); }
  const std::string& path() const { return path_; }
  /// Writes `name` in the folder; its path, or nullopt and `error`.
  std::optional<std::string> write(const std::string& name, const std::string& text,
                                   std::string& error) const {
    const std::string path = path_ + "/" + name;
    try {
      // Scratch, removed after the run: no fsync.
      write_file(path, text, std::chrono::milliseconds(0), {false, std::nullopt});
    } catch (const std::exception& e) {
      error = std::string(e.what()) + " (a file for the interpreter)";
      return std::nullopt;
    }
    return path;
  }

 private:
  std::string path_;
};

/// Splits a stream into lines for `take`; a line over `kLongest` is cut there.
template <class Take>
class LineSplitter {
 public:
  explicit LineSplitter(Take take) : take_(take) {}
  void add(const char* data, std::size_t size) {
    for (std::size_t i = 0; i < size; ++i) {
      if (data[i] == '\n') {
        take_(std::string_view(line_));
        line_.clear();
      } else if (line_.size() < kLongest) {
        line_.push_back(data[i]);
      }
    }
  }
  void end() {
    if (!line_.empty()) take_(std::string_view(line_));
    line_.clear();
  }

 private:
  static constexpr std::size_t kLongest = 4096;
  Take take_;
  std::string line_;
};

/// How the child ended, for the report.
struct Ending {
  bool timed_out = false;
  bool too_much_output = false;
  int status = 0;
};

/// Runs `argv` in `folder`, which writes its canonical calls to `calls_path`
/// (a file: rs274 buffers it, where on a pipe it writes every few
/// characters, four times slower), and feeds its standard error to `output`.
std::optional<Ending> run_child(const std::vector<std::string>& argv, const std::string& folder,
                                const std::string& home, const std::string& calls_path,
                                const InterpreterInput& input, program::InterpreterOutput& output,
                                std::string& error) {
  int err_pipe[2];
  if (::pipe2(err_pipe, O_CLOEXEC) != 0) {
    error = std::string("cannot start rs274: ") + std::strerror(errno);
    return std::nullopt;
  }
  // Everything the child needs is made before fork: only exec-safe calls after.
  std::vector<char*> args;
  for (const std::string& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
  args.push_back(nullptr);
  // LinuxCNC's tool data lives in $HOME/.tool.mmap, which rs274 makes anew:
  // in the machine's own HOME it would pull the table from under a running
  // LinuxCNC (and two rs274 at once end on SIGBUS). Its HOME is the scratch folder.
  std::vector<std::string> environment{"HOME=" + home};
  for (char** variable = environ; *variable != nullptr; ++variable) {
    if (std::strncmp(*variable, "HOME=", 5) != 0) environment.emplace_back(*variable);
  }
  std::vector<char*> env;
  for (std::string& variable : environment) env.push_back(variable.data());
  env.push_back(nullptr);
  const pid_t child = ::fork();
  if (child == 0) {
    // A group of its own: a remap's own children go with it when it is stopped.
    ::setpgid(0, 0);
    const int nothing = ::open("/dev/null", O_RDWR);
    if (nothing >= 0) {
      ::dup2(nothing, STDIN_FILENO);
      ::dup2(nothing, STDOUT_FILENO);
    }
    ::dup2(err_pipe[1], STDERR_FILENO);
    if (::chdir(folder.c_str()) != 0) ::_exit(126);
    ::execve(args[0], args.data(), env.data());
    ::_exit(127);
  }
  ::close(err_pipe[1]);
  if (child < 0) {
    error = std::string("cannot start rs274: ") + std::strerror(errno);
    ::close(err_pipe[0]);
    return std::nullopt;
  }
  ::setpgid(child, child);  // also here: whichever of the two runs first

  auto errors = [&](std::string_view line) { output.error_line(line); };
  LineSplitter<decltype(errors)> err_lines(errors);
  Ending ending;
  std::size_t error_bytes = 0;
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(input.seconds));
  pollfd err_fd = {err_pipe[0], POLLIN, 0};
  std::vector<char> buffer(64 * 1024);
  // The standard error closes when rs274 ends; meanwhile the file's size is
  // watched every tenth of a second.
  while (err_fd.fd >= 0) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      ending.timed_out = true;
      break;
    }
    const int ready = ::poll(&err_fd, 1, static_cast<int>(std::min<long long>(left.count() + 1, 100)));
    if (ready < 0 && errno != EINTR) break;
    if (ready > 0) {
      const ssize_t got = ::read(err_fd.fd, buffer.data(), buffer.size());
      if (got < 0 && errno != EINTR) break;
      if (got == 0) {
        ::close(err_fd.fd);
        err_fd.fd = -1;
      } else if (got > 0) {
        error_bytes += static_cast<std::size_t>(got);
        err_lines.add(buffer.data(), static_cast<std::size_t>(got));
      }
    }
    if (output.past_the_end()) break;
    struct stat st;
    if (error_bytes > input.max_output_bytes ||
        (::stat(calls_path.c_str(), &st) == 0 &&
         static_cast<std::uint64_t>(st.st_size) > input.max_output_bytes)) {
      ending.too_much_output = true;
      break;
    }
  }
  if (ending.timed_out || ending.too_much_output || output.past_the_end()) ::kill(-child, SIGKILL);
  if (err_fd.fd >= 0) ::close(err_fd.fd);
  err_lines.end();
  while (::waitpid(child, &ending.status, 0) < 0 && errno == EINTR) {
  }
  // The calls, up to the limit: what was written before rs274 was stopped counts.
  std::ifstream calls(calls_path, std::ios::binary);
  std::size_t read_bytes = 0;
  for (std::string line; read_bytes <= input.max_output_bytes && std::getline(calls, line);) {
    read_bytes += line.size() + 1;
    output.canonical_call(line);
  }
  return ending;
}

std::string amount(std::size_t bytes) {
  if (bytes % (1024 * 1024) == 0) return std::to_string(bytes / (1024 * 1024)) + " MiB";
  return std::to_string(bytes) + " bytes";
}

}  // namespace

std::optional<std::string> find_rs274(std::string& error) {
  if (const char* chosen = std::getenv("FATC_RS274"); chosen && *chosen) {
    if (::access(chosen, X_OK) == 0) return std::string(chosen);
    error = shown_path(chosen) +
            " ($FATC_RS274): no such program: LinuxCNC's interpreter rs274 is needed to read the "
            "program";
    return std::nullopt;
  }
  const char* path = std::getenv("PATH");
  const std::string folders = path && *path ? path : "/usr/bin:/bin";
  for (const std::string& folder : folders_of(folders)) {
    const std::string candidate = (folder.empty() ? "." : folder) + "/rs274";
    struct stat st;
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
        ::access(candidate.c_str(), X_OK) == 0) {
      return candidate;
    }
  }
  error =
      "rs274 not found on the PATH: LinuxCNC's interpreter is needed to read the program "
      "(Debian package linuxcnc-uspace)";
  return std::nullopt;
}

std::optional<program::InterpreterRun> run_interpreter(const InterpreterInput& input,
                                                       std::string& error) {
  const std::string name = shown_path(input.program_path);
  std::uint64_t file_bytes = 0;
  auto text = read_file_start(input.program_path, input.max_program_bytes, file_bytes, error);
  if (!text) return std::nullopt;
  const bool cut = text->size() < file_bytes;
  // A cut file ends at its last whole line: half a line could read as another word.
  if (cut) text->resize(text->rfind('\n') == std::string::npos ? 0 : text->rfind('\n') + 1);
  program::NumberedProgram numbered = program::number_lines(*text);
  program::InterpreterRun run;
  if (cut) {
    run.problems.push_back(finding(
        name, 0,
         "only the first " + std::to_string(text->size()) + " of its " +
             std::to_string(file_bytes) + " bytes read (the lint reads at most " +
             amount(input.max_program_bytes) + " of G-code): tool changes after line " +
             std::to_string(std::count(text->begin(), text->end(), '\n')) + " are not known"));
  }
  text.reset();
  if (!numbered.problems.empty()) {
    for (const LineNote& note : numbered.problems) run.problems.push_back(finding(name, note.line, note.text));
    return run;
  }

  std::optional<IniFile> ini;
  if (input.ini_path) {
    ini = IniFile::read(*input.ini_path, error);
    if (!ini) return std::nullopt;
  }
  const std::string machine_folder = input.ini_path ? folder_of(*input.ini_path) : ".";
  double units_per_mm = input.inch_machine ? 1.0 / 25.4 : 1.0;
  if (ini && ini->linear_units() && *ini->linear_units() > 0.0) units_per_mm = *ini->linear_units();

  program::InterpreterTable table = program::any_tool_table();
  if (input.tool_table_path) {
    const auto table_text = read_small_file(*input.tool_table_path, error);
    if (!table_text) return std::nullopt;
    table = program::interpreter_table(parse_tool_table(*table_text), 1.0 / (units_per_mm * 25.4));
  }

  ScratchFolder scratch(error);
  if (!scratch.made()) return std::nullopt;
  const auto program_copy = scratch.write("program.ngc", numbered.text, error);
  numbered.text = std::string();
  const auto table_copy = scratch.write("tools.tbl", table.text, error);
  if (!program_copy || !table_copy) return std::nullopt;
  std::string parameters;
  if (ini) {
    if (const auto file = ini->get("RS274NGC", "PARAMETER_FILE")) {
      std::string ignored;
      parameters = read_small_file(from_folder(*file, machine_folder), ignored).value_or("");
    }
  }
  const auto parameter_copy = scratch.write("parameters.var", parameters, error);
  if (!parameter_copy) return std::nullopt;

  std::vector<std::string> argv = {input.rs274};
  if (input.ini_path) {
    const auto ini_text = read_small_file(*input.ini_path, error);
    if (!ini_text) return std::nullopt;
    std::string folders;
    if (input.subroutine_path) {
      folders = absolute_folders(*input.subroutine_path);
      if (const auto own = ini->get("RS274NGC", "SUBROUTINE_PATH")) folders += ":" + *own;
    }
    const auto written =
        scratch.write("machine.ini", program::ini_for_preflight(*ini_text, folders), error);
    if (!written) return std::nullopt;
    argv.insert(argv.end(), {"-i", *written});
  } else {
    const auto written = scratch.write(
        "machine.ini",
        program::ini_for_preflight(
            "", input.subroutine_path ? absolute_folders(*input.subroutine_path) : ""),
        error);
    if (!written) return std::nullopt;
    argv.insert(argv.end(), {"-i", *written});
  }
  const std::string calls_path = *program_copy + ".calls";
  argv.insert(argv.end(),
              {"-t", *table_copy, "-v", *parameter_copy, "-g", "-n", "0", *program_copy, calls_path});

  program::InterpreterOutput output(name, *program_copy, table.tool_of_row, numbered.input_lines,
                                    numbered.lines);
  const auto ending =
      run_child(argv, machine_folder, scratch.path(), calls_path, input, output, error);
  if (!ending) return std::nullopt;
  if (WIFEXITED(ending->status) && WEXITSTATUS(ending->status) >= 126) {
    error = shown_path(input.rs274) + ": cannot run it" +
            (WEXITSTATUS(ending->status) == 126 ? " in " + shown_path(machine_folder) : "");
    return std::nullopt;
  }
  program::InterpreterRun ran = output.finish();
  ran.problems.insert(ran.problems.begin(), run.problems.begin(), run.problems.end());
  if (ending->timed_out) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", input.seconds);
    ran.problems.push_back(finding(name, 0, std::string("LinuxCNC's interpreter (rs274) still ran after ") +
                                           seconds +
                                           " s (a loop without end?): stopped; tool changes "
                                           "after that are not known"));
  } else if (ending->too_much_output) {
    ran.problems.push_back(finding(name, 0, "LinuxCNC's interpreter (rs274) printed over " +
                                           amount(input.max_output_bytes) +
                                           ": stopped; tool changes after that are not known"));
  } else if (!WIFEXITED(ending->status) && !output.past_the_end()) {
    ran.problems.push_back(finding(name, 0, "LinuxCNC's interpreter (rs274) ended on signal " +
                                           std::to_string(WTERMSIG(ending->status)) +
                                           ": tool changes after that are not known"));
  }
  return ran;
}

}  // namespace fatc::io
