// A mesh to be rendered as a subdivision surface: Blender's Subdivision Surface modifier, exported
// unapplied (docs/blender.md, "Subdivision"). The cage is refined into triangles only when a render
// needs it (core/subdiv/), so that importing and `filmback info` never load OpenSubdiv.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <filmback/vec.h>

#include "core/math/transform.h"
#include "core/scene/animation.h"

namespace fb {

// The modifier's settings, named as Blender names them.
struct SubdivisionSettings {
  enum class Scheme { kCatmullClark, kSimple };  // SIMPLE refines bilinearly
  enum class Boundary { kAll, kPreserveCorners };
  uint32_t levels_render = 2;
  uint32_t quality = 3;  // levels of patch isolation around irregular features, as Blender's
  Scheme scheme = Scheme::kCatmullClark;
  Boundary boundary_smooth = Boundary::kAll;
  bool use_creases = true;
  bool use_limit_surface = true;
};

struct EdgeCrease {
  uint32_t v0 = 0, v1 = 0;
  float weight = 0;  // Blender's crease, in [0, 1]
};

struct VertexCrease {
  uint32_t vertex = 0;
  float weight = 0;
};

struct SubdivisionSurface {
  std::string name;                          // for messages
  std::vector<Vec3f> cage_positions;         // object space
  std::vector<uint32_t> cage_face_sizes;     // each >= 3
  std::vector<uint32_t> cage_face_vertices;  // counter-clockwise, sum of the face sizes
  std::vector<EdgeCrease> edge_creases;
  std::vector<VertexCrease> vertex_creases;
  SubdivisionSettings settings;
  uint32_t material = 0;
  // Where it is placed, as a MeshInstance of the refined mesh will be.
  Transform world_from_object;
  std::string node;
  uint32_t node_index = kNoNode;
};

}  // namespace fb
