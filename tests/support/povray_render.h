// POV-Ray's own render of a .pov file, for the tests that compare filmback with it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace fb::test {

// Whether `povray` is on the PATH (the tests that need it skip without it).
bool have_povray();

// POV-Ray's render of `pov_file`, one ray through each pixel centre (-A), as linear RGB floats
// (16-bit PNG, File_Gamma 1): width * height * 3 values, top row first, or empty (with a message
// in `why`) if povray failed or its image could not be read. Its log is `pov_file`.log. The
// scene's folder is a library path, so that its files are found as filmback finds them.
std::vector<float> povray_render(const std::filesystem::path& pov_file, int width, int height,
                                 std::string& why);

}  // namespace fb::test
