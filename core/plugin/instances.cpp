#include "core/plugin/instances.h"

#include "core/util/error.h"

namespace fb {

void PluginInstance::fail(const char* reason) const {
  throw InputError(located(library_->file().string(), "",
                           std::string(kind_name(library_->descriptor().kind)) + " '" +
                               library_->descriptor().name +
                               "' refused to start: " + (*reason ? reason : "no reason given")));
}

CameraInstance::CameraInstance(std::shared_ptr<const PluginLibrary> library,
                               const BoundParams& params, const fb_camera_setup& setup)
    : PluginInstance(library, library->api<fb_camera_api>().destroy,
                     [&](void** out, fb_error_buffer error) {
                       return library->api<fb_camera_api>().create(params.data(), &setup, out,
                                                                   error);
                     }),
      api_(library->api<fb_camera_api>()) {
  // Asked once, under the guard: the render plans its samples from it before the first pixel.
  const PluginCrashGuard guard(library->file(), "needs()");
  needs_ = api_.needs(instance());
}

std::string CameraInstance::describe() const {
  if (!api_.describe) return {};
  char text[4096] = "";
  const PluginCrashGuard guard(library().file(), "describe()");
  api_.describe(instance(), text, sizeof text);
  text[sizeof text - 1] = '\0';  // whatever the plugin wrote, the host reads a terminated text
  return text;
}

FilterInstance::FilterInstance(std::shared_ptr<const PluginLibrary> library,
                               const BoundParams& params)
    : PluginInstance(library, library->api<fb_filter_api>().destroy,
                     [&](void** out, fb_error_buffer error) {
                       return library->api<fb_filter_api>().create(params.data(), out, error);
                     }),
      api_(library->api<fb_filter_api>()) {
  // Asked once, under the guard: the film and the tiles are sized from it before the first pixel.
  const PluginCrashGuard guard(library->file(), "radius()");
  api_.radius(instance(), radius_px_.data());
}

IntegratorInstance::IntegratorInstance(std::shared_ptr<const PluginLibrary> library,
                                       const BoundParams& params)
    : PluginInstance(library, library->api<fb_integrator_api>().destroy,
                     [&](void** out, fb_error_buffer error) {
                       return library->api<fb_integrator_api>().create(params.data(), out, error);
                     }),
      api_(library->api<fb_integrator_api>()) {
  // The names are the plugin's memory too: read under the guard.
  const PluginCrashGuard guard(library->file(), "channels()");
  const char* names[FB_MAX_CHANNELS] = {};
  const uint32_t count = api_.channels(instance(), names, FB_MAX_CHANNELS);
  // The film and the value buffers hold count channels per ray: more than declared would overflow.
  if (count > FB_MAX_CHANNELS)
    throw InputError(located(library->file().string(), "",
                             "integrator declares " + std::to_string(count) +
                                 " channels, at most " + std::to_string(FB_MAX_CHANNELS) +
                                 " are allowed"));
  for (uint32_t i = 0; i < count; ++i) {
    if (!names[i])
      throw InputError(
          located(library->file().string(), "", "channel " + std::to_string(i) + " has no name"));
    channels_.emplace_back(names[i]);
  }
  if (channels_.size() < 3)
    throw InputError(located(library->file().string(), "",
                             "integrator declares " + std::to_string(channels_.size()) +
                                 " channels, expected at least 3 (the colour)"));
}

}  // namespace fb
