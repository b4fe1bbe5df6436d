// The plugin ABI's growth rule on the host's side (plugin_abi.h, "Growth"; docs/plugins.md, "ABI
// growth"): the first published size of every struct that grows, the check that a plugin's size
// lies between that and this host's, and the copy of a plugin's struct that reads no more than its
// size covers.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include <filmback/plugin_abi.h>

namespace fb {

// The size C gives a struct whose last field ends at `end`: padded to the struct's alignment.
constexpr uint32_t padded_size(size_t end, size_t alignment) {
  return uint32_t((end + alignment - 1) / alignment * alignment);
}

// One published layout of a struct: its size, and where its fields end. The two differ by tail
// padding, where a later layout may append a field: the first layout of fb_integrator_api is 48
// bytes on LP64, its last 4 padding where scene_size now is. A plugin's struct therefore counts
// only up to the fields of its layout, never its padding.
struct Layout {
  uint32_t size, fields_end;
};

// The published layouts of each struct that grew, oldest first: the first is the previous
// published header's (tests/sdk/abi_frozen/filmback/plugin_abi.h, before issue 14), and
// tests/sdk/abi_growth_test.cpp checks it against that header's own sizeof. A growth appends a
// layout here.
inline constexpr Layout kCameraApiLayouts[] = {
    {padded_size(offsetof(fb_camera_api, describe), alignof(fb_camera_api)),
     uint32_t(offsetof(fb_camera_api, describe))},
    {sizeof(fb_camera_api), sizeof(fb_camera_api)}};
inline constexpr Layout kIntegratorApiLayouts[] = {
    {padded_size(offsetof(fb_integrator_api, scene_size), alignof(fb_integrator_api)),
     uint32_t(offsetof(fb_integrator_api, scene_size))},
    {sizeof(fb_integrator_api), sizeof(fb_integrator_api)}};
inline constexpr Layout kHitLayouts[] = {
    {padded_size(offsetof(fb_hit, surface), alignof(float)), uint32_t(offsetof(fb_hit, surface))},
    {sizeof(fb_hit), sizeof(fb_hit)}};
inline constexpr Layout kSceneApiLayouts[] = {
    {uint32_t(offsetof(fb_scene_api, bsdf_eval)), uint32_t(offsetof(fb_scene_api, bsdf_eval))},
    {uint32_t(offsetof(fb_scene_api, sample_lamp)), uint32_t(offsetof(fb_scene_api, sample_lamp))},
    {uint32_t(offsetof(fb_scene_api, closure_weight)),
     uint32_t(offsetof(fb_scene_api, closure_weight))},
    {uint32_t(offsetof(fb_scene_api, medium_segment)),
     uint32_t(offsetof(fb_scene_api, medium_segment))},
    {sizeof(fb_scene_api), sizeof(fb_scene_api)}};
// fb_scene's first layout ends at view_axis; issue 19 appended `povray` and `lamp_count`, then
// `media`.
inline constexpr Layout kSceneLayouts[] = {
    {padded_size(offsetof(fb_scene, povray), alignof(fb_scene)),
     uint32_t(offsetof(fb_scene, view_axis) + sizeof(float[3]))},
    {padded_size(offsetof(fb_scene, media), alignof(fb_scene)),
     uint32_t(offsetof(fb_scene, lamp_count) + sizeof(uint32_t))},
    {sizeof(fb_scene), sizeof(fb_scene)}};

// A growth must change sizeof, else a plugin's size could not tell its layout (plugin_abi.h).
template <size_t N>
constexpr bool sizes_grow(const Layout (&layouts)[N]) {
  for (size_t i = 1; i < N; ++i)
    if (layouts[i].size <= layouts[i - 1].size) return false;
  return true;
}
static_assert(sizes_grow(kCameraApiLayouts) && sizes_grow(kIntegratorApiLayouts) &&
                  sizes_grow(kHitLayouts) && sizes_grow(kSceneApiLayouts) &&
                  sizes_grow(kSceneLayouts),
              "a growth of the plugin ABI must change the struct's sizeof");

struct FirstLayout {
  static constexpr uint32_t plugin = sizeof(fb_plugin);
  static constexpr uint32_t camera_api = kCameraApiLayouts[0].size;
  static constexpr uint32_t filter_api = sizeof(fb_filter_api);
  static constexpr uint32_t integrator_api = kIntegratorApiLayouts[0].size;
  static constexpr uint32_t hit = kHitLayouts[0].size;
  static constexpr uint32_t scene = kSceneLayouts[0].size;
  static constexpr uint32_t scene_api = kSceneApiLayouts[0].size;
};

// The bytes of fields in a plugin's struct of `size` bytes (at least the first layout's): those of
// the newest published layout no larger than it.
template <size_t N>
constexpr uint32_t fields_end(const Layout (&layouts)[N], uint32_t size) {
  uint32_t end = layouts[0].fields_end;
  for (const Layout& layout : layouts)
    if (layout.size <= size) end = layout.fields_end;
  return end;
}

// Empty when a plugin's `size` of `what` ("fb_plugin", "fb_hit (hit_size)") is one this host reads:
// from the first published layout's up to this host's. Otherwise the reason, with both sizes.
std::string check_size(const char* what, uint32_t size, uint32_t first, uint32_t host);

// `defaults` with the first `bytes` of the plugin's struct copied over it: the fields an older
// plugin's layout lacks keep their defaults, and nothing past its fields is read. `bytes` is
// fields_end() of a size that passed check_size(), or that size for a struct that never grew.
template <typename T>
T read_covered(const void* plugin_struct, uint32_t bytes, T defaults) {
  static_assert(std::is_trivially_copyable_v<T>);
  std::memcpy(&defaults, plugin_struct, std::min<size_t>(bytes, sizeof(T)));
  return defaults;
}

}  // namespace fb
