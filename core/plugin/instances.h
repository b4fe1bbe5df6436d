// C++ owners of plugin instances: each holds its library open, creates the instance through the
// C ABI and destroys it on the way out. The render talks to plugins only through these.
#pragma once

#include <array>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <filmback/plugin_abi.h>

#include "core/plugin/crash_guard.h"
#include "core/plugin/loader.h"
#include "core/plugin/params.h"

namespace fb {

class PluginInstance {
 public:
  const PluginLibrary& library() const { return *library_; }
  const char* name() const { return library_->descriptor().name; }

 protected:
  using Destroy = void (*)(void*);
  // `create` is called with an error buffer; a non-zero return throws InputError naming the file.
  template <typename Create>
  PluginInstance(std::shared_ptr<const PluginLibrary> library, Destroy destroy, Create&& create)
      : library_(std::move(library)), instance_(nullptr, destroy) {
    char error[512] = "";
    void* instance = nullptr;
    int status;
    {
      const PluginCrashGuard guard(library_->file(), "create()");
      status = create(&instance, fb_error_buffer{error, sizeof error});
    }
    if (status != 0 || !instance) fail(error);
    instance_.reset(instance);
  }
  void* instance() const { return instance_.get(); }

 private:
  [[noreturn]] void fail(const char* reason) const;
  std::shared_ptr<const PluginLibrary> library_;
  std::unique_ptr<void, Destroy> instance_;
};

class CameraInstance : public PluginInstance {
 public:
  CameraInstance(std::shared_ptr<const PluginLibrary> library, const BoundParams& params,
                 const fb_camera_setup& setup);
  uint32_t needs() const { return needs_; }
  // What the camera derives from its values, as lines for `filmback info`; empty when it says
  // nothing (or was built before fb_camera_api::describe).
  std::string describe() const;
  void generate_rays(std::span<const fb_camera_sample> samples, fb_camera_ray* rays) const {
    api_.generate_rays(instance(), samples.data(), samples.size(), rays);
  }

 private:
  const fb_camera_api& api_;
  uint32_t needs_ = 0;
};

class FilterInstance : public PluginInstance {
 public:
  FilterInstance(std::shared_ptr<const PluginLibrary> library, const BoundParams& params);
  void radius(float radius_px[2]) const {
    radius_px[0] = radius_px_[0], radius_px[1] = radius_px_[1];
  }
  float evaluate(float x, float y) const { return api_.evaluate(instance(), x, y); }
  double integral() const { return api_.integral(instance()); }
  void sample(std::span<const float> u, fb_filter_sample* samples) const {
    api_.sample(instance(), u.data(), u.size() / 2, samples);
  }

 private:
  const fb_filter_api& api_;
  std::array<float, 2> radius_px_{};
};

class IntegratorInstance : public PluginInstance {
 public:
  IntegratorInstance(std::shared_ptr<const PluginLibrary> library, const BoundParams& params);
  const std::vector<std::string>& channels() const { return channels_; }
  // What the plugin knows of what the host hands it (plugin_abi.h, "Growth"): the host writes hit
  // records of hit_size bytes, and gives a scene and a function table of these sizes.
  uint32_t hit_size() const { return api_.hit_size; }
  uint32_t scene_size() const { return api_.scene_size; }
  uint32_t scene_api_size() const { return api_.scene_api_size; }
  void radiance(const fb_scene& scene, fb_trace_context* context, std::span<const fb_ray> rays,
                float* values) const {
    api_.radiance(instance(), &scene, context, rays.data(), rays.size(), values);
  }

 private:
  const fb_integrator_api& api_;
  std::vector<std::string> channels_;
};

}  // namespace fb
