// Inside libfilmback_subdiv.so: the cage as an OpenSubdiv topology, and the two ways of making
// triangles from it. Only module.cpp's C entry points are visible outside the module.
#pragma once

#include <opensubdiv/far/topologyRefiner.h>

#include <memory>
#include <string>
#include <vector>

#include "core/subdiv/subdiv_module.h"

namespace fb::subdiv {

namespace Far = OpenSubdiv::Far;

struct Triangles {
  std::vector<float> positions, normals;  // xyz per vertex
  std::vector<float> uvs;                 // per channel, (u, v) per vertex
  std::vector<uint32_t> indices;          // three per triangle
  std::vector<uint32_t> triangle_faces;   // when asked: the cage face of each triangle
};

// The vertices of a mesh whose face corners each name a vertex and a face-varying value per
// channel: one per distinct combination, so that they split along the seams of every channel
// and nowhere else. Ids are dense, in order of first appearance.
class CornerSplitter {
 public:
  CornerSplitter(uint32_t vertex_count, uint32_t channels)
      : channels_(channels), first_(vertex_count, kNone) {}
  // The id of the combination (vertex, values[0..channels)); `fresh` says whether it is new.
  uint32_t add(uint32_t vertex, const uint32_t* values, bool& fresh);
  uint32_t count() const { return uint32_t(vertex_of_.size()); }
  uint32_t vertex(uint32_t id) const { return vertex_of_[id]; }
  // The value of `channel` that combination `id` takes.
  uint32_t value(uint32_t id, uint32_t channel) const {
    return values_of_[size_t(id) * channels_ + channel];
  }

 private:
  static constexpr uint32_t kNone = 0xffffffffu;
  uint32_t channels_;
  // Each vertex's combinations as a list: its first id, then each id's next of the same vertex.
  std::vector<uint32_t> first_, next_;
  std::vector<uint32_t> vertex_of_, values_of_;
};

// Normals as Blender computes a mesh's (blenkernel's mesh_normals.cc, which Cycles renders for a
// mesh its Subdivision Surface modifier refined): each polygon's normal (Newell's: for a triangle
// the cross product of two edges, for a quad that of its diagonals) added to each of its
// vertices weighted by the polygon's angle at that corner, then normalised. `polygons` holds
// each polygon's vertex count then its vertices; `owner[v]` is the vertex whose sum v shares
// (the split copies of one surface point take one normal). Vertices no polygon gives a normal
// keep theirs.
void mesh_normals(const std::vector<float>& positions, const std::vector<uint32_t>& polygons,
                  const std::vector<uint32_t>& owner, std::vector<float>& normals);

// Throws std::runtime_error with what OpenSubdiv or the cage got wrong.
std::unique_ptr<Far::TopologyRefiner> make_refiner(const fb_subdiv_cage& cage);

// Uniform refinement to `level`, as Blender's modifier without use_limit_surface: each cage face
// becomes 4^level quads (n-gons n * 4^(level-1)), split into two triangles each. Normals: the
// refined quads' (mesh_normals) with `polygon_normals`, else the limit surface's.
Triangles refine_uniform(Far::TopologyRefiner& refiner, const fb_subdiv_cage& cage, uint32_t level,
                         uint64_t max_triangles, bool triangle_faces, bool polygon_normals);

// The cage's vertices pushed to the limit surface (Far's limit masks), and no triangles.
Triangles cage_limit(const Far::TopologyRefiner& refiner, const fb_subdiv_cage& cage);

// Each face tessellated on the limit surface at its edges' rates, shared edges stitched (split
// where a UV channel has a seam, the positions still shared). The
// limit is evaluated through patches isolated `quality` levels deep around irregular and
// semi-sharp features, as Blender's modifier does (docs/blender.md gives the differences).
// Normals: with `polygon_normals`, those of the quads of the tessellation (mesh_normals; with
// uniform rates, the quads of Blender's refined mesh), else the limit surface's.
Triangles tessellate(const Far::TopologyRefiner& refiner, const fb_subdiv_cage& cage,
                     const uint32_t* edge_rates, uint32_t quality, uint64_t max_triangles,
                     bool triangle_faces, bool polygon_normals);

}  // namespace fb::subdiv
