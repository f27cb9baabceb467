#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

namespace fatc::test {

/// How the program itself is started: its arguments, what it finds in its
/// environment, where it runs and where its output goes.
struct ProgramStart {
  std::vector<std::string> args;
  std::vector<std::string> env;  ///< "TMPDIR=x" set, "TMPDIR" removed
  std::string folder;            ///< where it runs; empty: here
  std::string out = "/dev/null";
  std::string err = "/dev/null";
};

/// Starts FATC_PROGRAM as `start` says, with every signal at its default (a
/// test runner may ignore SIGINT); its pid.
inline pid_t start_program(const ProgramStart& start) {
  std::vector<std::string> argv{FATC_PROGRAM};
  argv.insert(argv.end(), start.args.begin(), start.args.end());
  const pid_t child = ::fork();
  if (child != 0) return child;
  for (const int signal : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) ::signal(signal, SIG_DFL);
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  for (const std::string& variable : start.env) {
    const auto equals = variable.find('=');
    if (equals == std::string::npos) {
      ::unsetenv(variable.c_str());
    } else {
      ::setenv(variable.substr(0, equals).c_str(), variable.substr(equals + 1).c_str(), 1);
    }
  }
  if (!start.folder.empty() && ::chdir(start.folder.c_str()) != 0) ::_exit(125);
  const int out = ::open(start.out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  const int err = ::open(start.err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (out < 0 || err < 0) ::_exit(125);
  ::dup2(out, STDOUT_FILENO);
  ::dup2(err, STDERR_FILENO);
  std::vector<char*> args;
  for (std::string& arg : argv) args.push_back(arg.data());
  args.push_back(nullptr);
  ::execv(args[0], args.data());
  ::_exit(127);
}

/// Waits for the program: its wait status.
inline int wait_for(pid_t child) {
  int status = 0;
  while (::waitpid(child, &status, 0) < 0) {
  }
  return status;
}

}  // namespace fatc::test
