#include "core/subdiv/face_varying.h"

#include <cmath>

namespace fb {
namespace {

// Blender's UV winding of a face (cross_poly_v2(uvs) > 0: counter-clockwise in its UV space,
// v up). Our coordinates are glTF's, v down: there the same face winds the other way.
bool blender_winding(const Vec2f* uv, size_t n) {
  double twice_area = 0;  // the shoelace formula
  for (size_t k = 0; k < n; ++k) {
    const Vec2f a = uv[k], b = uv[(k + 1) % n];
    twice_area += double(a.x) * b.y - double(b.x) * a.y;
  }
  return twice_area < 0;
}

}  // namespace

FaceVaryingChannel join_uv_corners(const std::vector<uint32_t>& face_sizes,
                                   const std::vector<uint32_t>& face_vertices,
                                   uint32_t vertex_count, const std::vector<Vec2f>& corner_uvs) {
  const size_t corners = face_vertices.size();
  std::vector<uint8_t> winding(corners);  // of each corner's face
  for (size_t f = 0, first = 0; f < face_sizes.size(); first += face_sizes[f++]) {
    const bool w = blender_winding(&corner_uvs[first], face_sizes[f]);
    for (size_t k = 0; k < face_sizes[f]; ++k)
      winding[first + k] = w;
  }
  // Each vertex's corners, latest first: Blender prepends them to the vertex's list as it walks
  // the faces in order, then groups the list greedily from its head.
  std::vector<uint32_t> start(size_t(vertex_count) + 1, 0), order(corners);
  for (uint32_t v : face_vertices)
    ++start[v + 1];
  for (size_t v = 0; v < vertex_count; ++v)
    start[v + 1] += start[v];
  std::vector<uint32_t> fill(start.begin() + 1, start.end());
  for (size_t c = 0; c < corners; ++c)
    order[--fill[face_vertices[c]]] = uint32_t(c);

  FaceVaryingChannel out;
  constexpr uint32_t kUnset = 0xffffffffu;
  out.corner_values.assign(corners, kUnset);
  uint32_t values = 0;
  for (size_t v = 0; v < vertex_count; ++v)
    for (uint32_t i = start[v]; i < start[v + 1]; ++i) {
      const uint32_t lead = order[i];
      if (out.corner_values[lead] != kUnset) continue;
      out.corner_values[lead] = values;
      for (uint32_t j = i + 1; j < start[v + 1]; ++j) {
        const uint32_t c = order[j];
        if (out.corner_values[c] == kUnset &&
            std::abs(corner_uvs[c].x - corner_uvs[lead].x) < kUvConnectLimit &&
            std::abs(corner_uvs[c].y - corner_uvs[lead].y) < kUvConnectLimit &&
            winding[c] == winding[lead])
          out.corner_values[c] = values;
      }
      ++values;
    }
  out.values.resize(2 * size_t(values));
  for (size_t c = 0; c < corners; ++c) {
    out.values[2 * out.corner_values[c]] = corner_uvs[c].x;
    out.values[2 * out.corner_values[c] + 1] = corner_uvs[c].y;
  }
  return out;
}

}  // namespace fb
