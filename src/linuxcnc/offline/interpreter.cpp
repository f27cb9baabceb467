#include "interpreter.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "core/program/interpreter_inputs.hpp"
#include "core/program/interpreter_output.hpp"
#include "core/program/numbered_program.hpp"
#include "ini.hpp"
#include "io/files.hpp"
#include "io/interruption.hpp"
#include "machine_ini.hpp"
#include "rs274_child.hpp"

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
    result += (result.empty() ? "" : ":") + absolute(tilde_expanded(folder));
  }
  return result;
}

/// A folder of its own for the interpreter's inputs, removed with it.
class ScratchFolder {
 public:
  explicit ScratchFolder(std::string& error) {
    // Its undefined/ folder goes into the INI's SUBROUTINE_PATH, which LinuxCNC cuts.
    const std::string name = "/fatc_preflight_XXXXXX";
    const auto root =
        scratch_root(program::kMaxFolderLength - name.size() - std::strlen("/undefined"), error);
    if (!root) return;
    std::string pattern = *root + name;
    if (::mkdtemp(pattern.data()) == nullptr) {
      error = "cannot make a folder for the interpreter's files in " + shown_path(*root) + " (" +
              std::strerror(errno) + "; TMPDIR chooses where)";
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

  /// Makes `name` in the folder for a text written piece by piece (the
  /// program's numbered copy: FileWriter takes a whole text, and this one is
  /// never whole in memory), created exclusively, never through a link, in a
  /// folder only this user can write in. Its descriptor, or -1 and `error`.
  int create(const std::string& name, std::string& error) const {
    const std::string path = path_ + "/" + name;
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (fd < 0)
      error = "cannot write " + path + " for the interpreter (" + std::strerror(errno) + ")";
    return fd;
  }

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
  ScratchFolder scratch(error);
  if (!scratch.made()) return std::nullopt;
  // The program numbered as it is read, straight into the interpreter's copy.
  const std::string program_copy = scratch.path() + "/program.ngc";
  const int copy = scratch.create("program.ngc", error);
  if (copy < 0) return std::nullopt;
  int write_error = 0;
  auto write_out = [&](const std::string& text) {
    for (std::size_t done = 0; write_error == 0 && done < text.size();) {
      const ssize_t n = ::write(copy, text.data() + done, text.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) write_error = errno;
      done += n > 0 ? static_cast<std::size_t>(n) : 0;
    }
  };
  program::LineNumberer numberer;
  std::uint64_t file_bytes = 0;
  const bool read = read_file_pieces(input.program_path, input.max_program_bytes, file_bytes, error,
                                     [&](std::string_view piece) {
                                       numberer.add(piece);
                                       if (numberer.text_size() >= 64 * 1024) {
                                         write_out(numberer.take_text());
                                       }
                                     });
  const bool cut = file_bytes > input.max_program_bytes;
  numberer.finish(cut);
  write_out(numberer.take_text());
  if (::close(copy) != 0 && write_error == 0) write_error = errno;
  if (!read) return std::nullopt;
  if (write_error != 0) {
    error = "cannot write " + program_copy + " for the interpreter (" + std::strerror(write_error) +
            ")";
    return std::nullopt;
  }
  program::InterpreterRun run;
  if (const auto& nul = numberer.nul()) {
    run.problems.push_back(finding(name, nul->line, nul->text));
    return run;
  }
  if (cut) {
    // A cut file ends at its last whole line: half a line could read as another word.
    run.problems.push_back(
        finding(name, 0,
                "only the first " + std::to_string(numberer.bytes()) + " of its " +
                    std::to_string(file_bytes) + " bytes read (the lint reads at most " +
                    amount(input.max_program_bytes) + " of G-code): tool changes after line " +
                    std::to_string(numberer.lines()) + " are not known"));
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
  const auto table_copy = scratch.write("tools.tbl", table.text, error);
  if (!table_copy) return std::nullopt;
  std::string parameters;
  if (ini) {
    if (const auto file = ini->get("RS274NGC", "PARAMETER_FILE")) {
      std::string ignored;
      parameters = program::interpreter_parameters(
          read_small_file(from_folder(*file, machine_folder), ignored).value_or(""),
          1.0 / (units_per_mm * 25.4));
    }
  }
  const auto parameter_copy = scratch.write("parameters.var", parameters, error);
  if (!parameter_copy) return std::nullopt;

  // A call of a subroutine the program does not define finds, after every
  // folder of the machine's, an empty file: rs274 stops there at once, where
  // it would read the rest of the program looking for it, once for each call.
  std::string stub_folder;
  if (const auto undefined = numberer.undefined_calls(); !undefined.empty()) {
    stub_folder = scratch.path() + "/undefined";
    if (::mkdir(stub_folder.c_str(), 0700) != 0) {
      error = "cannot make " + stub_folder + " for the interpreter (" + std::strerror(errno) + ")";
      return std::nullopt;
    }
    for (const std::string& sub : undefined) {
      if (!scratch.write("undefined/" + sub + ".ngc", "", error)) return std::nullopt;
    }
  }
  std::string folders = input.subroutine_path ? absolute_folders(*input.subroutine_path) : "";
  for (const std::string& folder : folders_of(folders)) {
    if (folder.size() > program::kMaxFolderLength) {
      error = "--subroutine-path: " + shown_path(folder) + ": over the " +
              std::to_string(program::kMaxFolderLength) +
              " characters LinuxCNC reads of a folder in its INI";
      return std::nullopt;
    }
  }
  // rs274 runs with the scratch folder as its HOME: a `~/` of the INI's is
  // the user's, given as such. The INI's folders stay relative: rs274 runs
  // in the INI's folder, as LinuxCNC does.
  if (ini) {
    // Searched before SUBROUTINE_PATH: where it is the user's home, it goes first of them.
    if (const auto prefix = ini->get("DISPLAY", "PROGRAM_PREFIX"); prefix && prefix->rfind("~/", 0) == 0) {
      folders += (folders.empty() ? "" : ":") + tilde_expanded(*prefix);
    }
    if (const auto own = ini->get("RS274NGC", "SUBROUTINE_PATH")) {
      for (const std::string& folder : folders_of(*own)) {
        if (!folder.empty()) folders += (folders.empty() ? "" : ":") + tilde_expanded(folder);
      }
    }
  }
  if (!stub_folder.empty()) folders += (folders.empty() ? "" : ":") + stub_folder;
  const std::string stand_in_folder = scratch.path() + "/stand_ins";
  if (::mkdir(stand_in_folder.c_str(), 0700) != 0) {
    error = "cannot make " + stand_in_folder + " for the interpreter (" + std::strerror(errno) + ")";
    return std::nullopt;
  }
  for (const program::StandIn& stand_in : program::preflight_stand_ins()) {
    if (!scratch.write("stand_ins/" + stand_in.name + ".ngc", stand_in.text, error)) return std::nullopt;
  }
  // First where the INI's M6 runs it: LinuxCNC reads at most ten folders
  // (those that exist), and the undefined calls' folder, last, matters less.
  const auto remaps = ini ? ini->get_all("RS274NGC", "REMAP") : std::vector<std::string>{};
  if (std::any_of(remaps.begin(), remaps.end(), program::is_own_m6_remap)) {
    folders = stand_in_folder + (folders.empty() ? "" : ":") + folders;
  }
  // The INI's user M-codes, which LinuxCNC's task runs and tells the interpreter of.
  std::string toplevel;
  if (const auto codes = ini ? user_m_codes(*ini, machine_folder) : std::vector<int>{};
      !codes.empty()) {
    const auto module = scratch.write(
        "user_m_codes.py", program::user_m_code_module(codes, ini->get("PYTHON", "TOPLEVEL")),
        error);
    if (!module) return std::nullopt;
    toplevel = *module;
  }
  // The INI as LinuxCNC runs with it: its #INCLUDE lines expanded.
  const auto written = scratch.write(
      "machine.ini",
      program::ini_for_preflight(ini ? ini->text() : std::string(), folders, toplevel), error);
  if (!written) return std::nullopt;
  const std::vector<std::string> argv = {
      input.rs274,     "-i", *written, "-t", *table_copy,  "-v",
      *parameter_copy, "-g", "-n",     "0",  program_copy, "/dev/fd/" + std::to_string(kCallsFd)};

  program::ProgramGiven given;
  given.name = name;
  given.numbered_path = program_copy;
  given.stub_folder = stub_folder;
  given.input_lines = numberer.input_lines();
  given.lines = numberer.lines();
  program::InterpreterOutput output(std::move(given), table.tool_of_row);
  output.listen(input.listener);
  // Interrupted while the copies were made: rs274 is not started.
  const auto ending = Interruptible::signal() != 0
                          ? std::nullopt
                          : run_rs274(argv, machine_folder, scratch.path(), input.seconds,
                                      input.max_output_bytes, output, error);
  if (const int signal = Interruptible::signal(); signal != 0) {
    error = std::string("stopped by ") + signal_name(signal) + ": the program was not read to its end";
    return std::nullopt;
  }
  if (!ending) return std::nullopt;
  if (WIFEXITED(ending->status) && WEXITSTATUS(ending->status) >= 126) {
    error = shown_path(input.rs274) + ": cannot run it" +
            (WEXITSTATUS(ending->status) == 126 ? " in " + shown_path(machine_folder) : "");
    return std::nullopt;
  }
  const int reached = output.line();
  program::InterpreterRun ran = output.finish();
  ran.problems.insert(ran.problems.begin(), run.problems.begin(), run.problems.end());
  if (ending->timed_out) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", input.seconds);
    ran.problems.push_back(finding(
        name, 0,
        std::string("LinuxCNC's interpreter (rs274) still ran after ") + seconds + " s, at line " +
            std::to_string(reached) + " of " + std::to_string(numberer.lines()) +
            " (a loop without end, or a program longer than it reads in that time): stopped; "
            "tool changes after that are not known"));
  } else if (ending->too_much_output) {
    ran.problems.push_back(finding(name, 0, "LinuxCNC's interpreter (rs274) printed over " +
                                           amount(input.max_output_bytes) +
                                           ": stopped; tool changes after that are not known"));
  } else if (!WIFEXITED(ending->status) && !output.done()) {
    ran.problems.push_back(finding(name, 0, "LinuxCNC's interpreter (rs274) ended on signal " +
                                           std::to_string(WTERMSIG(ending->status)) +
                                           ": tool changes after that are not known"));
  }
  return ran;
}

}  // namespace fatc::io
