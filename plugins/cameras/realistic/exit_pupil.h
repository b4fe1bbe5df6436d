// Where on the rear element's plane light from a film point can leave through the whole lens: a
// rectangle per band of film radius, found once by tracing a grid of rays (pbrt-v4's
// RealisticCamera::BoundExitPupil). Sampling within the rectangle of the film point's band and
// rotating it to the point's azimuth (the lens is symmetric about its axis) wastes few rays on a
// lens that vignettes, and the rectangle's area is the sample's inverse density.
#pragma once

#include <filmback/lens_optics.h>

#include <algorithm>
#include <vector>

namespace fb {

struct PupilBounds {
  double x0, y0, x1, y1;  // mm on the plane z = rear vertex; x along the film point's radius
  bool empty() const { return !(x1 > x0 && y1 > y0); }
  double area_mm2() const { return empty() ? 0.0 : (x1 - x0) * (y1 - y0); }
};

class ExitPupil {
 public:
  // Bands of film radius in [0, film_radius_mm], each traced with kRadii film points times a
  // kGrid x kGrid grid over a square 1.5 times the rear element's radius (pbrt's margin: the
  // rear surface's sag lets oblique rays cross the plane outside the element's rim). About 150k
  // rays, 0.02 s for the double Gauss (pbrt-v4 traces 64 x 1024^2 in parallel); RealisticCamera.
  // ExitPupilBoundsHoldEveryRayThatPasses checks that they suffice.
  static constexpr int kBands = 16, kRadii = 4, kGrid = 48;

  ExitPupil(const LensStack& lens, double film_radius_mm)
      : band_mm_(film_radius_mm / kBands), bounds_(kBands) {
    const double half = 1.5 * lens.rear_aperture_radius_mm(), cell = 2 * half / kGrid;
    for (int band = 0; band < kBands; ++band) {
      PupilBounds b{HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
      for (int k = 0; k < kRadii; ++k) {
        const double r = band_mm_ * (band + double(k) / (kRadii - 1));
        for (int i = 0; i < kGrid; ++i)
          for (int j = 0; j < kGrid; ++j) {
            const double x = -half + (i + 0.5) * cell, y = -half + (j + 0.5) * cell;
            LensRay ray{{r, 0, 0}, normalize(Vec3d{x - r, y, lens.rear_z_mm()})};
            if (!lens.trace(ray)) continue;
            b = {std::min(b.x0, x), std::min(b.y0, y), std::max(b.x1, x), std::max(b.y1, y)};
          }
      }
      // Two cells of margin: the grid can miss a sliver of the pupil between its points.
      if (b.x1 >= b.x0)
        bounds_[band] = {b.x0 - 2 * cell, b.y0 - 2 * cell, b.x1 + 2 * cell, b.y1 + 2 * cell};
      else
        bounds_[band] = {0, 0, 0, 0};
    }
  }

  // The bounds for a film point at radius r mm (the last band beyond the film's corner).
  const PupilBounds& at(double r_mm) const {
    const int band = band_mm_ > 0 ? int(std::min(r_mm / band_mm_, double(kBands - 1))) : 0;
    return bounds_[std::max(band, 0)];
  }

 private:
  double band_mm_;
  std::vector<PupilBounds> bounds_;
};

}  // namespace fb
