#include "importers/gltf/gltf_camera_panorama.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <string_view>

#include "core/util/error.h"
#include "importers/gltf/gltf_json.h"

namespace fb::gltf {
namespace {

// Each kind and the values it takes (the parameters of its camera plugin, plugins/cameras/KIND;
// absent ones take the plugin's default, Blender's).
struct PanoramaKind {
  std::string_view kind;
  std::initializer_list<std::string_view> keys;
};
const PanoramaKind kKinds[] = {
    {"equirectangular",
     {"latitude_min_rad", "latitude_max_rad", "longitude_min_rad", "longitude_max_rad"}},
    {"fisheye_equidistant", {"fisheye_fov_rad"}},
    {"fisheye_equisolid", {"fisheye_lens_mm", "fisheye_fov_rad"}},
    {"mirrorball", {}},
    {"fisheye_polynomial", {"fisheye_fov_rad", "k0", "k1", "k2", "k3", "k4"}},
    {"central_cylindrical",
     {"central_cylindrical_range_u_min_rad", "central_cylindrical_range_u_max_rad",
      "central_cylindrical_range_v_min_m", "central_cylindrical_range_v_max_m",
      "central_cylindrical_radius_m"}},
    {"equiangular_cubemap_face", {}},
};

// Finite and far beyond any camera's value; each plugin's schema has the exact range.
constexpr double kLargestPanoramaValue = 1e9;

std::string joined(const auto& words) {
  std::string text;
  for (std::string_view w : words)
    text.append(text.empty() ? "" : ", ").append(w);
  return text;
}

}  // namespace

std::optional<CameraModel> read_panorama(const tinygltf::Value& blender_camera,
                                         const std::string& path, const std::string& file) {
  const Fields camera(blender_camera, path, file);
  if (!camera.has("panorama")) return std::nullopt;
  if (camera.type("panorama") != Fields::Type::kObject)
    camera.fail("panorama", "expected an object {\"type\": ..., values}");
  const Fields f = camera.object("panorama");
  const std::optional<std::string> type = f.word("type");
  const auto kind = std::find_if(std::begin(kKinds), std::end(kKinds),
                                 [&](const PanoramaKind& k) { return type && k.kind == *type; });
  if (kind == std::end(kKinds)) {
    std::vector<std::string_view> kinds;
    for (const PanoramaKind& k : kKinds)
      kinds.push_back(k.kind);
    f.fail("type", (type ? "'" + *type + "'" : std::string("absent")) + ", expected one of " +
                       joined(kinds));
  }
  CameraModel model{*type, {}, ValueOrigin::from_file(file, f.path() + ".type")};
  for (const std::string& key : blender_camera.Get("panorama").Keys()) {
    if (key == "type") continue;
    if (std::find(kind->keys.begin(), kind->keys.end(), key) == kind->keys.end())
      f.fail(key.c_str(), "a " + *type + " panorama takes " +
                              (kind->keys.size() ? joined(kind->keys) : std::string("no values")));
    const double x = *f.number(key.c_str(), -kLargestPanoramaValue, kLargestPanoramaValue);
    model.numbers.push_back({key, x, ValueOrigin::from_file(file, f.path() + "." + key)});
  }
  return model;
}

}  // namespace fb::gltf
