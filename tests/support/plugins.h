// The built plugins, for tests: the loader the front end would use from this binary's folder.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/plugin/instances.h"
#include "core/plugin/loader.h"

namespace fb::test {

const PluginLoader& loader();
std::unique_ptr<FilterInstance> make_filter(const std::string& spec);

// The camera plugin `name` with `settings` (its parameters by name, as --camera gives them).
std::unique_ptr<CameraInstance> make_camera(
    const char* name, const fb_camera_setup& setup,
    const std::vector<std::pair<std::string, std::string>>& settings = {});

// The ray of one camera sample at raster point (x, y), at the lens centre and shutter open.
fb_camera_ray generate_ray(const CameraInstance& camera, float x, float y);

}  // namespace fb::test
