#include "core/plugin/crash_guard.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "core/util/temporary_file.h"

namespace fb {
namespace {

// Written before the plugin runs, read by the handler: no formatting happens after the fault.
char message[2048];
size_t message_length = 0;

// Big enough for the handler and the sanitizers' own reporting frames.
alignas(16) char alternate_stack[1 << 16];

const char* signal_name(int signal) {
  switch (signal) {
    case SIGSEGV:
      return "SIGSEGV";
    case SIGBUS:
      return "SIGBUS";
    case SIGILL:
      return "SIGILL";
    case SIGFPE:
      return "SIGFPE";
    default:
      return "SIGABRT";
  }
}

void write_all(const char* text, size_t size) {
  while (size > 0) {
    const ssize_t written = write(STDERR_FILENO, text, size);
    if (written <= 0) return;
    text += written;
    size -= size_t(written);
  }
}

void report_and_exit(int signal) {
  write_all(message, message_length);
  const char* name = signal_name(signal);
  write_all(name, std::strlen(name));
  constexpr char kEnd[] = "); no render was started\n";
  write_all(kEnd, sizeof kEnd - 1);
  remove_temporaries_now();
  _exit(1);
}

}  // namespace

PluginCrashGuard::PluginCrashGuard(const std::filesystem::path& file, const char* doing) {
  const int length =
      std::snprintf(message, sizeof message, "filmback: error: %s: the plugin crashed in %s (",
                    file.c_str(), doing);
  message_length = length < 0 ? 0 : std::min(size_t(length), sizeof message - 1);
  stack_t stack{};
  stack.ss_sp = alternate_stack;
  stack.ss_size = sizeof alternate_stack;
  sigaltstack(&stack, &previous_stack_);
  struct sigaction action {};
  action.sa_handler = report_and_exit;
  action.sa_flags = SA_ONSTACK;
  sigemptyset(&action.sa_mask);
  for (size_t i = 0; i < std::size(kSignals); ++i)
    sigaction(kSignals[i], &action, &previous_[i]);
}

PluginCrashGuard::~PluginCrashGuard() {
  for (size_t i = 0; i < std::size(kSignals); ++i)
    sigaction(kSignals[i], &previous_[i], nullptr);
  sigaltstack(&previous_stack_, nullptr);
}

}  // namespace fb
