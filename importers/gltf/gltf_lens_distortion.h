// A tracked clip's lens distortion in the FILMBACK_blender camera extension ("lens_distortion",
// docs/blender.md, "Lens distortion") as the numbers of the projective camera plugins' distortion
// parameters (filmback/lens_distortion.h, FB_LENS_DISTORTION_PARAMS).
#pragma once

#include <vector>

#include "core/scene/value_origin.h"
#include "importers/gltf/gltf_json.h"

namespace fb::gltf {

// `blender` is the camera's FILMBACK_blender object. None when it has no "lens_distortion"; else
// every number the camera plugin needs, each required (a plugin that does not declare it is an
// error, never a silent undistorted render) and naming its JSON path. InputError at the member
// for an unknown model, a coefficient the model lacks, or a value out of range.
std::vector<NamedNumber> read_lens_distortion(const Fields& blender);

}  // namespace fb::gltf
