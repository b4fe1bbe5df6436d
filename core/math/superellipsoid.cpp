#include "core/math/superellipsoid.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace fb {

namespace {

// Samples per smooth piece of the ray: enough that a span of the set wider than an eighth of a
// piece holds a sample; narrower dips are found from the sampled minimum (superellipsoid.h).
constexpr int kSuperellipsoidSamples = 8;
// Pieces: the interval cut by five planes.
constexpr int kSuperellipsoidPieces = 6;
// Golden-section steps searching a sampled minimum for a dip below zero: 0.618^48 ~ 1e-10 of
// the sample spacing, below which a graze is a touch.
constexpr int kSuperellipsoidDipSteps = 48;

double value_along(SuperellipsoidExponents s, Vec3d o, Vec3d d, double t) {
  return superellipsoid_value(s, o + d * t);
}

// The sign change of f in (a, b), where (f(a) > 0) != (f(b) > 0), by bisection to neighbouring
// doubles: f is not smooth enough at the cut planes for Newton, and 60-odd halvings suffice.
double bisect(SuperellipsoidExponents s, Vec3d o, Vec3d d, double a, double b) {
  const bool a_positive = value_along(s, o, d, a) > 0;
  for (;;) {
    const double mid = 0.5 * (a + b);
    if (mid <= a || mid >= b) return mid;
    if ((value_along(s, o, d, mid) > 0) == a_positive)
      a = mid;
    else
      b = mid;
  }
}

// A point of (a, c) where f <= 0, searching from b, where f(b) < f(a) and f(b) <= f(c), for the
// bottom of the dip by golden section; NAN if the dip stays above zero.
double dip_below_zero(SuperellipsoidExponents s, Vec3d o, Vec3d d, double a, double b, double c) {
  constexpr double kGolden = 0.3819660112501051;  // 2 - phi
  double fb_ = value_along(s, o, d, b);
  for (int step = 0; step < kSuperellipsoidDipSteps; ++step) {
    const bool right = c - b > b - a;  // probe the larger side
    const double x = right ? b + kGolden * (c - b) : b - kGolden * (b - a);
    const double fx = value_along(s, o, d, x);
    if (fx <= 0) return x;
    if (fx < fb_) {
      (right ? a : c) = b;
      b = x, fb_ = fx;
    } else {
      (right ? c : a) = x;
    }
  }
  return NAN;
}

void add_root(double t, double* roots, int& count) {
  if (count < kSuperellipsoidMaxCrossings) roots[count++] = t;
}

}  // namespace

double superellipsoid_value(SuperellipsoidExponents s, Vec3d p) {
  const double xy = std::pow(std::abs(p.x), 2 / s.e) + std::pow(std::abs(p.y), 2 / s.e);
  return std::pow(xy, s.e / s.n) + std::pow(std::abs(p.z), 2 / s.n) - 1;
}

Vec3d superellipsoid_gradient(SuperellipsoidExponents s, Vec3d p) {
  // grad f = (2/n) (g^(e/n - 1) |x|^(2/e - 1) sgn x, ... y ..., |z|^(2/n - 1) sgn z) with
  // g = |x|^(2/e) + |y|^(2/e); each component's logarithm, then scaled by the largest.
  constexpr double kTiny = 1e-300;
  const double lx = std::log(std::max(std::abs(p.x), kTiny));
  const double ly = std::log(std::max(std::abs(p.y), kTiny));
  const double lz = std::log(std::max(std::abs(p.z), kTiny));
  const double ax = 2 / s.e * lx, ay = 2 / s.e * ly, m = std::max(ax, ay);
  const double log_g = m + std::log(std::exp(ax - m) + std::exp(ay - m));
  const double gx = (s.e / s.n - 1) * log_g + (2 / s.e - 1) * lx;
  const double gy = (s.e / s.n - 1) * log_g + (2 / s.e - 1) * ly;
  const double gz = (2 / s.n - 1) * lz;
  // An exact zero coordinate contributes nothing: the pole of a round section, or a cusp's tip
  // whose normal is undefined.
  const double top =
      std::max({p.x != 0 ? gx : -HUGE_VAL, p.y != 0 ? gy : -HUGE_VAL, p.z != 0 ? gz : -HUGE_VAL});
  const auto component = [top](double log_size, double coordinate) {
    return coordinate == 0 ? 0.0 : std::copysign(std::exp(log_size - top), coordinate);
  };
  return {component(gx, p.x), component(gy, p.y), component(gz, p.z)};
}

Vec3d superellipsoid_point(SuperellipsoidExponents s, double eta, double omega) {
  const auto signed_power = [](double v, double k) {
    return std::copysign(std::pow(std::abs(v), k), v);
  };
  const double ring = signed_power(std::cos(eta), s.n);
  return {ring * signed_power(std::cos(omega), s.e), ring * signed_power(std::sin(omega), s.e),
          signed_power(std::sin(eta), s.n)};
}

int superellipsoid_crossings(SuperellipsoidExponents s, Vec3d o, Vec3d d, double lo, double hi,
                             double* roots) {
  if (!(lo < hi)) return 0;
  // The pieces' ends: lo, where the ray crosses x = 0, y = 0, z = 0, x = y, x = -y, hi.
  double ends[kSuperellipsoidPieces + 1];
  int end_count = 0;
  ends[end_count++] = lo;
  const double planes[5][2] = {
      {o.x, d.x}, {o.y, d.y}, {o.z, d.z}, {o.x - o.y, d.x - d.y}, {o.x + o.y, d.x + d.y}};
  for (const auto& [offset, rate] : planes) {
    const double t = -offset / rate;
    if (t > lo && t < hi) ends[end_count++] = t;
  }
  ends[end_count++] = hi;
  // Insertion sort: seven at most (std::sort on so short an array trips GCC's -Warray-bounds).
  for (int i = 1; i < end_count; ++i)
    for (int j = i; j > 0 && ends[j] < ends[j - 1]; --j)
      std::swap(ends[j], ends[j - 1]);
  int count = 0;
  double t_before = NAN, f_before = NAN, t_prev = lo, f_prev = value_along(s, o, d, lo);
  for (int piece = 0; piece + 1 < end_count; ++piece)
    for (int i = 1; i <= kSuperellipsoidSamples; ++i) {
      const double t = i == kSuperellipsoidSamples ? ends[piece + 1]
                                                   : ends[piece] + (ends[piece + 1] - ends[piece]) *
                                                                       i / kSuperellipsoidSamples;
      if (!(t > t_prev)) continue;  // pieces of zero width
      const double f = value_along(s, o, d, t);
      if ((f > 0) != (f_prev > 0)) {
        add_root(bisect(s, o, d, t_prev, t), roots, count);
      } else if (f > 0 && f_prev < f_before && f_prev <= f) {
        const double dip = dip_below_zero(s, o, d, t_before, t_prev, t);
        if (!std::isnan(dip)) {
          add_root(bisect(s, o, d, t_before, dip), roots, count);
          add_root(bisect(s, o, d, dip, t), roots, count);
        }
      }
      t_before = t_prev, f_before = f_prev;
      t_prev = t, f_prev = f;
    }
  return count - count % 2;
}

}  // namespace fb
