#include <opensubdiv/far/primvarRefiner.h>

#include <cmath>
#include <stdexcept>

#include "core/subdiv/refine.h"

namespace fb::subdiv {
namespace {

// The vertex types Far::PrimvarRefiner interpolates: a point or a tangent (3), texture
// coordinates (2).
template <int N>
struct Values {
  float p[N];
  void Clear(void* = nullptr) {
    for (int i = 0; i < N; ++i)
      p[i] = 0;
  }
  void AddWithWeight(const Values& src, float weight) {
    for (int i = 0; i < N; ++i)
      p[i] += weight * src.p[i];
  }
};
using Point = Values<3>;
using Uv = Values<2>;

// Each channel's values refined level by level to `level`: the last level's, per channel.
std::vector<std::vector<Uv>> refined_uvs(const Far::TopologyRefiner& refiner,
                                         const fb_subdiv_cage& cage, uint32_t level) {
  const Far::PrimvarRefiner primvar(refiner);
  std::vector<std::vector<Uv>> out(cage.uv_channel_count);
  for (uint32_t c = 0; c < cage.uv_channel_count; ++c) {
    const fb_subdiv_uv_channel& channel = cage.uv_channels[c];
    std::vector<Uv> src(channel.value_count);
    for (uint32_t i = 0; i < channel.value_count; ++i)
      src[i] = {{channel.values[2 * i], channel.values[2 * i + 1]}};
    for (int l = 1; l <= int(level); ++l) {
      std::vector<Uv> dst(size_t(refiner.GetLevel(l).GetNumFVarValues(int(c))));
      Uv* to = dst.data();
      primvar.InterpolateFaceVarying(l, src.data(), to, int(c));
      src = std::move(dst);
    }
    out[c] = std::move(src);
  }
  return out;
}

// The cage face each face of `level` comes from.
std::vector<uint32_t> parent_faces(const Far::TopologyRefiner& refiner, uint32_t level) {
  std::vector<uint32_t> faces(size_t(refiner.GetLevel(0).GetNumFaces()));
  for (size_t f = 0; f < faces.size(); ++f)
    faces[f] = uint32_t(f);
  const Far::PrimvarRefiner primvar(refiner);
  for (int l = 1; l <= int(level); ++l) {
    std::vector<uint32_t> children(size_t(refiner.GetLevel(l).GetNumFaces()));
    uint32_t* to = children.data();
    primvar.InterpolateFaceUniform(l, faces.data(), to);
    faces = std::move(children);
  }
  return faces;
}

// Triangles the refinement will make: a quad gives four per level; an n-gon gives n quads at the
// first level.
uint64_t triangle_count(const fb_subdiv_cage& cage, uint32_t level) {
  uint64_t total = 0;
  for (uint32_t f = 0; f < cage.face_count; ++f) {
    const uint64_t n = cage.face_sizes[f];
    if (level == 0)
      total += n - 2;
    else
      total += 2 * (n == 4 ? 4 : n) << (2 * (level - 1));
  }
  return total;
}

}  // namespace

Triangles cage_limit(const Far::TopologyRefiner& refiner, const fb_subdiv_cage& cage) {
  std::vector<Point> points(cage.vertex_count), limit(cage.vertex_count);
  for (uint32_t v = 0; v < cage.vertex_count; ++v)
    for (int i = 0; i < 3; ++i)
      points[v].p[i] = cage.positions[3 * v + i];
  Far::PrimvarRefiner(refiner).Limit(points.data(), limit);
  Triangles out;
  for (const Point& p : limit)
    out.positions.insert(out.positions.end(), {p.p[0], p.p[1], p.p[2]});
  return out;
}

Triangles refine_uniform(Far::TopologyRefiner& refiner, const fb_subdiv_cage& cage, uint32_t level,
                         uint64_t max_triangles, bool triangle_faces, bool polygon_normals) {
  const uint64_t count = level > 24 ? UINT64_MAX : triangle_count(cage, level);
  if (count > max_triangles)
    throw std::runtime_error("level " + std::to_string(level) + " makes " + std::to_string(count) +
                             " triangles, more than the limit of " + std::to_string(max_triangles));
  // Full topology in the last level: the limit masks need each last-level vertex's neighbours.
  Far::TopologyRefiner::UniformOptions options{int(level)};
  options.fullTopologyInLastLevel = true;
  if (level > 0) refiner.RefineUniform(options);

  std::vector<Point> points(size_t(refiner.GetNumVerticesTotal()));
  for (uint32_t v = 0; v < cage.vertex_count; ++v)
    for (int i = 0; i < 3; ++i)
      points[v].p[i] = cage.positions[3 * v + i];
  const Far::PrimvarRefiner primvar(refiner);
  Point* src = points.data();
  for (int l = 1; l <= int(level); ++l) {
    Point* dst = src + refiner.GetLevel(l - 1).GetNumVertices();
    primvar.Interpolate(l, src, dst);
    src = dst;
  }
  const Far::TopologyLevel& last = refiner.GetLevel(int(level));
  const size_t n = size_t(last.GetNumVertices());
  // The limit tangents, whose cross product is the smooth normal (Far's limit masks; the
  // positions stay those of the refined cage).
  std::vector<Point> limit(n), du(n), dv(n);
  primvar.Limit(src, limit, du, dv);
  std::vector<float> positions(3 * n), normals(3 * n);
  for (size_t v = 0; v < n; ++v) {
    const float* a = du[v].p;
    const float* b = dv[v].p;
    const float nrm[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                          a[0] * b[1] - a[1] * b[0]};
    const float len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    for (int i = 0; i < 3; ++i) {
      positions[3 * v + i] = src[v].p[i];
      normals[3 * v + i] = len > 0 ? nrm[i] / len : 0;
    }
  }
  if (polygon_normals) {
    std::vector<uint32_t> polygons, owner(n);
    for (int f = 0; f < last.GetNumFaces(); ++f) {
      const auto face = last.GetFaceVertices(f);
      polygons.push_back(uint32_t(face.size()));
      for (int k = 0; k < face.size(); ++k)
        polygons.push_back(uint32_t(face[k]));
    }
    for (size_t v = 0; v < n; ++v)
      owner[v] = uint32_t(v);
    mesh_normals(positions, polygons, owner, normals);
  }

  // The face corners of the last level, each a vertex and a value per channel: the output's
  // vertices, split along the channels' seams.
  const uint32_t channels = cage.uv_channel_count;
  const std::vector<std::vector<Uv>> uvs = refined_uvs(refiner, cage, level);
  CornerSplitter splitter(uint32_t(n), channels);
  std::vector<uint32_t> corner_ids, values(channels);
  corner_ids.reserve(size_t(last.GetNumFaceVertices()));
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    const auto face = last.GetFaceVertices(f);
    for (int k = 0; k < face.size(); ++k) {
      for (uint32_t c = 0; c < channels; ++c)
        values[c] = uint32_t(last.GetFaceFVarValues(f, int(c))[k]);
      bool fresh;
      corner_ids.push_back(splitter.add(uint32_t(face[k]), values.data(), fresh));
    }
  }

