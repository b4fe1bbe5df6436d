// A checkered rectangle seen by a camera at the origin, for texture filtering tests and
// benchmarks (tests/unit/texture_footprint_render_test.cpp,
// tests/bench/texture_filtering_bench.cpp).
#pragma once

#include <filesystem>
#include <vector>

#include <filmback/vec.h>

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

}  // namespace fb::test
