// A mesh to be rendered as a subdivision surface: Blender's Subdivision Surface modifier, exported
// unapplied (docs/blender.md, "Subdivision"). The cage is refined into triangles only when a render
// needs it (core/subdiv/), so that importing and `filmback info` never load OpenSubdiv.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <filmback/vec.h>

#include "core/math/transform.h"
#include "core/scene/animation.h"
#include "core/scene/material_textures.h"

namespace fb {

// The modifier's settings, named as Blender names them.
struct SubdivisionSettings {
  enum class Scheme { kCatmullClark, kSimple };  // SIMPLE refines bilinearly
  enum class Boundary { kAll, kPreserveCorners };
  // How texture coordinates are smoothed (the modifier's uv_smooth, in Blender's order).
  enum class UvSmooth {
    kNone,
    kPreserveCorners,
    kPreserveCornersAndJunctions,
    kPreserveCornersJunctionsAndConcave,
    kPreserveBoundaries,
    kSmoothAll
  };
  uint32_t levels_render = 2;
  uint32_t quality = 3;  // levels of patch isolation around irregular features, as Blender's
  Scheme scheme = Scheme::kCatmullClark;
  Boundary boundary_smooth = Boundary::kAll;
  bool use_creases = true;
  bool use_limit_surface = true;
  UvSmooth uv_smooth = UvSmooth::kPreserveBoundaries;  // Blender's default
};

struct EdgeCrease {
  uint32_t v0 = 0, v1 = 0;
  float weight = 0;  // Blender's crease, in [0, 1]
};

struct VertexCrease {
  uint32_t vertex = 0;
  float weight = 0;
};

// A UV map of the cage: one texture coordinate per face corner (per entry of cage_face_vertices),
// in glTF's texture space (v down the image, as TEXCOORD_n). Corners of one vertex with (nearly)
// the same coordinates are joined; elsewhere the map has a seam (core/subdiv/face_varying.h).
struct SubdivisionUvMap {
  std::string name;
  std::vector<Vec2f> corner_uvs;
};

constexpr uint32_t kNoUvMap = 0xffffffffu;

// The cage faces of one material, and which of the surface's UV maps its textures read: the
// importer resolves the material's UV map names against the cage's, as it does for a triangle
// mesh's TEXCOORD_n, so the refinement needs no names.
struct SubdivisionPart {
  uint32_t material = 0;
  // The uv_maps entry that fills each texture-coordinate slot of the refined mesh, or kNoUvMap.
  std::array<uint32_t, VertexTextureData::kSets> slot_uv_maps{kNoUvMap, kNoUvMap};
  uint32_t tangent_slot = kNoUvMap;  // the slot from whose coordinates normal maps' tangents come
};

struct SubdivisionSurface {
  std::string name;                          // for messages
  std::vector<Vec3f> cage_positions;         // object space
  std::vector<uint32_t> cage_face_sizes;     // each >= 3
  std::vector<uint32_t> cage_face_vertices;  // counter-clockwise, sum of the face sizes
  std::vector<EdgeCrease> edge_creases;
  std::vector<VertexCrease> vertex_creases;
  SubdivisionSettings settings;
  std::vector<SubdivisionUvMap> uv_maps;  // those the parts read
  std::vector<SubdivisionPart> parts{1};  // at least one
  std::vector<uint32_t> face_parts;  // per cage face, its index in `parts`; empty: all parts[0]
  // Where it is placed, as a MeshInstance of the refined mesh will be.
  Transform world_from_object;
  std::string node;
  uint32_t node_index = kNoNode;
  uint32_t asset = kNoAsset;  // as MeshInstance::asset
};

}  // namespace fb
