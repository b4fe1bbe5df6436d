#include "core/cmd/interrupts.h"

#include <unistd.h>

#include <csignal>
#include <ctime>

#include "core/util/temporary_file.h"

namespace fb {
namespace {

std::atomic<bool> armed{false};
std::atomic<bool> stop_requested{false};
std::atomic<int> first_signal{0};
timespec signalled_at{};  // written by the handler before it publishes stop_requested
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "signal handlers may only touch lock-free atomics");

struct sigaction previous_int, previous_term;

// Only async-signal-safe work: atomics, unlink (through remove_temporaries_now) and _exit.
void on_signal(int signal) {
  int none = 0;
  if (armed.load() && first_signal.compare_exchange_strong(none, signal)) {
    clock_gettime(CLOCK_MONOTONIC, &signalled_at);  // async-signal-safe (POSIX.1-2008)
    stop_requested.store(true);
    return;
  }
  remove_temporaries_now();
  _exit(128 + signal);  // the shell's convention for "ended by signal N"
}

}  // namespace

InterruptGuard::InterruptGuard() {
  armed = false;
  stop_requested = false;
  first_signal = 0;
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &previous_int);
  sigaction(SIGTERM, &action, &previous_term);
}

void InterruptGuard::arm() {
  armed = true;
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGTERM, &previous_term, nullptr);
}

const std::atomic<bool>& InterruptGuard::requested() const {
  return stop_requested;
}

int InterruptGuard::signal_number() const {
  return first_signal.load();
}

double InterruptGuard::seconds_since_signal() const {
  if (!stop_requested.load()) return 0;
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return double(now.tv_sec - signalled_at.tv_sec) +
         1e-9 * double(now.tv_nsec - signalled_at.tv_nsec);
}

}  // namespace fb
