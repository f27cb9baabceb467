#pragma once

#include <csignal>

namespace fatc::io {

/// Every signal a terminal session ends a program with: Ctrl-C (SIGINT),
/// kill (SIGTERM), a closed terminal or a dropped SSH session (SIGHUP),
/// Ctrl-\ (SIGQUIT), and a reader gone from the pipe it writes to (SIGPIPE).
inline constexpr int kEndingSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE};

/// While one lives, each of kEndingSignals only notes that it came (the
/// handler sets a flag), so what is under way can stop its child, remove its
/// scratch files or leave HAL; when it ends, the handlers are put back and the
/// signal that came is raised again: the shell sees the program ended by it,
/// as any Unix tool. A signal ignored when it starts (nohup) stays ignored.
class Interruptible {
 public:
  Interruptible();
  ~Interruptible();
  Interruptible(const Interruptible&) = delete;
  Interruptible& operator=(const Interruptible&) = delete;

  /// The signal that came while one lived, 0 none.
  static int signal();
};

/// "SIGINT", "SIGHUP", ...: the name of `signal` for a message.
const char* signal_name(int signal);

}  // namespace fatc::io
