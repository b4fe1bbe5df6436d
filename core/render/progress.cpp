#include "core/render/progress.h"

#include <unistd.h>

#include <cstdio>
#include <string>

namespace fb {
namespace {

std::string format_seconds(double s) {
  char text[32];
  if (s < 60)
    std::snprintf(text, sizeof text, "%.0fs", s);
  else if (s < 3600)
    std::snprintf(text, sizeof text, "%dm%02ds", int(s) / 60, int(s) % 60);
  else
    std::snprintf(text, sizeof text, "%dh%02dm", int(s) / 3600, int(s) % 3600 / 60);
  return text;
}

}  // namespace

bool stderr_is_terminal() {
  return isatty(STDERR_FILENO) == 1;
}

Progress::Progress(uint64_t total, std::ostream& out, bool terminal,
                   std::chrono::steady_clock::duration line_every)
    : total_(total),
      out_(out),
      terminal_(terminal && line_every <= line_every.zero()),
      line_every_(line_every),
      start_(std::chrono::steady_clock::now()) {
  reporter_ = std::thread([this] { report_loop(); });
}

Progress::~Progress() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  reporter_.join();
  if (printed_) print(true);
}

void Progress::report_loop() {
  using namespace std::chrono_literals;
  const bool asked = line_every_ > line_every_.zero();
  const std::chrono::steady_clock::duration first = asked ? line_every_ : 500ms;
  const std::chrono::steady_clock::duration period = asked       ? line_every_
                                                     : terminal_ ? 250ms
                                                                 : 10000ms;
  std::unique_lock lock(mutex_);
  if (wake_.wait_for(lock, first, [this] { return stop_; })) return;
  do
    print(false);
  while (!wake_.wait_for(lock, period, [this] { return stop_; }));
}

void Progress::print(bool final_line) {
  printed_ = true;
  const uint64_t done = std::min(done_.load(std::memory_order_relaxed), total_);
  const double fraction = total_ ? double(done) / double(total_) : 1.0;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::string eta = fraction > 0 ? format_seconds(elapsed / fraction - elapsed) : "?";
  char line[160];
  if (terminal_) {
    constexpr int kWidth = 30;
    const int filled = int(fraction * kWidth);
    std::snprintf(line, sizeof line, "\r[%s%s] %5.1f%%  %s elapsed, ETA %s ",
                  std::string(filled, '#').c_str(), std::string(kWidth - filled, '.').c_str(),
                  100 * fraction, format_seconds(elapsed).c_str(), eta.c_str());
    out_ << line;
    if (final_line) out_ << "\r\033[K";  // clear the bar: the summary line follows
  } else if (!final_line) {
    std::snprintf(line, sizeof line, "progress: %.1f%% after %s, ETA %s\n", 100 * fraction,
                  format_seconds(elapsed).c_str(), eta.c_str());
    out_ << line;
  }
  out_.flush();
}

}  // namespace fb
