#include "core/render/plugin_choice_loader.h"

#include <algorithm>
#include <optional>
#include <string>

#include "core/plugin/params.h"
#include "core/util/error.h"

namespace fb {
namespace {

// Says what is wrong with the plugin `choice` names as its origin calls for: an option's text is
// bad usage ("--filter 'gaussian:sigma=0': ..."), a scene's value bad input naming its file and
// JSON path.
[[noreturn]] void fail(const PluginChoice& choice, const std::string& what) {
  if (choice.origin.typed())
    throw UsageError(choice.origin.path + " '" + choice.typed_text() + "': " + what);
  choice.origin.fail("the plugin " + choice.text() + ": " + what);
}

bool declares(const fb_plugin& plugin, std::string_view key) {
  for (uint32_t i = 0; i < plugin.param_count; ++i)
    if (key == plugin.params[i].name) return true;
  return false;
}

// Loads the plugin `choice` names and creates an instance with its typed values, then the shot's
// numbers the plugin declares and the typed ones leave.
template <typename Instance, typename... Setup>
std::unique_ptr<Instance> instantiate(const PluginLoader& loader, uint32_t kind,
                                      const PluginChoice& choice, const Setup&... setup) {
  auto library = loader.load(kind, choice.name);
  const fb_plugin& plugin = library->descriptor();
  std::optional<BoundParams> params;
  try {
    params.emplace(plugin, choice.typed);
  } catch (const UsageError& e) {
    fail(choice, e.what());
  }
  for (const NamedNumber& n : choice.numbers) {
    if (n.required && !declares(plugin, n.key))
      fail(choice, "it has no parameter '" + n.key + "' for the shot's " + n.origin.text() +
                       " (a lens distortion renders with perspective or thinlens)");
    if (choice.typed_key(n.key) || !declares(plugin, n.key)) continue;
    if (std::string expected = params->set_number(plugin, n.key, n.value); !expected.empty())
      n.origin.fail("the plugin " + choice.name + "'s parameter '" + n.key +
                    "' = " + number_text(n.value) + ": expected " + expected);
  }
  try {
    return std::make_unique<Instance>(library, *params, setup...);
  } catch (const UsageError& e) {
    fail(choice, e.what());
  }
}

}  // namespace

std::unique_ptr<CameraInstance> load_camera(const PluginLoader& loader, const ShotPlan& plan) {
  return instantiate<CameraInstance>(loader, FB_KIND_CAMERA, plan.camera_model,
                                     plan.camera_setup());
}

std::unique_ptr<FilterInstance> load_filter(const PluginLoader& loader,
                                            const PluginChoice& choice) {
  return instantiate<FilterInstance>(loader, FB_KIND_FILTER, choice);
}

std::unique_ptr<IntegratorInstance> load_integrator(const PluginLoader& loader,
                                                    const PluginChoice& choice) {
  return instantiate<IntegratorInstance>(loader, FB_KIND_INTEGRATOR, choice);
}

}  // namespace fb
