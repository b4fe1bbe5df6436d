#include "importers/pov/sdl/path_rules.h"

namespace fb::pov {

namespace fs = std::filesystem;

bool lexically_inside(const fs::path& path, const fs::path& folder) {
  const fs::path rel = path.lexically_normal().lexically_relative(folder.lexically_normal());
  return !rel.empty() && *rel.begin() != "..";
}

bool really_inside(const fs::path& path, const fs::path& folder) {
  std::error_code path_error, folder_error;
  const fs::path real = fs::weakly_canonical(path, path_error);
  const fs::path real_folder = fs::weakly_canonical(folder, folder_error);
  return !path_error && !folder_error && lexically_inside(real, real_folder);
}

}  // namespace fb::pov
