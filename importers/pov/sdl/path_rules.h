// Where a POV-Ray scene may read files: inside its own folder and the library folders, never led
// out of them by '..' or a symbolic link (docs/pov.md "The language"). #include, #fopen and the
// paths an .ini names follow the same rule.
#pragma once

#include <filesystem>

namespace fb::pov {

// Whether `path` lies inside `folder` as written (both lexically normal or made so): no '..'
// leads out of it.
bool lexically_inside(const std::filesystem::path& path, const std::filesystem::path& folder);

// Whether `path` lies inside `folder` once both have their symbolic links followed.
bool really_inside(const std::filesystem::path& path, const std::filesystem::path& folder);

}  // namespace fb::pov
