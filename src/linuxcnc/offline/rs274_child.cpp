#include "rs274_child.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <string_view>

#include "io/interruption.hpp"

namespace fatc::io {
namespace {

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

/// Reads what is there on `fd` (made non-blocking) into `lines`, at most 16
/// buffers at a time; false once it is closed.
template <class Lines>
bool drain(int fd, std::vector<char>& buffer, Lines& lines, std::size_t& bytes) {
  for (int reads = 0; reads < 16;) {
    const ssize_t got = ::read(fd, buffer.data(), buffer.size());
    if (got > 0) {
      ++reads;
      bytes += static_cast<std::size_t>(got);
      lines.add(buffer.data(), static_cast<std::size_t>(got));
      continue;
    }
    if (got < 0 && errno == EINTR) continue;
    return got < 0 && (errno == EAGAIN || errno == EWOULDBLOCK);
  }
  return true;
}

}  // namespace

std::optional<Rs274Ending> run_rs274(const std::vector<std::string>& argv, const std::string& folder,
                                     const std::string& home, double seconds,
                                     std::size_t max_output_bytes,
                                     program::InterpreterOutput& output, std::string& error) {
  int err_pipe[2];
  int calls_pipe[2];
  if (::pipe2(err_pipe, O_CLOEXEC) != 0) {
    error = std::string("cannot start rs274: ") + std::strerror(errno);
    return std::nullopt;
  }
  if (::pipe2(calls_pipe, O_CLOEXEC) != 0) {
    error = std::string("cannot start rs274: ") + std::strerror(errno);
    ::close(err_pipe[0]);
    ::close(err_pipe[1]);
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
  const pid_t parent = ::getpid();
  // Its CPU time on its own, should no one be left to stop it at `seconds`.
  const rlim_t cpu_seconds = static_cast<rlim_t>(seconds) + 5;
  const pid_t child = ::fork();
  if (child == 0) {
    // A group of its own: a remap's own children go with it when it is stopped.
    ::setpgid(0, 0);
    // It goes with the one who started it (a component stopped with LinuxCNC
    // left rs274 running a program without end, at full CPU, for an hour).
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(126);
    const struct rlimit cpu = {cpu_seconds, cpu_seconds};
    ::setrlimit(RLIMIT_CPU, &cpu);
    const int nothing = ::open("/dev/null", O_RDWR);
    if (nothing >= 0) {
      ::dup2(nothing, STDIN_FILENO);
      ::dup2(nothing, STDOUT_FILENO);
    }
    ::dup2(err_pipe[1], STDERR_FILENO);
    // dup2 onto itself would leave close-on-exec set.
    if (calls_pipe[1] == kCallsFd) {
      ::fcntl(kCallsFd, F_SETFD, 0);
    } else {
      ::dup2(calls_pipe[1], kCallsFd);
    }
    if (::chdir(folder.c_str()) != 0) ::_exit(126);
    ::execve(args[0], args.data(), env.data());
    ::_exit(127);
  }
  ::close(err_pipe[1]);
  ::close(calls_pipe[1]);
  if (child < 0) {
    error = std::string("cannot start rs274: ") + std::strerror(errno);
    ::close(err_pipe[0]);
    ::close(calls_pipe[0]);
    return std::nullopt;
  }
  ::setpgid(child, child);  // also here: whichever of the two runs first

  auto errors = [&](std::string_view line) { output.error_line(line); };
  LineSplitter<decltype(errors)> err_lines(errors);
  auto calls = [&](std::string_view line) { output.canonical_call(line); };
  LineSplitter<decltype(calls)> call_lines(calls);
  Rs274Ending ending;
  std::size_t printed = 0;
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(seconds));
  pollfd fds[2] = {{err_pipe[0], POLLIN, 0}, {calls_pipe[0], POLLIN, 0}};
  for (pollfd& fd : fds) ::fcntl(fd.fd, F_SETFL, O_NONBLOCK);
  std::vector<char> buffer(64 * 1024);
  // Both close when rs274 ends.
  while (fds[0].fd >= 0 || fds[1].fd >= 0) {
    if (Interruptible::signal() != 0) break;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      ending.timed_out = true;
      break;
    }
    const int ready = ::poll(fds, 2, static_cast<int>(std::min<long long>(left.count() + 1, 100)));
    if (ready < 0 && errno != EINTR) break;
    // An error is written at once, the calls before it only when their buffer
    // fills: the errors read first keep the order in which rs274 met them.
    if (fds[0].fd >= 0 && !drain(fds[0].fd, buffer, err_lines, printed)) {
      ::close(fds[0].fd);
      fds[0].fd = -1;
    }
    if (fds[1].fd >= 0 && !drain(fds[1].fd, buffer, call_lines, printed)) {
      ::close(fds[1].fd);
      fds[1].fd = -1;
    }
    if (output.done()) break;
    if (printed > max_output_bytes) {
      ending.too_much_output = true;
      break;
    }
  }
  if (ending.timed_out || ending.too_much_output || output.done() || Interruptible::signal() != 0) {
    ::kill(-child, SIGKILL);
  }
  for (const pollfd& fd : fds) {
    if (fd.fd >= 0) ::close(fd.fd);
  }
  err_lines.end();
  call_lines.end();
  while (::waitpid(child, &ending.status, 0) < 0 && errno == EINTR) {
  }
  return ending;
}

}  // namespace fatc::io
