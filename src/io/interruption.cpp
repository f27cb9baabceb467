#include "interruption.hpp"

#include <signal.h>

#include <csignal>
#include <string>

namespace fatc::io {
namespace {

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
volatile std::sig_atomic_t came = 0;
struct sigaction before[3];
bool installed[3] = {false, false, false};

void note(int signal) {
  if (came == 0) came = signal;
}

}  // namespace

Interruptible::Interruptible() {
  came = 0;
  for (int i = 0; i < 3; ++i) {
    struct sigaction action = {};
    action.sa_handler = note;
    sigemptyset(&action.sa_mask);
    // No SA_RESTART: a poll() or read() under way returns at once with EINTR.
    action.sa_flags = 0;
    if (::sigaction(kSignals[i], nullptr, &before[i]) != 0 || before[i].sa_handler == SIG_IGN) {
      continue;
    }
    installed[i] = ::sigaction(kSignals[i], &action, nullptr) == 0;
  }
}

Interruptible::~Interruptible() {
  for (int i = 0; i < 3; ++i) {
    if (installed[i]) ::sigaction(kSignals[i], &before[i], nullptr);
    installed[i] = false;
  }
  if (came != 0) ::raise(came);
}

int Interruptible::signal() { return came; }

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
  }
  return "a signal";
}

}  // namespace fatc::io
