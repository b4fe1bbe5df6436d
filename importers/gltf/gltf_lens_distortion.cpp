#include "importers/gltf/gltf_lens_distortion.h"

#include <algorithm>
#include <array>
#include <string>
#include <string_view>

#include "core/util/error.h"

namespace fb::gltf {
namespace {

// Blender 3.4's models (MovieTrackingCamera.distortion_model) and the coefficients each has,
// under the names of Track > Camera > Lens; the plugin parameters prefix them with the model.
struct ModelCoefficients {
  std::string_view model;   // as the add-on writes it: Blender's enum word, lower case
  std::string_view prefix;  // of the plugin parameters: "division" -> "division_k1"
  std::vector<std::string_view> names;
};
const std::array<ModelCoefficients, 4> kModels = {{
    {"polynomial", "polynomial", {"k1", "k2", "k3"}},
    {"division", "division", {"k1", "k2"}},
    {"nuke", "nuke", {"k1", "k2"}},
    {"brown", "brown", {"k1", "k2", "k3", "k4", "p1", "p2"}},
}};
constexpr std::array<const char*, 6> kAllCoefficients = {"k1", "k2", "k3", "k4", "p1", "p2"};

// Bounds far beyond any solved camera, the plugin parameters' own.
constexpr double kMaxCoefficient = 1e6;
constexpr double kMaxClipSide = 1e6;   // px
constexpr double kMaxFocalPx = 1e9;    // px
constexpr double kMaxPrincipal = 1e7;  // px, either side of the clip

}  // namespace

std::vector<NamedNumber> read_lens_distortion(const Fields& blender) {
  if (!blender.has("lens_distortion")) return {};
  const Fields d = blender.object("lens_distortion");
  std::vector<NamedNumber> numbers;
  const auto add = [&](std::string key, double x, const char* member, std::string how = {}) {
    numbers.push_back(
        {std::move(key), x, ValueOrigin::from_file(d.file(), d.path() + "." + member, how), true});
  };

  const std::optional<std::string> word = d.word("model");
  if (!word) d.fail("model", "expected the distortion model: polynomial, division, nuke or brown");
  const auto model = std::find_if(kModels.begin(), kModels.end(),
                                  [&](const ModelCoefficients& m) { return m.model == *word; });
  if (model == kModels.end())
    d.fail("model", "'" + *word +
                        "' is not a distortion model (expected polynomial, division, "
                        "nuke or brown)");
  std::string names;
  for (std::string_view n : model->names)
    names.append(names.empty() ? "" : ", ").append(n);
  for (const char* name : kAllCoefficients) {
    const bool has =
        std::find(model->names.begin(), model->names.end(), name) != model->names.end();
    if (!has && d.has(name))
      d.fail(name, "the " + *word + " model has no " + name + " (expected only " + names + ")");
    if (has)
      if (std::optional<double> k = d.number(name, -kMaxCoefficient, kMaxCoefficient))
        add(std::string(model->prefix) + "_" + name, *k, name);
  }

  const std::optional<std::vector<double>> size = d.numbers("clip_size_px", 2, 1, kMaxClipSide);
  if (!size || size->size() != 2)
    d.fail("clip_size_px", "expected the clip's [width, height] in pixels, each in [1, 1e6]");
  add("clip_width_px", (*size)[0], "clip_size_px[0]");
  add("clip_height_px", (*size)[1], "clip_size_px[1]");

  // Blender keeps the focal length in pixels; its panel shows millimetres as
  // f_px * sensor width / clip width (MovieTrackingCamera's focal_mm).
  if (std::optional<double> px = d.number("focal_length_px", 1e-6, kMaxFocalPx)) {
    if (d.has("focal_length_mm"))
      d.fail("focal_length_mm", "give focal_length_px or _mm, not both");
    add("clip_focal_length_px", *px, "focal_length_px");
  } else {
    const std::optional<double> mm = d.number("focal_length_mm", 1e-6, 1e6);
    const std::optional<double> sensor = d.number("sensor_width_mm", 1e-6, 1e6);
    if (!mm || !sensor)
      d.fail("focal_length_px",
             "expected the clip's focal length: focal_length_px, or focal_length_mm with "
             "sensor_width_mm");
    add("clip_focal_length_px", *mm / *sensor * (*size)[0], "focal_length_mm",
        "times clip width / sensor_width_mm");
  }

  const std::optional<std::vector<double>> principal =
      d.numbers("principal_px", 2, -kMaxPrincipal, kMaxPrincipal);
  if (!principal || principal->size() != 2)
    d.fail("principal_px",
           "expected the optical centre [x, y] in the clip's pixels from its bottom-left corner");
  add("clip_principal_x_px", (*principal)[0], "principal_px[0]");
  add("clip_principal_y_px", (*principal)[1], "principal_px[1]");
  add("clip_pixel_aspect", d.number("pixel_aspect", 1e-3, 1e3).value_or(1.0), "pixel_aspect");
  return numbers;
}

}  // namespace fb::gltf
