// A wall whose base colour is a coloured checker (read through a KHR_texture_transform offset),
// seen square-on by a camera at the origin: for the tests of the textured albedo (the aov
// integrator's albedo, tests/unit/aov_render_test.cpp; the DiffCol and Denoising Albedo passes,
// tests/unit/render_passes_test.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

#include <filmback/vec.h>

#include "core/image/image.h"
#include "core/render/shot_plan.h"
#include "core/scene/scene.h"

namespace fb::test {

inline constexpr uint32_t kAlbedoCheckerImagePx = 48;

// The wall, white times the checker, emitting nothing; written to `gltf_file` and imported.
Scene albedo_checker_wall(const std::filesystem::path& gltf_file);

// How it is rendered: kAlbedoCheckerImagePx square, 4 spp, box filter (each sample in its pixel).
RenderOptions albedo_checker_options();

// Expects the three channels from the one named `first_channel` (an albedo's R) of each pixel that
// shows a single check to hold that check's linear texel, to 1e-5; returns how many pixels of each
// colour were checked.
std::array<int, 2> expect_checker_albedo(const Image& image, const std::string& first_channel);

}  // namespace fb::test
