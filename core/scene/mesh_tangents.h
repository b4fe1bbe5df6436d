// Per-vertex tangents of a triangle mesh from its texture coordinates, for normal maps: what a
// glTF primitive without TANGENT and a refined subdivision surface both need.
#pragma once

#include <array>
#include <vector>

#include "core/scene/scene.h"

namespace fb {

// Per-vertex tangents from the triangles' position and texture-coordinate gradients (Lengyel
// 2001, as MikkTSpace does before its splitting rules): summed over the triangles at a vertex,
// made orthogonal to the vertex normal, with the bitangent's handedness in w. The tangent follows
// +u; the bitangent follows -v, because glTF's v runs down the image while a normal texture's
// green points up it (glTF 2.0, normalTextureInfo: "+X is right and +Y is up", OpenGL's
// convention and Blender's), so B = w (N x T) points where -dp/dv does. `uv` is parallel to
// mesh.positions.
std::vector<std::array<float, 4>> mesh_tangents(const TriangleMesh& mesh,
                                                const std::vector<Vec2f>& uv);

}  // namespace fb
