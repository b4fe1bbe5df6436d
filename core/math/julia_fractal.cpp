#include "core/math/julia_fractal.h"

#include <algorithm>
#include <cmath>

namespace fb {

namespace {

// POV-Ray's Fractal_Tolerance, added to the quaternion bound so that c = 0 still bounds its ball.
constexpr double kJuliaBoundSlack = 1e-7;
// A crossing is bisected to this fraction of the bounding radius (at most kJuliaBisections
// halvings): far below a pixel of any view that shows the whole set.
constexpr double kJuliaRootFraction = 1e-10;
constexpr int kJuliaBisections = 80;

// A 4-D number (1, i, j, k parts).
struct Four {
  double v[4] = {0, 0, 0, 0};
};

Four operator+(const Four& a, const Four& b) {
  return {{a.v[0] + b.v[0], a.v[1] + b.v[1], a.v[2] + b.v[2], a.v[3] + b.v[3]}};
}

double norm2(const Four& a) {
  return a.v[0] * a.v[0] + a.v[1] * a.v[1] + a.v[2] * a.v[2] + a.v[3] * a.v[3];
}

// Hamilton's quaternion product, or the commutative hypercomplex one (POV-Ray's HMult: i^2 =
// j^2 = -1, k^2 = 1, ij = k).
Four product(JuliaAlgebra algebra, const Four& a, const Four& b) {
  const double* x = a.v;
  const double* y = b.v;
  if (algebra == JuliaAlgebra::kQuaternion)
    return {{x[0] * y[0] - x[1] * y[1] - x[2] * y[2] - x[3] * y[3],
             x[0] * y[1] + x[1] * y[0] + x[2] * y[3] - x[3] * y[2],
             x[0] * y[2] - x[1] * y[3] + x[2] * y[0] + x[3] * y[1],
             x[0] * y[3] + x[1] * y[2] - x[2] * y[1] + x[3] * y[0]}};
  return {{x[0] * y[0] - x[1] * y[1] - x[2] * y[2] + x[3] * y[3],
           x[1] * y[0] + x[0] * y[1] - x[3] * y[2] - x[2] * y[3],
           x[2] * y[0] - x[3] * y[1] + x[0] * y[2] - x[1] * y[3],
           x[3] * y[0] + x[2] * y[1] + x[1] * y[2] + x[0] * y[3]}};
}

// A 4-D number and its partial derivatives with respect to the object-space x, y, z: products
// follow the product rule (in order: quaternions do not commute).
struct Jet {
  Four value;
  Four d[3];
};

Jet product(JuliaAlgebra algebra, const Jet& a, const Jet& b) {
  Jet r;
  r.value = product(algebra, a.value, b.value);
  for (int i = 0; i < 3; ++i)
    r.d[i] = product(algebra, a.d[i], b.value) + product(algebra, a.value, b.d[i]);
  return r;
}

// z_0 for p: w from the slice hyperplane, w = (distance - slice.xyz . p) / slice.w.
Four start_value(const JuliaFractal& julia, Vec3d p) {
  const double* s = julia.slice;
  return {{p.x, p.y, p.z, (julia.slice_distance - s[0] * p.x - s[1] * p.y - s[2] * p.z) / s[3]}};
}

// The same with its derivatives.
Jet start(const JuliaFractal& julia, Vec3d p) {
  Jet z;
  z.value = start_value(julia, p);
  for (int i = 0; i < 3; ++i) {
    z.d[i].v[i] = 1;
    z.d[i].v[3] = -julia.slice[i] / julia.slice[3];
  }
  return z;
}

const Four& value_of(const Four& z) {
  return z;
}
const Four& value_of(const Jet& z) {
  return z.value;
}
Four plus(const Four& z, const Four& c) {
  return z + c;
}
Jet plus(Jet z, const Four& c) {
  z.value = z.value + c;
  return z;
}

// What one run of the iteration found: whether it escaped, and the iterate that escaped, or for a
// point inside the largest of those tested. Number: Four alone (the inside test, 4 times cheaper)
// or a Jet (the gradient and the distance estimate).
template <class Number>
struct JuliaOrbit {
  bool escaped = false;
  Number z;
};

template <class Number>
JuliaOrbit<Number> orbit(const JuliaFractal& julia, Number z) {
  JuliaOrbit<Number> result;
  const Four c{{julia.c[0], julia.c[1], julia.c[2], julia.c[3]}};
  double largest = -1;
  for (int k = 0; k < julia.max_iteration; ++k) {
    const double n2 = norm2(value_of(z));
    if (n2 > largest) largest = n2, result.z = z;
    if (n2 > julia.exit_value || !(n2 == n2)) {  // NaN: escaped too
      result.escaped = true;
      result.z = z;
      return result;
    }
    if (k + 1 == julia.max_iteration) break;  // POV-Ray tests no further iterate
    Number next = product(julia.algebra, z, z);
    if (julia.power == 3) next = product(julia.algebra, next, z);
    z = plus(next, c);
  }
  return result;
}

bool escapes(const JuliaFractal& julia, Vec3d p) {
  return orbit(julia, start_value(julia, p)).escaped;
}

// J^T z: half the gradient of |z|^2.
Vec3d half_gradient(const Jet& z) {
  double g[3];
  for (int i = 0; i < 3; ++i)
    g[i] = z.d[i].v[0] * z.value.v[0] + z.d[i].v[1] * z.value.v[1] + z.d[i].v[2] * z.value.v[2] +
           z.d[i].v[3] * z.value.v[3];
  return {g[0], g[1], g[2]};
}

// One run of the iteration at a sample of the march: whether p escapes and, if it does, a step
// from p that stays outside. The escaped iterate z_k keeps |z_k| > R on the way to the set, whose
// points have |z_k| <= R: half the log-space Newton step to that sphere, (ln|z_k| - ln R) /
// |grad ln|z_k||, with |grad |z_k|| bounded by the running derivative |z_k'| (no derivatives
// carried: |z_0'| = 1 / |slice_w|, |z_{k+1}'| <= m g^(m-1) |z_k|^(m-1) |z_k'|, g = 1 for
// quaternions, whose norm multiplies, sqrt(2) for hypercomplex numbers, |ab| <= sqrt(2) |a| |b|).
// Hubbard and Douady's factor 1/2 for the quaternion maps, a heuristic for the others.
struct JuliaSample {
  bool escaped = false;
  double step = 0;  // 0 where the estimate is no number
};

JuliaSample march_sample(const JuliaFractal& julia, Vec3d p) {
  const bool hypercomplex = julia.algebra == JuliaAlgebra::kHypercomplex;
  const double growth =
      julia.power * (hypercomplex ? std::pow(std::sqrt(2.0), julia.power - 1) : 1);
  const Four c{{julia.c[0], julia.c[1], julia.c[2], julia.c[3]}};
  Four z = start_value(julia, p);
  double slope = 1 / std::abs(julia.slice[3]);
  for (int k = 0; k < julia.max_iteration; ++k) {
    const double n2 = norm2(z);
    if (n2 > julia.exit_value || !(n2 == n2)) {
      const double d = 0.25 * (std::log(n2) - std::log(julia.exit_value)) * std::sqrt(n2) / slope;
      return {true, d > 0 && std::isfinite(d) ? d : 0};
    }
    if (k + 1 == julia.max_iteration) break;
    slope *= growth * (julia.power == 3 ? n2 : std::sqrt(n2));
    Four next = product(julia.algebra, z, z);
    if (julia.power == 3) next = product(julia.algebra, next, z);
    z = next + c;
  }
  return {};
}

}  // namespace

void julia_fractal_set_bounds(JuliaFractal& julia) {
  if (julia.algebra == JuliaAlgebra::kQuaternion) {
    const double* c = julia.c;
    const double r =
        1 + std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2] + c[3] * c[3]) + kJuliaBoundSlack;
    julia.radius = std::min(r, 2.0);
    julia.exit_value = julia.radius * julia.radius + kJuliaBoundSlack;
  } else {
    julia.radius = 4;
    julia.exit_value = 16;
  }
}

