// Procedural scenes for the primary-ray benchmark, built in memory as an importer would: one
// TriangleMesh with vertex normals, one MeshInstance, one Material and one perspective camera.
#pragma once

#include <cstdint>

#include "core/scene/scene.h"

namespace fb::bench {

// A closed UV sphere of radius about 1 m, radially displaced by a few sines, with `segments`
// around and segments / 2 + 1 latitude bands: segments^2 triangles (1024 -> 1,048,576). The
// camera sits at its centre; the surface is star-shaped around it, so every ray hits exactly once
// ("sphere-in" of shared notes/deps.md section 4).
Scene make_sphere_in(uint32_t segments);

// An open heightfield of cells x cells quads (2 cells^2 triangles; 724 -> 1,048,352) over
// 100 m x 100 m, seen from above its edge so that the upper part of the image sees the sky.
Scene make_terrain(uint32_t cells);

}  // namespace fb::bench
