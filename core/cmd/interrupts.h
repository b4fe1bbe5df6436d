// SIGINT and SIGTERM (docs/cli.md, "Interrupts and checkpoints"). Once the render loop is about
// to run (arm()), the first asks the render to stop, so that the image it has can be written; a
// second one, or any before that point (nothing to save yet), ends the process at once with
// 128 + the signal, removing any temporary file first.
#pragma once

#include <atomic>

namespace fb {

// Installs the handlers for its lifetime and puts back the previous ones after.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  // From now on the first signal only asks to stop (a render is running, or writing its result).
  void arm();
  // Becomes true at the first signal after arm(); what RenderControl::cancel watches.
  const std::atomic<bool>& requested() const;
  // The first signal's number (SIGINT or SIGTERM), 0 before any.
  int signal_number() const;
  // Seconds from the first signal to now (CLOCK_MONOTONIC); 0 before any.
  double seconds_since_signal() const;
};

}  // namespace fb
