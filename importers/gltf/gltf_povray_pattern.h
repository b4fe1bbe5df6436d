// A POV-Ray pigment (core/scene/solid_texture.h) as JSON, for the FILMBACK_povray extension
// (docs/pov.md "Conversion"): materials[i].extensions.FILMBACK_povray.pigment holds the whole
// SolidPattern tree, so that a converted file renders the pattern filmback rendered.
#pragma once

#include <tiny_gltf.h>

#include "core/scene/solid_texture.h"
#include "importers/gltf/gltf_json.h"

namespace fb::gltf {

// Untrusted files may nest list patterns this deep at most, with this many patterns in all.
constexpr int kMaxPatternDepth = 16;
constexpr size_t kMaxPatterns = 1024;

tinygltf::Value pattern_json(const SolidPattern& pattern);

// Throws InputError naming the file and the JSON path of the first value out of range.
SolidPattern read_pattern(const Fields& json);

// The pattern's mean colour over its values (a list pattern: the mean of its entries): what a
// viewer without the extension is given as the base colour.
SolidColour mean_colour(const SolidPattern& pattern);

}  // namespace fb::gltf
