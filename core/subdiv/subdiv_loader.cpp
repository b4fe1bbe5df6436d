#include "core/subdiv/subdiv_loader.h"

#include <cstdlib>
#include <mutex>
#include <optional>
#include <utility>

#include "core/util/error.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

constexpr const char* kModuleFile = "libfilmback_subdiv.so";

fs::path module_path() {
  if (const char* env = std::getenv("FILMBACK_SUBDIV_MODULE"); env && *env) return env;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path beside = exe.parent_path().parent_path() / "lib/filmback" / kModuleFile;
    if (fs::exists(beside, ec)) return beside;
  }
  return fs::path(FILMBACK_INSTALL_MODULE_DIR) / kModuleFile;
}

SubdivModule open_module() {
  const fs::path file = module_path();
  SharedLibrary library(file);
  if (!library.is_open())
    throw InputError(file.string() +
                     ": cannot load the subdivision module, which the scene's subdivision "
                     "surfaces need (" +
                     library.error() + ")");
  const auto refine = reinterpret_cast<fb_subdiv_refine_fn>(library.symbol(FB_SUBDIV_ENTRY_POINT));
  const auto free = reinterpret_cast<fb_subdiv_free_fn>(library.symbol(FB_SUBDIV_FREE_POINT));
  if (!refine || !free)
    throw InputError(file.string() +
                     ": not filmback's subdivision module (no " FB_SUBDIV_ENTRY_POINT
                     " or " FB_SUBDIV_FREE_POINT ")");
  return {file, refine, free, std::move(library)};
}

}  // namespace

const SubdivModule& subdiv_module() {
  // Not std::call_once's static: a failed load is retried (and reported) by the next caller.
  static std::mutex mutex;
  // Never destroyed: once opened, the module stays mapped for the life of the process, however
  // late a mesh it refined is freed.
  static auto& module = *new std::optional<SubdivModule>;
  const std::lock_guard lock(mutex);
  if (!module) module = open_module();
  return *module;
}

}  // namespace fb
