// SIGINT and SIGTERM during a render (docs/cli.md, "Interrupts and checkpoints"): the first asks
// the render to stop, so the image it has can be written; the second ends the process at once,
// removing any temporary file first.
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

  // Becomes true at the first signal; what RenderControl::cancel watches.
  const std::atomic<bool>& requested() const;
  // The first signal's number (SIGINT or SIGTERM), 0 before any.
  int signal_number() const;
  // Seconds from the first signal to now (CLOCK_MONOTONIC); 0 before any.
  double seconds_since_signal() const;
};

}  // namespace fb
