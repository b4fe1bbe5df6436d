// What importing a deliberately broken glTF file says, for the tests of its error messages.
#pragma once

#include <filesystem>
#include <string>

namespace fb::test {

// The InputError importing `file` raises, or "" when it imports.
std::string import_error(const std::filesystem::path& file);

}  // namespace fb::test
