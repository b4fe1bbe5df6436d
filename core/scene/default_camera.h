#pragma once

#include "core/scene/scene.h"

namespace fb {

// The camera a scene without one gets (docs/scenes.md): a 50 mm lens on a 36 x 24 mm sensor at
// 16:9, looking at the centre of the bounds from the +Z side and a little above, far enough that
// the bounding sphere fits the vertical field of view with a 10 % margin.
SceneCamera frame_bounds(const Bounds3d& bounds);

}  // namespace fb
