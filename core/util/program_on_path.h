// Where a program named without a folder is found, as posix_spawnp and the shell find it: the
// first folder of $PATH (an empty entry is the current folder) holding an executable file of
// that name.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace fb {

// The file as found (not resolved through symbolic links), or none.
std::optional<std::filesystem::path> program_on_path(const std::string& name);

}  // namespace fb
