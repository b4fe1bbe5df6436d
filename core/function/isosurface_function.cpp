#include "core/function/isosurface_function.h"

#include <algorithm>
#include <cmath>

#include "core/function/user_function.h"

namespace fb {

namespace {

// The root search stops once its bracket is this fraction of the accuracy: a hit then lies on
// the surface to within max_gradient times that, far below what the sampling step resolves.
constexpr double kIsosurfaceRootFraction = 1e-9;
constexpr int kIsosurfaceRootIterations = 100;

// The crossing in (a, b), where the inside state at a is `inside_at_a` and differs at b, whose
// values are va and vb: regula falsi with the Illinois modification (the end kept twice has its
// value halved, so that both ends close in, superlinearly), bisecting where a value is not a
// number (NaN counts as outside, and has no slope to follow).
double refine_crossing(const Isosurface& iso, Vec3d o, Vec3d d, double a, double b, double va,
                       double vb, bool inside_at_a, double speed) {
  const double enough = iso.accuracy * kIsosurfaceRootFraction;
  int kept = 0;  // -1: a kept last time, +1: b
  for (int i = 0; i < kIsosurfaceRootIterations && (b - a) * speed > enough; ++i) {
    double x = 0.5 * (a + b);
    if (std::isfinite(va) && std::isfinite(vb) && va != vb) {
      const double falsi = b - vb * (b - a) / (vb - va);
      if (falsi > a && falsi < b) x = falsi;
    }
    if (!(x > a && x < b)) break;  // no double between them
    const double vx = isosurface_value(iso, o + d * x);
    if ((vx < 0) == inside_at_a) {
      a = x, va = vx;
      if (kept == 1) vb *= 0.5;
      kept = 1;
    } else {
      b = x, vb = vx;
      if (kept == -1) va *= 0.5;
      kept = -1;
    }
  }
  return 0.5 * (a + b);
}

}  // namespace

double isosurface_value(const Isosurface& iso, Vec3d p) {
  return iso.function->evaluate(p.x, p.y, p.z) - iso.threshold;
}

bool isosurface_contains(const Isosurface& iso, Vec3d p) {
  return isosurface_container_holds(iso, p) && isosurface_value(iso, p) < 0;
}

IsosurfaceWalk isosurface_walk(const Isosurface& iso, Vec3d o, Vec3d d, double t_in, double t_out,
                               double t_stop) {
  IsosurfaceWalk walk;
  walk.t_end = t_out;
  const double speed = length(d);  // object units per unit of t
  if (!(speed > 0) || !(t_in < t_out)) return walk;
  const double min_step = iso.accuracy / speed;
  double t = t_in, v = isosurface_value(iso, o + d * t);
  bool inside = v < 0;
  walk.inside_at_entry = inside;
  for (int samples = 1; t < t_out; ++samples) {
    if (samples >= kIsosurfaceMaxSamples || t > t_stop) {
      walk.complete = false, walk.t_end = t;
      return walk;
    }
    // Lipschitz: |f(t + s) - f(t)| <= max_gradient s speed, so no root lies within |v| /
    // (max_gradient speed); never less than the accuracy (roots closer than it may pair off
    // unseen, as in POV-Ray), and the accuracy where f is not a number.
    const double safe = std::isfinite(v) ? std::abs(v) / (iso.max_gradient * speed) : 0;
    double t_next = std::min(t + std::max(safe, min_step), t_out);
    if (!(t_next > t)) t_next = std::nextafter(t, HUGE_VAL);
    const double v_next = isosurface_value(iso, o + d * t_next);
    if ((v_next < 0) != inside) {
      if (walk.count == kIsosurfaceMaxCrossings) {
        walk.complete = false, walk.t_end = t;
        return walk;
      }
      walk.crossings[walk.count++] =
          refine_crossing(iso, o, d, t, t_next, v, v_next, inside, speed);
      inside = !inside;
    }
    t = t_next, v = v_next;
  }
  return walk;
}

Vec3d isosurface_gradient(const Isosurface& iso, Vec3d p) {
  const double h = 0.1 * iso.accuracy;
  const auto f = [&](Vec3d q) { return isosurface_value(iso, q); };
  return Vec3d{f(p + Vec3d{h, 0, 0}) - f(p - Vec3d{h, 0, 0}),
               f(p + Vec3d{0, h, 0}) - f(p - Vec3d{0, h, 0}),
               f(p + Vec3d{0, 0, h}) - f(p - Vec3d{0, 0, h})} /
         (2 * h);
}

IsosurfaceProbe isosurface_probe(const Isosurface& iso, int cells_per_axis) {
  const Bounds3d box = isosurface_bounds(iso);
  const int n = std::max(cells_per_axis, 1);
  const Vec3d cell = (box.hi - box.lo) / double(n);
  // Within the container only: a sphere's box corners do not count.
  const auto value = [&](int i, int j, int k) {
    const Vec3d p = box.lo + Vec3d{cell.x * i, cell.y * j, cell.z * k};
    return isosurface_container_holds(iso, p) ? isosurface_value(iso, p) : NAN;
  };
  IsosurfaceProbe probe;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) {
        const double v = value(i, j, k);
        if (!std::isfinite(v)) continue;
        ++probe.finite_samples;
        if (i == n || j == n || k == n) continue;
        // Difference quotients along the grid's edges: each is at most the Lipschitz constant,
        // so a steepest one above max_gradient proves it too low (the vector of the three
        // would overstate it at a kink, |p| at the origin giving sqrt 3).
        const double slopes[3] = {std::abs(value(i + 1, j, k) - v) / cell.x,
                                  std::abs(value(i, j + 1, k) - v) / cell.y,
                                  std::abs(value(i, j, k + 1) - v) / cell.z};
        for (double slope : slopes)
          if (std::isfinite(slope))
            probe.steepest_gradient = std::max(probe.steepest_gradient, slope);
      }
  return probe;
}

}  // namespace fb
