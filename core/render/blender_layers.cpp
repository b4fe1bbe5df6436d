#include "core/render/blender_layers.h"

#include <filmback/render_passes.h>

#include <algorithm>
#include <vector>

namespace fb {

void name_beauty_as_combined(Image& image) {
  for (size_t c = 0; c < 3; ++c)
    image.channels[c] = pass_channel_name("Combined", "RGB"[c]);
  const size_t n = image.channels.size(), pixels = size_t(image.width) * image.height;
  std::vector<float> with_alpha(pixels * (n + 1), 1.f);
  for (size_t i = 0; i < pixels; ++i)
    std::copy_n(&image.pixels[i * n], n, &with_alpha[i * (n + 1)]);
  image.pixels = std::move(with_alpha);
  image.channels.push_back(pass_channel_name("Combined", 'A'));
}

void rename_view_layer(Image& image, const std::string& view_layer) {
  const std::string prefix = std::string(kViewLayer) + ".";
  for (std::string& channel : image.channels)
    if (channel.starts_with(prefix)) channel = view_layer + "." + channel.substr(prefix.size());
}

void denoising_normal_to_camera_space(Image& image, const Transform& exr_camera_from_world) {
  const auto x = std::find(image.channels.begin(), image.channels.end(),
                           pass_channel_name("Denoising Normal", 'X'));
  if (x == image.channels.end()) return;
  const size_t first = size_t(x - image.channels.begin()), n = image.channels.size();
  const Transform rotation = exr_camera_from_world.without_scale_and_translation();
  for (size_t i = 0; i < size_t(image.width) * image.height; ++i) {
    float* v = &image.pixels[i * n + first];
    Vec3f(rotation.vector(Vec3d(Vec3f(v)))).store(v);
  }
}

}  // namespace fb
