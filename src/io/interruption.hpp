#pragma once

namespace fatc::io {

/// While one lives, SIGINT, SIGTERM and SIGHUP only note that they came (the
/// handler sets a flag), so what is under way can stop its child and remove
/// its scratch files; when it ends, the handlers are put back and the signal
/// that came is raised again: the shell sees the program ended by it, as any
/// Unix tool. A signal ignored when it starts (nohup) stays ignored.
class Interruptible {
 public:
  Interruptible();
  ~Interruptible();
  Interruptible(const Interruptible&) = delete;
  Interruptible& operator=(const Interruptible&) = delete;

  /// The signal that came while one lived, 0 none.
  static int signal();
};

/// "SIGINT", "SIGTERM", "SIGHUP": the name of `signal` for a message.
const char* signal_name(int signal);

}  // namespace fatc::io
