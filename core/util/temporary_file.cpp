#include "core/util/temporary_file.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <climits>
#include <cstring>

#include "core/util/error.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

// Fixed storage a signal handler can read without allocating. A writer claims a slot, fills its
// path, then publishes it; the handler reads only published slots.
struct Slot {
  std::atomic<bool> claimed{false}, published{false};
  char path[PATH_MAX] = {};
};
std::array<Slot, 32> registry;

int register_path(const fs::path& path) {
  const std::string text = path.string();
  if (text.size() >= PATH_MAX) return -1;
  for (size_t i = 0; i < registry.size(); ++i) {
    bool expected = false;
    if (!registry[i].claimed.compare_exchange_strong(expected, true)) continue;
    std::memcpy(registry[i].path, text.c_str(), text.size() + 1);
    registry[i].published.store(true, std::memory_order_release);
    return int(i);
  }
  return -1;
}

void unregister(int& slot) {
  if (slot < 0) return;
  registry[size_t(slot)].published.store(false);
  registry[size_t(slot)].claimed.store(false);
  slot = -1;
}

}  // namespace

TemporaryFile::TemporaryFile(const fs::path& file) : file_(file) {
  const fs::path folder = file.has_parent_path() ? file.parent_path() : fs::path(".");
  std::string name = ".";
  name += file.stem().string();
  name += ".filmback-" + std::to_string(getpid()) + file.extension().string();
  temporary_ = folder / name;
  slot_ = register_path(temporary_);
}

TemporaryFile::~TemporaryFile() {
  if (!committed_) {
    std::error_code ignored;
    fs::remove(temporary_, ignored);
  }
  unregister(slot_);
}

bool TemporaryFile::commit(std::string& why) {
  std::error_code ec;
  fs::rename(temporary_, file_, ec);
  if (ec) {
    why = ec.message();
    return false;
  }
  committed_ = true;
  unregister(slot_);
  return true;
}

void write_atomically(const fs::path& file,
                      const std::function<std::string(const fs::path&)>& write) {
  TemporaryFile temporary(file);
  std::string why = write(temporary.path());
  if (why.empty()) temporary.commit(why);
  if (!why.empty()) throw InputError("'" + file.string() + "': could not be written (" + why + ")");
}

void remove_temporaries_now() {
  for (Slot& slot : registry)
    if (slot.published.load(std::memory_order_acquire)) unlink(slot.path);
}

}  // namespace fb
