#include "core/subdiv/subdiv_loader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <mutex>
#include <optional>

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
  SubdivModule m;
  m.file = module_path();
  const std::string name = m.file.string();
  // RTLD_NOW: a missing OpenSubdiv is reported here, naming the file, not at the first call.
  void* handle = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle)
    throw InputError(name +
                     ": cannot load the subdivision module, which the scene's subdivision "
                     "surfaces need (" +
                     dlerror() + ")");
  m.refine = reinterpret_cast<fb_subdiv_refine_fn>(dlsym(handle, FB_SUBDIV_ENTRY_POINT));
  m.free = reinterpret_cast<fb_subdiv_free_fn>(dlsym(handle, FB_SUBDIV_FREE_POINT));
  if (!m.refine || !m.free) {
    dlclose(handle);
    throw InputError(name + ": not filmback's subdivision module (no " FB_SUBDIV_ENTRY_POINT
                            " or " FB_SUBDIV_FREE_POINT ")");
  }
  return m;  // the handle stays open for the life of the process
}

}  // namespace

const SubdivModule& subdiv_module() {
  // Not std::call_once's static: a failed load is retried (and reported) by the next caller.
  static std::mutex mutex;
  static std::optional<SubdivModule> module;
  const std::lock_guard lock(mutex);
  if (!module) module = open_module();
  return *module;
}

}  // namespace fb
