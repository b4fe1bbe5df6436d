// The folders of the deliberately broken plugins that tests/plugin_abi/CMakeLists.txt builds: one
// defect each, duplicates of one name, and plugins that crash when called.
#pragma once

#include <filesystem>

namespace fb::test {

inline const std::filesystem::path kTestPlugins = FB_TEST_PLUGIN_DIR;
inline const std::filesystem::path kDuplicates = FB_TEST_DUPLICATE_DIR;

}  // namespace fb::test
