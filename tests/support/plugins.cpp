#include "support/plugins.h"

#include "core/plugin/params.h"

namespace fb::test {

const PluginLoader& loader() {
  static const PluginLoader instance(PluginLoader::default_search_dirs());
  return instance;
}

std::unique_ptr<FilterInstance> make_filter(const std::string& text) {
  const PluginSpec spec = parse_plugin_spec(text, "--filter");
  auto library = loader().load(FB_KIND_FILTER, spec.name);
  return std::make_unique<FilterInstance>(library,
                                          BoundParams(library->descriptor(), spec.settings));
}

std::unique_ptr<CameraInstance> make_camera(
    const char* name, const fb_camera_setup& setup,
    const std::vector<std::pair<std::string, std::string>>& settings) {
  auto library = loader().load(FB_KIND_CAMERA, name);
  return std::make_unique<CameraInstance>(library, BoundParams(library->descriptor(), settings),
                                          setup);
}

fb_camera_ray generate_ray(const CameraInstance& camera, float x, float y) {
  fb_camera_sample sample{x, y, 0.f, 0.f, 0.f};
  fb_camera_ray ray;
  camera.generate_rays({&sample, 1}, &ray);
  return ray;
}

}  // namespace fb::test
