#include "importers/pov/pov_importer.h"

#include <map>

#include "importers/pov/pov_appearance.h"
#include "importers/pov/pov_camera.h"
#include "importers/pov/pov_geometry.h"
#include "importers/pov/sdl/evaluate.h"
#include "importers/pov/sdl/solid_pigment.h"

namespace fb {
namespace {

// What Debian's `povray` renders without options (its povray.ini: Width 800, Height 600).
constexpr uint32_t kDefaultWidth = 800, kDefaultHeight = 600;
const std::filesystem::path kStandardIncludes = "/usr/share/povray-3.7/include";

// Objects whose absence leaves the geometry incomplete (docs/pov.md "What is not supported").
bool is_object(const std::string& feature) {
  static const char* kObjects[] = {"text",       "height_field",  "blob",           "lathe",
                                   "sor",        "prism",         "superellipsoid", "isosurface",
                                   "parametric", "julia_fractal", "quadric",        "quartic",
                                   "poly",       "cubic",         "bicubic_patch",  "sphere_sweep",
                                   "polynomial", "ovus",          "lemon",          "object"};
  for (const char* name : kObjects)
    if (feature == name) return true;
  return false;
}

// SDL functions the evaluator answers with zeros: what the scene computes with them (often where
// it places objects) is wrong, so the geometry counts as incomplete too. A user function says
// what it lacks: "function internal(8)", "function pigment".
bool is_zero_function(const std::string& feature) {
  static const char* kFunctions[] = {"trace", "inside", "min_extent", "max_extent", "spline"};
  for (const char* name : kFunctions)
    if (feature == name) return true;
  return feature.starts_with("function ");
}

// Once per feature, at the first place it appears (and where an unsupported object declared
// elsewhere was placed).
void report_unsupported(const pov::Scene& pov, Diagnostics& diagnostics) {
  std::map<std::string, bool> seen;
  for (const pov::Unsupported& u : pov.unsupported) {
    if (!seen.emplace(u.feature, true).second) continue;
    std::string what = is_object(u.feature) ? "object '" + u.feature + "': not rendered"
                       : is_zero_function(u.feature)
                           ? "function '" + u.feature + "': evaluated as zero"
                           : "feature '" + u.feature + "': ignored";
    if (u.placed) what += " (placed at " + u.placed->text() + ")";
    diagnostics.warn(u.where.text() + ": unsupported " + what);
  }
  for (const std::string& warning : pov.warnings)
    diagnostics.warn(warning);
}

}  // namespace

Scene import_pov(const std::filesystem::path& file, const ImportOptions& options,
                 Diagnostics& diagnostics) {
  const auto [width, height] =
      options.resolution.value_or(std::pair{kDefaultWidth, kDefaultHeight});
  pov::EvaluateOptions evaluate;
  evaluate.scene_file = file;
  // The standard include folder first, as Debian's povray.ini puts it before the Library_Path
  // options of the command line and the scene's .ini.
  if (std::filesystem::is_directory(kStandardIncludes))
    evaluate.library_paths.push_back(kStandardIncludes);
  evaluate.library_paths.insert(evaluate.library_paths.end(), options.library_paths.begin(),
                                options.library_paths.end());
  evaluate.image_width = width;
  evaluate.image_height = height;
  evaluate.clock = options.clock;
  evaluate.frame_number = options.frame;
  evaluate.animation = options.pov_animation;
  evaluate.declarations = options.pov_declarations;
  evaluate.limits = options.pov_limits;
  const pov::Scene pov = pov::evaluate_pov(evaluate);
  report_unsupported(pov, diagnostics);

  Scene scene;
  scene.file = file;
  // image_map files, at the indices the pigments give (pov_appearance's to_solid)
  for (const std::filesystem::path& image : pov.images)
    scene.images.push_back({image.filename().string(), image, {}});
  scene.settings.width_px = width;
  scene.settings.height_px = height;
  const pov::PovCamera camera = pov::convert_camera(pov.camera, width, height, diagnostics);
  scene.cameras.push_back(camera.camera);
  scene.settings.pixel_aspect = camera.pixel_aspect;
  pov::MaterialTable materials(pov, scene, diagnostics);
  pov::convert_objects(
      pov,
      [&](const pov::Texture& texture, const std::optional<pov::Interior>& interior) {
        return materials.material(texture, interior);
      },
      scene, diagnostics);
  pov::convert_lights(pov, scene, diagnostics);
  pov::convert_environment(pov, scene, diagnostics);
  PovTracing& tracing = scene.pov_tracing.emplace();
  if (pov.max_trace_level) tracing.max_trace_level = uint32_t(*pov.max_trace_level);
  if (pov.adc_bailout) tracing.adc_bailout = *pov.adc_bailout;
  tracing.colour_gamma = pov::colour_gamma(pov);
  tracing.ambient_light = pov::decode(pov.ambient_light, tracing.colour_gamma);
  return scene;
}

}  // namespace fb
