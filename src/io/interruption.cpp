#include "interruption.hpp"

#include <signal.h>

#include <csignal>
#include <iterator>
#include <string>

namespace fatc::io {
namespace {

constexpr std::size_t kCount = std::size(kEndingSignals);
volatile std::sig_atomic_t came = 0;
struct sigaction before[kCount];
bool installed[kCount] = {};

void note(int signal) {
  if (came == 0) came = signal;
}

}  // namespace

Interruptible::Interruptible() {
  came = 0;
  for (std::size_t i = 0; i < kCount; ++i) {
    struct sigaction action = {};
    action.sa_handler = note;
    sigemptyset(&action.sa_mask);
    // No SA_RESTART: a poll() or read() under way returns at once with EINTR.
    action.sa_flags = 0;
    if (::sigaction(kEndingSignals[i], nullptr, &before[i]) != 0 ||
        before[i].sa_handler == SIG_IGN) {
      continue;
    }
    installed[i] = ::sigaction(kEndingSignals[i], &action, nullptr) == 0;
  }
}

Interruptible::~Interruptible() {
  for (std::size_t i = 0; i < kCount; ++i) {
    if (installed[i]) ::sigaction(kEndingSignals[i], &before[i], nullptr);
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
    case SIGQUIT:
      return "SIGQUIT";
    case SIGPIPE:
      return "SIGPIPE";
  }
  return "a signal";
}

}  // namespace fatc::io