  Triangles out;
  const size_t vertices = splitter.count();
  out.positions.resize(3 * vertices);
  out.normals.resize(3 * vertices);
  out.uvs.resize(2 * channels * vertices);
  for (uint32_t id = 0; id < vertices; ++id) {
    const uint32_t v = splitter.vertex(id);
    for (int i = 0; i < 3; ++i) {
      out.positions[3 * size_t(id) + i] = positions[3 * size_t(v) + i];
      out.normals[3 * size_t(id) + i] = normals[3 * size_t(v) + i];
    }
    for (uint32_t c = 0; c < channels; ++c) {
      const Uv& uv = uvs[c][splitter.value(id, c)];
      out.uvs[2 * (c * vertices + id)] = uv.p[0];
      out.uvs[2 * (c * vertices + id) + 1] = uv.p[1];
    }
  }
  // Quads split along their first diagonal, as Blender's tessellation of a quad (0-1-2, 0-2-3);
  // level 0 leaves the cage's n-gons, split into fans.
  out.indices.reserve(3 * count);
  std::vector<uint32_t> faces;
  if (triangle_faces) faces = parent_faces(refiner, level);
  size_t corner = 0;
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    const int size = last.GetFaceVertices(f).size();
    const uint32_t* ids = &corner_ids[corner];
    for (int k = 2; k < size; ++k) {
      out.indices.insert(out.indices.end(), {ids[0], ids[k - 1], ids[k]});
      if (triangle_faces) out.triangle_faces.push_back(faces[size_t(f)]);
    }
    corner += size_t(size);
  }
  return out;
}

}  // namespace fb::subdiv
