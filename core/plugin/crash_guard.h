// A plugin runs inside filmback's process, so a fault in its code kills the process. While
// filmback runs plugin code before a render (the entry point, the descriptor's checks, create()),
// a crash there (SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT) is reported as an error naming the file
// and the process exits with status 1 (docs/reliability.md, "Plugins").
//
// After such a signal the process's memory can no longer be trusted (the plugin may have written
// anywhere, a lock may be held), so the handler only writes its preformatted message, removes
// registered temporary files (remove_temporaries_now) and calls _exit(1): all async-signal-safe,
// nothing that allocates, locks or returns into the faulting code. Rendering never continues.
#pragma once

#include <csignal>
#include <filesystem>
#include <iterator>

namespace fb {

// Installs the handlers (on an alternate stack, so a stack overflow is caught too) for its
// lifetime on the calling thread's behalf, and puts back the previous ones after. Guards do not
// nest; the one in effect is the most recent.
class PluginCrashGuard {
 public:
  // `doing` says what the plugin was doing: "its entry point", "create()".
  PluginCrashGuard(const std::filesystem::path& file, const char* doing);
  ~PluginCrashGuard();
  PluginCrashGuard(const PluginCrashGuard&) = delete;
  PluginCrashGuard& operator=(const PluginCrashGuard&) = delete;

 private:
  static constexpr int kSignals[] = {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT};
  struct sigaction previous_[std::size(kSignals)];
  stack_t previous_stack_;
};

}  // namespace fb
