#include "support/povray_render.h"

#include <OpenImageIO/imageio.h>

#include <cstdlib>

namespace fb::test {

bool have_povray() {
  return std::system("command -v povray > /dev/null 2>&1") == 0;
}

std::vector<float> povray_render(const std::filesystem::path& pov_file, int width, int height,
                                 std::string& why) {
  const std::filesystem::path png = std::filesystem::path(pov_file).replace_extension(".png");
  const std::string command = "povray +W" + std::to_string(width) + " +H" + std::to_string(height) +
                              " -D -A +FN16 File_Gamma=1.0 +L'" + pov_file.parent_path().string() +
                              "' +I'" + pov_file.string() + "' +O'" + png.string() + "' > '" +
                              pov_file.string() + ".log' 2>&1";
  if (std::system(command.c_str()) != 0) {
    why = "failed: " + command;
    return {};
  }
  auto in = OIIO::ImageInput::open(png.string());
  if (!in || in->spec().width != width || in->spec().height != height) {
    why = "no " + std::to_string(width) + "x" + std::to_string(height) + " image from " + command;
    return {};
  }
  const int channels = in->spec().nchannels;
  std::vector<float> pixels(size_t(width) * height * channels);
  if (!in->read_image(0, 0, 0, -1, OIIO::TypeDesc::FLOAT, pixels.data())) {
    why = "unreadable " + png.string();
    return {};
  }
  std::vector<float> rgb;
  for (size_t i = 0; i < size_t(width) * height; ++i)
    for (int c = 0; c < 3; ++c)
      rgb.push_back(pixels[i * channels + c]);
  return rgb;
}

}  // namespace fb::test
