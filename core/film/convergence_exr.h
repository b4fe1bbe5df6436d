// Adaptive sampling's state (core/film/adaptive_sampling.h) over a region of the film, as one
// UINT32 subimage of an OpenEXR file, exactly: per pixel the half buffer's three sums and weight
// (each double as its two 32-bit halves, film_state_exr.h) and the converged flag; the sample
// count of the last check in the header. For checkpoints (core/film/checkpoint.h).
#pragma once

#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/film/adaptive_sampling.h"
#include "core/film/pixel_rect.h"

namespace fb {

// A spec whose data window is `region` and display window the whole map, and its pixels.
OIIO::ImageSpec convergence_spec(const ConvergenceMap& map, const PixelRect& region);
std::vector<uint32_t> encode_convergence(const ConvergenceMap& map, const PixelRect& region);

// Reads the current subimage of `in`, a state over `region` of a map of `map`'s size, into `map`.
// Returns "" or what is wrong (another window, a missing channel, a flag other than 0 or 1, a
// non-finite sum, a truncated file).
std::string decode_convergence(OIIO::ImageInput& in, const PixelRect& region, ConvergenceMap& map);

}  // namespace fb
