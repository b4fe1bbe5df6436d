// A scene that uses one mesh several times, for the instancing tests (core/accel/instancing.h).
#pragma once

#include "core/scene/scene.h"

namespace fb::test {

// A UV sphere (radius 0.5 m, 24 x 12, vertex normals) in front of a camera-less origin, used five
// times: plain at (0, 0, -4); rotated and unevenly scaled; mirrored (a negative determinant);
// nested under a rotated, scaled parent; and moving 0.4 m along +X over the first second
// (node "moving", animated). Written as glTF and imported.
Scene five_spheres();

}  // namespace fb::test
