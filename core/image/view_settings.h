// Blender's Color Management panel and its Post Processing > Dither: how a render's scene-linear
// pixels become an 8-bit file's values (docs/conventions.md, "Images"). Only 8-bit outputs use
// them; the EXR stays scene-linear and records them in its metadata.
#pragma once

#include <string>

namespace fb {

struct ViewSettings {
  std::string display_device = "sRGB";
  // An OpenColorIO view of the display ("Standard", "Filmic", ...); empty: none, the plain sRGB
  // curve (IEC 61966-2-1), which is what a file that names no view gets.
  std::string view_transform;
  std::string look = "None";    // an OpenColorIO look, or "None"
  double exposure_stops = 0;    // scene-linear values times 2^stops before the view
  double gamma = 1;             // display values v become v^(1/gamma)
  double dither_intensity = 0;  // Blender's noise amplitude before rounding; 0: none

  bool names_view() const { return !view_transform.empty(); }
};

}  // namespace fb
