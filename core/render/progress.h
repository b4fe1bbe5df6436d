// Progress of a long render on stderr: a bar with ETA on a terminal, plain periodic lines
// otherwise (logs, CI). Silent for renders that finish within half a second.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <ostream>
#include <thread>

namespace fb {

class Progress {
 public:
  // `total` units of work (pixel samples); `out` is normally std::cerr. A positive `line_every`
  // asks for plain lines at that interval whatever `out` is (--progress-every: a program reading
  // the lines from a pipe, such as the Blender render engine, wants them often).
  Progress(uint64_t total, std::ostream& out, bool terminal,
           std::chrono::steady_clock::duration line_every = {});
  ~Progress();  // stops the reporter and clears the bar
  void advance(uint64_t units = 1) { done_.fetch_add(units, std::memory_order_relaxed); }

 private:
  void report_loop();
  void print(bool final_line);
  uint64_t total_;
  std::atomic<uint64_t> done_{0};
  std::ostream& out_;
  bool terminal_;
  std::chrono::steady_clock::duration line_every_;
  bool printed_ = false;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread reporter_;
};

// Whether stderr is a terminal (decides the bar versus plain lines).
bool stderr_is_terminal();

}  // namespace fb
