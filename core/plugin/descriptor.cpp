#include "core/plugin/descriptor.h"

#include <cctype>
#include <utility>
#include <vector>

#include "core/plugin/abi_layout.h"
#include "core/plugin/loader.h"
#include "core/plugin/params.h"

namespace fb {
namespace {

// The function-table entries each kind must fill, by name, for the "incomplete plugin" message:
// read from the host's copy of the table, which holds no more than the plugin's size covered.
std::vector<std::pair<const char*, const void*>> required_functions(const PluginDescriptor& d) {
  switch (d.plugin.kind) {
    case FB_KIND_CAMERA: {
      const fb_camera_api& a = d.camera;
      return {{"create", (const void*)a.create},
              {"destroy", (const void*)a.destroy},
              {"needs", (const void*)a.needs},
              {"generate_rays", (const void*)a.generate_rays}};
    }
    case FB_KIND_FILTER: {
      const fb_filter_api& a = d.filter;
      return {{"create", (const void*)a.create},     {"destroy", (const void*)a.destroy},
              {"radius", (const void*)a.radius},     {"evaluate", (const void*)a.evaluate},
              {"integral", (const void*)a.integral}, {"sample", (const void*)a.sample}};
    }
    default: {
      const fb_integrator_api& a = d.integrator;
      return {{"create", (const void*)a.create},
              {"destroy", (const void*)a.destroy},
              {"channels", (const void*)a.channels},
              {"radiance", (const void*)a.radiance}};
    }
  }
}

// The kind's function table, read as far as its struct_size covers once that size proved one
// this host reads; an integrator table of the first layout lacks scene_size and scene_api_size,
// which default to that layout's.
std::string read_function_table(const void* api, PluginDescriptor& d) {
  const uint32_t size = *static_cast<const uint32_t*>(api);
  const std::string what = std::string(kind_name(d.plugin.kind)) + " function table";
  std::string problem;
  switch (d.plugin.kind) {
    case FB_KIND_CAMERA:
      problem = check_size(what.c_str(), size, FirstLayout::camera_api, sizeof(fb_camera_api));
      if (problem.empty())
        d.camera = read_covered(api, fields_end(kCameraApiLayouts, size), fb_camera_api{});
      return problem;
    case FB_KIND_FILTER:
      problem = check_size(what.c_str(), size, FirstLayout::filter_api, sizeof(fb_filter_api));
      if (problem.empty()) d.filter = read_covered(api, size, fb_filter_api{});
      return problem;
    default:
      problem =
          check_size(what.c_str(), size, FirstLayout::integrator_api, sizeof(fb_integrator_api));
      if (!problem.empty()) return problem;
      fb_integrator_api defaults{};
      defaults.hit_size = FirstLayout::hit;
      defaults.scene_size = FirstLayout::scene;
      defaults.scene_api_size = FirstLayout::scene_api;
      d.integrator = read_covered(api, fields_end(kIntegratorApiLayouts, size), defaults);
      return {};
  }
}

// The sizes of what the host hands an integrator, as the plugin knows them.
std::string check_integrator_sizes(const fb_integrator_api& a) {
  if (std::string problem =
          check_size("fb_hit (hit_size)", a.hit_size, FirstLayout::hit, sizeof(fb_hit));
      !problem.empty())
    return problem;
  if (std::string problem =
          check_size("fb_scene (scene_size)", a.scene_size, FirstLayout::scene, sizeof(fb_scene));
      !problem.empty())
    return problem;
  return check_size("fb_scene_api (scene_api_size)", a.scene_api_size, FirstLayout::scene_api,
                    sizeof(fb_scene_api));
}

bool is_plugin_name(const char* name) {
  if (!name || !*name) return false;
  for (const char* c = name; *c; ++c)
    if (!(std::islower(static_cast<unsigned char>(*c)) ||
          std::isdigit(static_cast<unsigned char>(*c)) || *c == '_'))
      return false;
  return true;
}

}  // namespace

// Everything the descriptor promises, checked in the order the handshake allows reading it.
std::string check_descriptor(const fb_plugin* raw, PluginDescriptor& d) {
  if (!raw) return "not a filmback plugin: its " FB_ENTRY_POINT "() returned no descriptor";
  if (raw->abi_version != FB_ABI_VERSION)
    return "ABI version mismatch: the plugin was built for plugin ABI " +
           std::to_string(raw->abi_version) + ", this filmback speaks " +
           std::to_string(FB_ABI_VERSION) + " (rebuild it against this SDK)";
  if (std::string problem =
          check_size("fb_plugin", raw->struct_size, FirstLayout::plugin, sizeof(fb_plugin));
      !problem.empty())
    return problem;
  d = PluginDescriptor{};
  d.plugin = read_covered(raw, raw->struct_size, fb_plugin{});
  const fb_plugin& p = d.plugin;
  if (p.kind < FB_KIND_CAMERA || p.kind > FB_KIND_INTEGRATOR)
    return "unknown plugin kind " + std::to_string(p.kind) +
           " (expected camera, filter or integrator)";
  if (!is_plugin_name(p.name))
    return "invalid plugin name (expected lower-case letters, digits and '_')";
  if (!p.version || !p.summary) return "descriptor lacks a version or a summary";
  if (p.param_count > 0 && !p.params) return "descriptor declares parameters but lists none";
  for (uint32_t i = 0; i < p.param_count; ++i) {
    const fb_param_desc& desc = p.params[i];
    if (!desc.name || !desc.default_value || !desc.unit || !desc.doc)
      return "parameter " + std::to_string(i) + " lacks a name, default, unit or doc";
    fb_value value;
    if (std::string expected = parse_param_value(desc, desc.default_value, value);
        !expected.empty())
      return std::string("parameter '") + desc.name + "' has default '" + desc.default_value +
             "', expected " + expected;
  }
  if (!p.api) return std::string("incomplete plugin: no ") + kind_name(p.kind) + " function table";
  if (std::string problem = read_function_table(p.api, d); !problem.empty()) return problem;
  for (const auto& [name, function] : required_functions(d))
    if (!function)
      return std::string("incomplete plugin: its ") + kind_name(p.kind) +
             " function table lacks '" + name + "'";
  if (p.kind == FB_KIND_INTEGRATOR) return check_integrator_sizes(d.integrator);
  return {};
}

}  // namespace fb
