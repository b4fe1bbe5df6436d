// Loads the plugins a shot plan names (core/render/shot_plan.h), each with its values: the pairs
// typed with it, then the shot's numbers on the parameters of the same name the plugin declares
// and the typed pairs leave. An error names where the choice or the value came from: an option
// (bad usage, exit 2) or the scene's file and JSON path (bad input, exit 1).
#pragma once

#include <memory>

#include "core/plugin/instances.h"
#include "core/plugin/loader.h"
#include "core/render/shot_plan.h"

namespace fb {

std::unique_ptr<CameraInstance> load_camera(const PluginLoader& loader, const ShotPlan& plan);
std::unique_ptr<FilterInstance> load_filter(const PluginLoader& loader, const PluginChoice& choice);
std::unique_ptr<IntegratorInstance> load_integrator(const PluginLoader& loader,
                                                    const PluginChoice& choice);

}  // namespace fb
