// Subdivision surfaces become triangle meshes when a render needs them (the importer keeps the
// cage): at Blender's render level, or adaptively for the camera (docs/blender.md, "Subdivision").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace fb {

enum class SubdivMode {
  kRender,    // uniform, at the modifier's levels_render, as Blender renders it
  kAdaptive,  // each cage edge cut into segments of about one pixel through the camera
};

// What adaptive refinement needs of the camera: where it is, where it looks, and how many pixels
// a metre covers (the view plane's fx, fy: at 1 m depth in perspective, everywhere orthographic).
struct SubdivView {
  Transform camera_from_world;  // the camera at the origin looking down -Z
  double fx = 1, fy = 1;
  bool orthographic = false;
};

// All subdivision surfaces of a scene together make at most this many triangles (about 1.6 GB
// of mesh with normals): render mode refuses more, adaptive mode coarsens to fit, with a warning.
constexpr uint64_t kMaxSubdivTriangles = uint64_t(1) << 25;

struct SubdivReport {
  std::string summary;                // one line for the render's plan
  std::vector<std::string> warnings;  // what was coarsened to fit the cap
};

// Appends one mesh and one instance per subdivision surface to `scene` and empties
// scene.subdivision_surfaces. Loads the subdivision module only when there is one. Throws
// InputError naming the file and the surface when it cannot be refined within the cap.
SubdivReport refine_subdivision_surfaces(Scene& scene, SubdivMode mode, const SubdivView& view,
                                         uint64_t max_triangles = kMaxSubdivTriangles);

// Blender's edge or vertex crease c in [0, 1] as OpenSubdiv's sharpness: 10 c^2
// (BKE_subdiv_crease_to_sharpness_f; 10 is Sdc's infinitely sharp).
inline float crease_sharpness(float crease) {
  return crease * crease * 10.0f;
}

}  // namespace fb
