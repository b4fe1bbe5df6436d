// How far a moving vertex may stray from its true path between two motion steps, for the render's
// choice of how many steps a moving mesh gets (core/render/render_job.cpp derives it from the
// camera: a twentieth of a pixel).
#pragma once

namespace fb {

// absolute_m plus per_metre times the vertex's distance from the camera (render space is
// camera-centred): a fraction of a pixel's footprint.
struct MotionTolerance {
  double absolute_m = 0;
  double per_metre = 0;
};

}  // namespace fb
