// Opens libfilmback_subdiv.so, the module that links OpenSubdiv, the first time a render needs
// it: a scene without subdivision surfaces never maps OpenSubdiv into the process.
#pragma once

#include <filesystem>

#include "core/subdiv/subdiv_module.h"
#include "core/util/shared_library.h"

namespace fb {

struct SubdivModule {
  std::filesystem::path file;
  fb_subdiv_refine_fn refine = nullptr;
  fb_subdiv_free_fn free = nullptr;
  SharedLibrary library;  // open while refine and free are in use
};

// The module beside the executable (../lib/filmback/, the build tree's or the install tree's),
// else in the install folder; FILMBACK_SUBDIV_MODULE names another file. Loaded once per process;
// throws InputError naming the file when it is missing or is not the module.
const SubdivModule& subdiv_module();

}  // namespace fb
