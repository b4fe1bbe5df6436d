#include "core/math/sphere_sweep.h"

#include <algorithm>
#include <cmath>

#include "core/math/polynomial.h"

namespace fb {

namespace {

// A polynomial in u of degree < kSweepTerms, c[0] + c[1] u + ...: the products below reach 10.
constexpr int kSweepTerms = 11;
struct UPoly {
  double c[kSweepTerms] = {};
};

UPoly times(const UPoly& a, int degree_a, const UPoly& b, int degree_b) {
  UPoly p;
  for (int i = 0; i <= degree_a; ++i)
    for (int j = 0; j <= degree_b && i + j < kSweepTerms; ++j)
      p.c[i + j] += a.c[i] * b.c[j];
  return p;
}

UPoly plus(const UPoly& a, const UPoly& b, double scale_b = 1) {
  UPoly p;
  for (int i = 0; i < kSweepTerms; ++i)
    p.c[i] = a.c[i] + scale_b * b.c[i];
  return p;
}

// One axis of o - c(u), of c'(u), and r(u), r'(u), as polynomials.
UPoly axis_offset(const SweepSegment& s, Vec3d o, int axis) {
  UPoly p;
  for (int i = 0; i < 4; ++i)
    p.c[i] = -s.c[i][axis];
  p.c[0] += o[axis];
  return p;
}

UPoly axis_slope(const SweepSegment& s, int axis) {
  UPoly p;
  for (int i = 1; i < 4; ++i)
    p.c[i - 1] = i * s.c[i][axis];
  return p;
}

UPoly radius(const SweepSegment& s) {
  UPoly p;
  std::copy_n(s.r, 4, p.c);
  return p;
}

UPoly radius_slope(const SweepSegment& s) {
  UPoly p;
  for (int i = 1; i < 4; ++i)
    p.c[i - 1] = i * s.r[i];
  return p;
}

// |p - c(u)|^2 - r(u)^2, degree 6.
UPoly reach(const SweepSegment& s, Vec3d p) {
  UPoly h = times(radius(s), 3, radius(s), 3);
  for (double& c : h.c)
    c = -c;
  for (int a = 0; a < 3; ++a) {
    const UPoly q = axis_offset(s, p, a);
    h = plus(h, times(q, 3, q, 3));
  }
  return h;
}

Vec3d centre(const SweepSegment& s, double u) {
  return s.c[0] + (s.c[1] + (s.c[2] + s.c[3] * u) * u) * u;
}

double radius_at(const SweepSegment& s, double u) {
  return s.r[0] + (s.r[1] + (s.r[2] + s.r[3] * u) * u) * u;
}

// The line's crossings of the sphere at u: |o + s d - c|^2 = r^2.
int sphere_crossings(const SweepSegment& seg, double u, Vec3d o, Vec3d d, double* s) {
  const Vec3d q = o - centre(seg, u);
  const double r = radius_at(seg, u), a = dot(d, d), b = dot(q, d), c = dot(q, q) - r * r;
  const double disc = b * b - a * c;
  if (!(disc > 0) || !(a > 0)) return 0;
  const double h = std::sqrt(disc);
  s[0] = (-b - h) / a, s[1] = (-b + h) / a;
  return 2;
}

}  // namespace

size_t sweep_least_spheres(SweepSpline spline) {
  return spline == SweepSpline::kLinear ? 2 : 4;
}

SphereSweep sphere_sweep_from_spheres(SweepSpline spline, const std::vector<Vec3d>& centres,
                                      const std::vector<double>& radii) {
  // The power-basis matrices of POV-Ray's spheresweep.cpp: row k gives the coefficient of u^k
  // from four consecutive spheres.
  static constexpr double kBSpline[4][4] = {{1.0 / 6, 4.0 / 6, 1.0 / 6, 0},
                                            {-3.0 / 6, 0, 3.0 / 6, 0},
                                            {3.0 / 6, -6.0 / 6, 3.0 / 6, 0},
                                            {-1.0 / 6, 3.0 / 6, -3.0 / 6, 1.0 / 6}};
  static constexpr double kCatmullRom[4][4] = {
      {0, 1, 0, 0}, {-0.5, 0, 0.5, 0}, {1, -2.5, 2, -0.5}, {-0.5, 1.5, -1.5, 0.5}};
  SphereSweep sweep;
  const size_t n = std::min(centres.size(), radii.size());
  if (n < sweep_least_spheres(spline)) return sweep;
  const bool linear = spline == SweepSpline::kLinear;
  const auto& m = spline == SweepSpline::kBSpline ? kBSpline : kCatmullRom;
  for (size_t i = 0; i + (linear ? 1 : 3) < n; ++i) {
    SweepSegment s;
    if (linear) {
      s.c[0] = centres[i], s.c[1] = centres[i + 1] - centres[i];
      s.r[0] = radii[i], s.r[1] = radii[i + 1] - radii[i];
    } else {
      for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 4; ++j)
          s.c[k] = s.c[k] + centres[i + j] * m[k][j], s.r[k] += radii[i + j] * m[k][j];
    }
    // The Bezier control points of c and r (the curve lies in their hull, |r| within theirs).
    const Vec3d b[4] = {s.c[0], s.c[0] + s.c[1] / 3, s.c[0] + s.c[1] * (2.0 / 3) + s.c[2] / 3,
                        s.c[0] + s.c[1] + s.c[2] + s.c[3]};
    const double rb[4] = {s.r[0], s.r[0] + s.r[1] / 3, s.r[0] + s.r[1] * (2.0 / 3) + s.r[2] / 3,
                          s.r[0] + s.r[1] + s.r[2] + s.r[3]};
    double widest = 0;
    for (double r : rb)
      widest = std::max(widest, std::abs(r));
    for (const Vec3d& p : b)
      s.bounds.extend(
          Bounds3d{p - Vec3d{widest, widest, widest}, p + Vec3d{widest, widest, widest}});
    sweep.segments.push_back(s);
  }
  return sweep;
}

