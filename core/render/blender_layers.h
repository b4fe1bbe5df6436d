// A resolved image with render passes as Blender's multi-layer EXR has it (docs/blender.md,
// "Passes"): the beauty named ViewLayer.Combined, and what the film cannot give in Cycles' terms
// converted after it resolves.
#pragma once

#include <string>

#include "core/image/image.h"
#include "core/math/transform.h"

namespace fb {

// R, G, B become ViewLayer.Combined.R/G/B, keeping their places (the 8-bit outputs show the first
// three channels), and ViewLayer.Combined.A = 1, as Cycles' without a transparent film, goes last.
void name_beauty_as_combined(Image& image);

// Channels "ViewLayer.<pass>.<channel>" (kViewLayer, as integrators name them) renamed
// "<view_layer>.<pass>.<channel>": the view layer Blender loads the file into.
void rename_view_layer(Image& image, const std::string& view_layer);

// The Denoising Normal channels, world-space as integrators write them, turned into Cycles' camera
// space (+Z forward, +Y up: OpenEXR's, the worldToCamera the EXR carries): the mean of rotated
// normals is the rotated mean, so turning the resolved pixels is exact.
void denoising_normal_to_camera_space(Image& image, const Transform& exr_camera_from_world);

}  // namespace fb