Bounds3d julia_fractal_bounds(const JuliaFractal& julia) {
  const double r = julia.radius;
  return {{-r, -r, -r}, {r, r, r}};
}

bool julia_fractal_contains(const JuliaFractal& julia, Vec3d p) {
  return !escapes(julia, p);
}

Vec3d julia_fractal_gradient(const JuliaFractal& julia, Vec3d p) {
  return half_gradient(orbit(julia, start(julia, p)).z);
}

bool julia_fractal_chord(const JuliaFractal& julia, Vec3d o, Vec3d d, double& t_in, double& t_out) {
  // |o + t d|^2 = R^2, in the numerically stable form
  const double a = dot(d, d), b = dot(o, d), c = dot(o, o) - julia.radius * julia.radius;
  const double disc = b * b - a * c;
  if (!(a > 0) || !(disc > 0)) return false;
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  double t0 = q / a, t1 = q != 0 ? c / q : -t0;
  if (t0 > t1) std::swap(t0, t1);
  t_in = t0, t_out = t1;
  return true;
}

JuliaWalk julia_fractal_walk(const JuliaFractal& julia, Vec3d o, Vec3d d, double t_in, double t_out,
                             double hi) {
  JuliaWalk walk;
  const double speed = length(d);
  const double enough = kJuliaRootFraction * julia.radius;
  double t = t_in;
  JuliaSample here = march_sample(julia, o + d * t);
  walk.inside_at_entry = !here.escaped;
  for (int samples = 0;; ++samples) {
    if (!(t < t_out)) {
      walk.t_end = t_out;
      return walk;
    }
    if (samples >= kJuliaMaxSamples || t > hi) break;
    // Inside, the step is POV-Ray's least.
    const double step = std::max(here.step, julia.least_step);
    const double t_next = std::min(t + step / speed, t_out);
    const JuliaSample next = march_sample(julia, o + d * t_next);
    if (next.escaped != here.escaped) {
      // Bisect, keeping [a, b] across the boundary; the crossing is its outside end, where the
      // gradient of the escaping iterate is the normal.
      double a = t, b = t_next;
      for (int i = 0; i < kJuliaBisections && (b - a) * speed > enough; ++i) {
        const double m = 0.5 * (a + b);
        (escapes(julia, o + d * m) == here.escaped ? a : b) = m;
      }
      if (walk.count == kJuliaMaxCrossings) {
        t = a;
        break;
      }
      walk.crossings[walk.count++] = here.escaped ? a : b;
    }
    t = t_next;
    here = next;
  }
  walk.complete = false;
  walk.t_end = t;
  return walk;
}

}  // namespace fb