Bounds3d sphere_sweep_bounds(const SphereSweep& sweep) {
  Bounds3d box;
  for (const SweepSegment& s : sweep.segments)
    box.extend(s.bounds);
  return box;
}

double sweep_segment_value(const SweepSegment& segment, Vec3d p, double* at_u) {
  const UPoly h = reach(segment, p);
  UPoly slope;
  for (int i = 1; i <= 6; ++i)
    slope.c[i - 1] = i * h.c[i];
  double u[5];
  const int count = sign_changes(slope.c, 5, 0, 1, u);
  double best = evaluate_polynomial(h.c, 6, 0), best_u = 0;
  const auto consider = [&](double v) {
    const double value = evaluate_polynomial(h.c, 6, v);
    if (value < best) best = value, best_u = v;
  };
  consider(1);
  for (int i = 0; i < count; ++i)
    consider(u[i]);
  if (at_u) *at_u = best_u;
  return best;
}

double sphere_sweep_value(const SphereSweep& sweep, Vec3d p) {
  double best = HUGE_VAL;
  for (const SweepSegment& s : sweep.segments) {
    const Bounds3d& b = s.bounds;
    if (p.x < b.lo.x || p.y < b.lo.y || p.z < b.lo.z || p.x > b.hi.x || p.y > b.hi.y ||
        p.z > b.hi.z)
      continue;
    best = std::min(best, sweep_segment_value(s, p));
  }
  return best;
}

Vec3d sweep_segment_normal(const SweepSegment& segment, Vec3d p) {
  double u = 0;
  sweep_segment_value(segment, p, &u);
  return p - centre(segment, u);
}

int sweep_segment_crossings(const SweepSegment& seg, Vec3d o, Vec3d d, double* s) {
  int count = sphere_crossings(seg, 0, o, d, s);
  count += sphere_crossings(seg, 1, o, d, s + count);
  // Where the sphere at u touches the line: G(s, u) = |o + s d - c(u)|^2 - r(u)^2 = 0 and
  // dG/du = -2 (A(u) s + B(u)) = 0, A = d . c', B = (o - c) . c' + r r'. With s = -B / A,
  // A^2 G = |d|^2 B^2 - 2 A B D + A^2 E = 0, D = d . (o - c), E = |o - c|^2 - r^2.
  UPoly a, b = times(radius(seg), 3, radius_slope(seg), 2), dd;
  for (int k = 0; k < 3; ++k) {
    const UPoly offset = axis_offset(seg, o, k), slope = axis_slope(seg, k);
    for (int i = 0; i < 3; ++i)
      a.c[i] += d[k] * slope.c[i];
    for (int i = 0; i < 4; ++i)
      dd.c[i] += d[k] * offset.c[i];
    b = plus(b, times(offset, 3, slope, 2));
  }
  double a_size = 0, slope_size = 0;
  for (int i = 0; i < 3; ++i) {
    a_size = std::max(a_size, std::abs(a.c[i]));
    slope_size = std::max(slope_size, length(seg.c[i + 1]) * (i + 1));
  }
  double u[10];
  if (a_size <= 1e-12 * length(d) * slope_size) {
    // The line is square to the curve's plane (A = 0 for all u): the spheres touching it are
    // those where B = 0, each crossed where G = 0.
    const int roots = sign_changes(b.c, 5, 0, 1, u);
    for (int i = 0; i < roots; ++i)
      count += sphere_crossings(seg, u[i], o, d, s + count);
    return count;
  }
  const UPoly e = reach(seg, o);
  UPoly p = times(b, 5, b, 5);
  for (double& c : p.c)
    c *= dot(d, d);
  p = plus(p, times(times(a, 2, b, 5), 7, dd, 3), -2);
  p = plus(p, times(times(a, 2, a, 2), 4, e, 6));
  int degree = 10;
  while (degree > 0 && p.c[degree] == 0)
    --degree;
  const int roots = sign_changes(p.c, degree, 0, 1, u);
  for (int i = 0; i < roots; ++i) {
    const double slope = evaluate_polynomial(a.c, 2, u[i]);
    if (slope == 0) continue;
    // -B/A loses what the root u loses twice over; the point is on the sphere at u, whose
    // crossing nearest it has the root's error only to second order (the envelope touches it).
    const double estimate = -evaluate_polynomial(b.c, 5, u[i]) / slope;
    double on_sphere[2];
    s[count] = estimate;
    if (sphere_crossings(seg, u[i], o, d, on_sphere) == 2)
      s[count] = std::abs(on_sphere[0] - estimate) < std::abs(on_sphere[1] - estimate)
                     ? on_sphere[0]
                     : on_sphere[1];
    ++count;
  }
  return count;
}

}  // namespace fb
