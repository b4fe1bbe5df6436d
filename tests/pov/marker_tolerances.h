// How closely filmback's image of a POV-Ray scene must land on POV-Ray's own: each marker's
// centroid and area, measured on both images (docs/pov.md, "Camera").
#pragma once

namespace fb::test {

inline constexpr double kMaxCentroidErrorPx = 0.1;
inline constexpr double kMaxAreaError = 0.02;  // of the area's ratio to POV-Ray's

}  // namespace fb::test
