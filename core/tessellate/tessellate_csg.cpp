#include "core/tessellate/tessellate_csg.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "core/tessellate/csg_probe.h"
#include "core/tessellate/csg_trim.h"
#include "core/tessellate/seam_join.h"
#include "core/tessellate/triangle_bvh.h"

namespace fb {

namespace {

// The primitive's whole boundary as a closed surface: where its set ends, which is what cuts the
// others (an open cylinder still ends at its caps; a disc's set is its half-space).
Solid closed_boundary(const Solid& primitive) {
  Solid s = primitive;
  s.kind = primitive.kind == SolidKind::kDisc ? SolidKind::kHalfSpace : primitive.kind;
  s.open = s.inverse = s.bounds_only = false;
  return s;
}

void add_world_triangles(const TriangleMesh& mesh, const Transform& world_from_object, uint32_t tag,
                         std::vector<TaggedTriangle>& out) {
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    TaggedTriangle t;
    for (size_t k = 0; k < 3; ++k)
      t.p[k] = world_from_object.point(Vec3d(mesh.positions[mesh.indices[i + k]]));
    t.tag = tag;
    out.push_back(t);
  }
}

// One mesh per material in the frame `origin` translates to; a vertex per position and normal.
std::vector<TriangleMesh> meshes_by_material(const JoinedSurface& surface, Vec3d origin,
                                             const std::string& name) {
  std::map<uint32_t, TriangleMesh> meshes;
  std::map<uint32_t, std::map<std::array<uint32_t, 4>, uint32_t>> vertex_of;
  for (const JoinedSurface::Triangle& t : surface.triangles) {
    TriangleMesh& mesh = meshes[t.material];
    auto& vertices = vertex_of[t.material];
    for (size_t k = 0; k < 3; ++k) {
      const Vec3f n(t.n[k]);
      std::array<uint32_t, 4> key{t.v[k], 0, 0, 0};
      std::memcpy(&key[1], &n, sizeof n);
      const auto [it, added] = vertices.try_emplace(key, uint32_t(mesh.positions.size()));
      if (added) {
        mesh.positions.emplace_back(surface.positions[t.v[k]] - origin);
        mesh.normals.push_back(n);
      }
      mesh.indices.push_back(it->second);
    }
  }
  std::vector<TriangleMesh> out;
  for (auto& [material, mesh] : meshes) {
    mesh.name = name;
    mesh.material = material;
    out.push_back(std::move(mesh));
  }
  return out;
}

}  // namespace

SolidTessellation tessellate_csg(const Solid& solid, const TessellationOptions& options,
                                 Diagnostics& diagnostics) {
  const CsgProbe probe(solid);
  const size_t leaves = probe.leaf_count();
  // Seams are as fine as the finest bounded primitive asks (half-spaces have no size of their
  // own: they count only in a solid of nothing else).
  double bounded = HUGE_VAL, unbounded = HUGE_VAL;
  for (size_t i = 0; i < leaves; ++i) {
    double& t = object_bounds(probe.leaf(i)).finite() ? bounded : unbounded;
    t = std::min(t, tessellation_tolerance_m(probe.leaf(i), options));
  }
  const double tolerance = std::isfinite(bounded) ? bounded : unbounded;
  double coarsest = tolerance;  // of the primitives' tessellations
  for (size_t i = 0; i < leaves; ++i)
    if (object_bounds(probe.leaf(i)).finite())
      coarsest = std::max(coarsest, tessellation_tolerance_m(probe.leaf(i), options));

  std::vector<TaggedTriangle> boundaries;
  for (size_t i = 0; i < leaves; ++i) {
    const Solid closed = closed_boundary(probe.leaf(i));
    add_world_triangles(tessellate(closed, options), closed.world_from_object, uint32_t(i),
                        boundaries);
  }
  const TriangleBvh bvh(std::move(boundaries));

  std::vector<SurfacePart> parts(leaves);
  std::vector<char> untessellated(leaves, 0);
  tbb::parallel_for(size_t(0), leaves, [&](size_t i) {
    if (!probe.is_surface(i)) return;
    const TriangleMesh mesh = tessellate(probe.leaf(i), options);
    untessellated[i] = mesh.indices.empty();
    const TrimTolerances tolerances{tolerance, tessellation_tolerance_m(probe.leaf(i), options),
                                    coarsest};
    parts[i].surface = trim_surface(probe, i, mesh, bvh, tolerances);
    parts[i].leaf = uint32_t(i);
    parts[i].material = probe.leaf(i).material;
  });
  for (size_t i = 0; i < leaves; ++i)
    if (untessellated[i]) warn_untessellated(probe.leaf(i), diagnostics);
  const JoinedSurface joined = join_surfaces(parts, tolerance);

  Bounds3d used;
  for (const JoinedSurface::Triangle& t : joined.triangles)
    for (uint32_t v : t.v)
      used.extend(joined.positions[v]);
  SolidTessellation out;
  if (used.empty()) return out;
  const Vec3d origin = (used.lo + used.hi) * 0.5;
  out.world_from_mesh = Transform::translate(origin);
  out.meshes = meshes_by_material(joined, origin, solid.name);
  return out;
}

}  // namespace fb
