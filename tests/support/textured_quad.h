// A checkered rectangle seen by a camera at the origin, for texture filtering tests and
// benchmarks (tests/unit/texture_footprint_render_test.cpp,
// tests/bench/texture_filtering_bench.cpp).
#pragma once

#include <filesystem>
#include <vector>

#include <filmback/vec.h>

#include "core/render/shot_plan.h"
#include "core/scene/scene.h"

namespace fb::test {

// The bytes of a PNG of a black-and-white checker, `size` x `size` texels in checks of `check`.
std::vector<unsigned char> checker_png(int size, int check);

// A rectangle with corners (counter-clockwise seen from its front) whose emission is the checker,
// one tile per `metres_per_tile` at (u, v) = (x, z) when `ground`, else (x, y); the camera at the
// origin looks down -z with a vertical field of view of 0.5 rad and the given aspect ratio. The
// surface is black and emits the texture: a path tracer at max_depth 0 shows the texture alone.
// Written to `gltf_file` and imported from there.
Scene textured_quad(const std::vector<Vec3f>& corners, bool ground, float metres_per_tile,
                    int texels, int check, double aspect_ratio,
                    const std::filesystem::path& gltf_file);

// How such a quad is rendered: the emitted texture alone (path tracer at max_depth 0), box
// filter, no progress; textures filtered by the ray's footprint or read at the finest level.
RenderOptions texture_render_options(uint32_t width, uint32_t height, uint32_t spp, bool footprint,
                                     uint64_t seed);

}  // namespace fb::test
