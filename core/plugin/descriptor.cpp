#include "core/plugin/descriptor.h"

#include <cctype>
#include <utility>
#include <vector>

#include "core/plugin/loader.h"
#include "core/plugin/params.h"

namespace fb {
namespace {

size_t api_size(uint32_t kind) {
  switch (kind) {
    case FB_KIND_CAMERA:
      return sizeof(fb_camera_api);
    case FB_KIND_FILTER:
      return sizeof(fb_filter_api);
    default:
      return sizeof(fb_integrator_api);
  }
}

// The function-table entries each kind must fill, by name, for the "incomplete plugin" message.
// Read only after the table's struct_size matched api_size(): a smaller table from another SDK
// would otherwise be read past its end.
std::vector<std::pair<const char*, const void*>> required_functions(const fb_plugin& p) {
  switch (p.kind) {
    case FB_KIND_CAMERA: {
      const auto* a = static_cast<const fb_camera_api*>(p.api);
      return {{"create", (const void*)a->create},
              {"destroy", (const void*)a->destroy},
              {"needs", (const void*)a->needs},
              {"generate_rays", (const void*)a->generate_rays}};
    }
    case FB_KIND_FILTER: {
      const auto* a = static_cast<const fb_filter_api*>(p.api);
      return {{"create", (const void*)a->create},     {"destroy", (const void*)a->destroy},
              {"radius", (const void*)a->radius},     {"evaluate", (const void*)a->evaluate},
              {"integral", (const void*)a->integral}, {"sample", (const void*)a->sample}};
    }
    default: {
      const auto* a = static_cast<const fb_integrator_api*>(p.api);
      return {{"create", (const void*)a->create},
              {"destroy", (const void*)a->destroy},
              {"channels", (const void*)a->channels},
              {"radiance", (const void*)a->radiance}};
    }
  }
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
std::string check_descriptor(const fb_plugin* p) {
  if (!p) return "not a filmback plugin: its " FB_ENTRY_POINT "() returned no descriptor";
  if (p->abi_version != FB_ABI_VERSION)
    return "ABI version mismatch: the plugin was built for plugin ABI " +
           std::to_string(p->abi_version) + ", this filmback speaks " +
           std::to_string(FB_ABI_VERSION) + " (rebuild it against this SDK)";
  if (p->struct_size != sizeof(fb_plugin))
    return "descriptor size mismatch: the plugin's fb_plugin is " + std::to_string(p->struct_size) +
           " bytes, this filmback's is " + std::to_string(sizeof(fb_plugin)) +
           " (rebuild it against this SDK)";
  if (p->kind < FB_KIND_CAMERA || p->kind > FB_KIND_INTEGRATOR)
    return "unknown plugin kind " + std::to_string(p->kind) +
           " (expected camera, filter or integrator)";
  if (!is_plugin_name(p->name))
    return "invalid plugin name (expected lower-case letters, digits and '_')";
  if (!p->version || !p->summary) return "descriptor lacks a version or a summary";
  if (p->param_count > 0 && !p->params) return "descriptor declares parameters but lists none";
  for (uint32_t i = 0; i < p->param_count; ++i) {
    const fb_param_desc& d = p->params[i];
    if (!d.name || !d.default_value || !d.unit || !d.doc)
      return "parameter " + std::to_string(i) + " lacks a name, default, unit or doc";
    fb_value value;
    if (std::string expected = parse_param_value(d, d.default_value, value); !expected.empty())
      return std::string("parameter '") + d.name + "' has default '" + d.default_value +
             "', expected " + expected;
  }
  if (!p->api)
    return std::string("incomplete plugin: no ") + kind_name(p->kind) + " function table";
  const uint32_t table_size = *static_cast<const uint32_t*>(p->api);
  if (table_size != api_size(p->kind))
    return std::string(kind_name(p->kind)) + " function table size mismatch: the plugin's is " +
           std::to_string(table_size) + " bytes, this filmback's is " +
           std::to_string(api_size(p->kind)) + " (rebuild it against this SDK)";
  for (const auto& [name, function] : required_functions(*p))
    if (!function)
      return std::string("incomplete plugin: its ") + kind_name(p->kind) +
             " function table lacks '" + name + "'";
  if (p->kind == FB_KIND_INTEGRATOR) {
    const uint32_t hit_size = static_cast<const fb_integrator_api*>(p->api)->hit_size;
    if (hit_size != sizeof(fb_hit))
      return "hit record size mismatch: the plugin's fb_hit is " + std::to_string(hit_size) +
             " bytes, this filmback's is " + std::to_string(sizeof(fb_hit)) +
             " (rebuild it against this SDK)";
  }
  return {};
}

}  // namespace fb
