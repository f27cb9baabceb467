// An interrupted --lint (SIGINT, SIGTERM, SIGHUP) stops rs274, removes its
// scratch folder with the copy of the program, and ends by that signal: the
// real program, signalled while rs274 reads and while the copy is made.
#include "io/interruption.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include "program_run.hpp"
#include "temp_folder.hpp"

namespace fatc {
namespace {

namespace fs = std::filesystem;
using test::text_of;

const std::string kConfig = FATC_SOURCE_DIR "/config/config.json";

class Interrupted : public test::TempFolder {
 protected:
  void SetUp() override {
    TempFolder::SetUp();
    scratch_ = folder_ + "/tmp";
    fs::create_directories(scratch_);
  }

  /// --lint of `program` with TMPDIR in the test's folder, signalled with
  /// `signal` once `ready` is in its scratch folder; its wait status.
  int lint_and_signal(const std::string& program, int signal, const std::string& ready) {
    test::ProgramStart start;
    start.args = {"--lint", program, "--config", kConfig, "--state", folder_ + "/none"};
    start.env = {"TMPDIR=" + scratch_};
    start.err = folder_ + "/err";
    const pid_t lint = test::start_program(start);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (!made(ready) && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    EXPECT_TRUE(made(ready)) << "no " << ready << " in " << scratch_;
    ::kill(lint, signal);
    return test::wait_for(lint);
  }

  /// Whether a scratch folder holds `name`.
  bool made(const std::string& name) const {
    for (const auto& entry : fs::directory_iterator(scratch_)) {
      if (fs::exists(entry.path() / name)) return true;
    }
    return false;
  }

  std::vector<std::string> left_behind() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::recursive_directory_iterator(scratch_)) {
      names.push_back(entry.path().string());
    }
    return names;
  }

  /// A program rs274 reads for its whole 15 s.
  std::string endless() const {
    const std::string path = folder_ + "/endless.ngc";
    std::ofstream(path) << "T1 M6\no100 while [1]\nG0 X10\nG0 X20\no100 endwhile\nM2\n";
    return path;
  }

  std::string scratch_;
};

TEST_F(Interrupted, shouldLeaveNoScratchFolderWhenStoppedWhileRs274Reads) {
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
    // machine.ini is the last file made before rs274 starts.
    const int status = lint_and_signal(endless(), signal, "machine.ini");
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal)
        << io::signal_name(signal) << ": status " << status;
    EXPECT_EQ(left_behind(), std::vector<std::string>{}) << io::signal_name(signal);
    EXPECT_EQ(text_of(folder_ + "/err"), std::string("stopped by ") + io::signal_name(signal) +
                                             ": the program was not read to its end\n");
  }
}

TEST_F(Interrupted, shouldLeaveNoScratchFolderWhenStoppedWhileTheProgramIsCopied) {
  const std::string big = folder_ + "/big.ngc";
  {
    std::ofstream out(big);
    for (int i = 0; i < 1500000; ++i) out << "G1 X" << i % 100 << " Y2 F100\n";
    out << "M2\n";
  }
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
    const int status = lint_and_signal(big, signal, "program.ngc");
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal)
        << io::signal_name(signal) << ": status " << status;
    EXPECT_EQ(left_behind(), std::vector<std::string>{}) << io::signal_name(signal);
  }
}

/// In a child of its own (`ignored`: the signal ignored first, as nohup
/// does): an Interruptible, `signal` raised while it lives; the child's wait
/// status, exit 1 when the Interruptible did not note it, 2 when it noted one it was to leave.
int raised_inside(int signal, bool ignored) {
  const pid_t child = ::fork();
  if (child != 0) return test::wait_for(child);
  const struct rlimit no_core = {0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);  // SIGQUIT's default leaves a core file
  ::signal(signal, ignored ? SIG_IGN : SIG_DFL);
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  {
    const io::Interruptible interruptible;
    ::raise(signal);
    if (io::Interruptible::signal() != (ignored ? 0 : signal)) ::_exit(ignored ? 2 : 1);
  }
  ::_exit(0);  // the signal raised again did not end it
}

TEST(Interruptible, shouldNoteEverySignalATerminalSessionEndsAProgramWithThenEndByIt) {
  // --operator and --lint clean up on each (leave HAL, remove the scratch folder), then end
  // by it: a dropped SSH session's SIGHUP, Ctrl-C, Ctrl-\, kill and a closed pipe alike.
  EXPECT_EQ(std::vector<int>(std::begin(io::kEndingSignals), std::end(io::kEndingSignals)),
            (std::vector<int>{SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE}));
  for (const int signal : io::kEndingSignals) {
    const int status = raised_inside(signal, false);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal)
        << io::signal_name(signal) << ": status " << status;
    EXPECT_STRNE(io::signal_name(signal), "a signal");
  }
}

TEST(Interruptible, shouldLeaveASignalIgnoredAsItFoundIt) {
  for (const int signal : io::kEndingSignals) {
    const int status = raised_inside(signal, true);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
        << io::signal_name(signal) << ": status " << status;
  }
}

TEST(Interruptible, shouldPutTheHandlersBackAndRaiseNothingWhenNoSignalCame) {
  struct sigaction before, after;
  ::sigaction(SIGTERM, nullptr, &before);
  { const io::Interruptible quiet; }
  ::sigaction(SIGTERM, nullptr, &after);
  EXPECT_EQ(io::Interruptible::signal(), 0);
  EXPECT_EQ(after.sa_handler, before.sa_handler);
}

}  // namespace
}  // namespace fatc
