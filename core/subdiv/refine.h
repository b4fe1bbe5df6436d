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
  std::vector<uint32_t> indices;          // three per triangle
};

// Throws std::runtime_error with what OpenSubdiv or the cage got wrong.
std::unique_ptr<Far::TopologyRefiner> make_refiner(const fb_subdiv_cage& cage);

// Uniform refinement to `level`, as Blender's modifier without use_limit_surface: each cage face
// becomes 4^level quads (n-gons n * 4^(level-1)), split into two triangles each.
Triangles refine_uniform(Far::TopologyRefiner& refiner, const fb_subdiv_cage& cage, uint32_t level,
                         uint64_t max_triangles);

// The cage's vertices pushed to the limit surface (Far's limit masks), and no triangles.
Triangles cage_limit(const Far::TopologyRefiner& refiner, const fb_subdiv_cage& cage);

// Each face tessellated on the limit surface at its edges' rates, shared edges stitched. The
// limit is evaluated through patches isolated `quality` levels deep around irregular and
// semi-sharp features, as Blender's modifier does (docs/blender.md gives the differences).
Triangles tessellate(const Far::TopologyRefiner& refiner, const fb_subdiv_cage& cage,
                     const uint32_t* edge_rates, uint32_t quality, uint64_t max_triangles);

}  // namespace fb::subdiv
