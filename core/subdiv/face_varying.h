// A cage UV map (a texture coordinate per face corner) as OpenSubdiv's face-varying channel:
// values, and the value each corner takes. Blender joins the corners of a vertex as
// BKE_mesh_uv_vert_map_create does for its subdivision converter (blenkernel
// subdiv_converter_mesh.c, precalc_uv_layer, Blender 3.4): corners whose coordinates differ by
// less than STD_UV_CONNECT_LIMIT (1e-4) in u and in v, on faces of the same UV winding, share a
// value; any other pair of corners of that vertex is a seam. filmback joins them the same way, so
// that its refinement has Blender's seams.
#pragma once

#include <cstdint>
#include <vector>

#include <filmback/vec.h>

namespace fb {

struct FaceVaryingChannel {
  std::vector<float> values;            // u, v per value
  std::vector<uint32_t> corner_values;  // per face corner, an index into values / 2
  uint32_t value_count() const { return uint32_t(values.size() / 2); }
};

// Blender's STD_UV_CONNECT_LIMIT (BKE_mesh_mapping.h).
constexpr float kUvConnectLimit = 1e-4f;

// `corner_uvs` parallel to `face_vertices` (faces of `face_sizes` corners, vertices below
// `vertex_count`). A value takes the coordinates of the last corner (in face order) joined to it,
// as Blender's evaluator stores them (subdiv_eval.c, set_face_varying_data_from_uv).
FaceVaryingChannel join_uv_corners(const std::vector<uint32_t>& face_sizes,
                                   const std::vector<uint32_t>& face_vertices,
                                   uint32_t vertex_count, const std::vector<Vec2f>& corner_uvs);

}  // namespace fb
