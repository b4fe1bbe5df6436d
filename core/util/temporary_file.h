// Every file filmback writes is written under a temporary name in its target folder and renamed
// into place, so a failed or interrupted write never leaves a half-written file under the real
// name (docs/conventions.md, "Errors"). Temporaries are registered while they exist, so that a
// process killed by a second interrupt can still remove them (remove_temporaries_now, which is
// async-signal-safe).
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace fb {

// A temporary file for `file`: hidden, in the same folder (so rename() is atomic), with the same
// extension (image libraries choose the format by it). Registered until it is renamed or removed.
class TemporaryFile {
 public:
  explicit TemporaryFile(const std::filesystem::path& file);
  ~TemporaryFile();  // removes the temporary unless it was committed
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  const std::filesystem::path& path() const { return temporary_; }
  // Renames the temporary to `file`; false (and errno's message in `why`) if that failed.
  bool commit(std::string& why);

 private:
  std::filesystem::path file_, temporary_;
  int slot_ = -1;  // in the registry; -1: not registered (the registry was full)
  bool committed_ = false;
};

// Writes `file` through a temporary: `write(temporary)` returns what went wrong, or "". Throws
// InputError "'file': could not be written (why)" and leaves no temporary behind on failure.
void write_atomically(const std::filesystem::path& file,
                      const std::function<std::string(const std::filesystem::path&)>& write);

// Removes every registered temporary; only async-signal-safe calls (unlink). For a signal
// handler that is about to _exit().
void remove_temporaries_now();

}  // namespace fb
