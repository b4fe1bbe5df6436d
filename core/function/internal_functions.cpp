#include "core/function/internal_functions.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

#include "core/texture/solid_pattern.h"

namespace fb {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

// Arguments: x, y, z, then the function's own parameters p[0], p[1] ...
struct InternalArguments {
  const double* a;
  double x() const { return a[0]; }
  double y() const { return a[1]; }
  double z() const { return a[2]; }
  double p(int i) const { return a[3 + i]; }
};

// f_ellipsoid (17): the sphere's distance with each axis scaled by p0, p1, p2.
double ellipsoid(InternalArguments a) {
  const double x = a.x() * a.p(0), y = a.y() * a.p(1), z = a.z() * a.p(2);
  return std::sqrt(x * x + y * y + z * z);
}

// f_helix1 (25): p0 helices of frequency p1 about y, minor radius p2, major radius p3, p4 the
// shape (stretch along the helix), p5 the cross section (1 circle, 2 diamond, < 1 rounded
// rectangle, 0 square) turned by p6 degrees.
double helix1(InternalArguments a) {
  const double r = std::hypot(a.x(), a.z());
  const double x_for_angle = (a.x() == 0 && a.z() == 0) ? 1e-6 : a.x();
  double turn =
      std::fmod(std::atan2(a.z(), x_for_angle) * a.p(0) + a.y() * a.p(1) * a.p(0), kTwoPi);
  if (turn < 0) turn += kTwoPi;
  double along = (turn - std::numbers::pi) / a.p(4) / (a.p(1) * a.p(0));
  double across = r - a.p(3);
  double section;
  if (a.p(5) == 1) {
    section = std::hypot(across, along);
  } else {
    if (a.p(6) != 0) {
      const double c = std::cos(a.p(6) * std::numbers::pi / 180),
                   s = std::sin(a.p(6) * std::numbers::pi / 180);
      const double turned = across * c - along * s;
      along = across * s + along * c;
      across = turned;
    }
    if (a.p(5) != 0) {
      const double e = 2 / a.p(5);
      section = std::pow(std::pow(std::abs(across), e) + std::pow(std::abs(along), e), a.p(5) / 2);
    } else {
      section = std::max(std::abs(across), std::abs(along));
    }
  }
  return -a.p(2) + std::min(a.p(3) + r, section);
}

// f_ridged_mf (59): Musgrave's ridged multifractal: p0 the fractal increment H, p1 the
// lacunarity, p2 the octaves, p3 the offset, p4 the gain (p5, the noise generator, is ours).
double ridged_multifractal(InternalArguments a) {
  Vec3d point{a.x(), a.y(), a.z()};
  const auto ridge = [&](Vec3d q) {
    const double s = a.p(3) - std::abs(solid::noise(q) * 2 - 1);
    return s * s;
  };
  double signal = ridge(point), result = signal;
  const int octaves = int(std::clamp(a.p(2), 0.0, 64.0));
  const double octave_weight = std::pow(a.p(1), -a.p(0));
  double amplitude = 1;
  for (int i = 1; i < octaves; ++i) {
    point = point * a.p(1);
    amplitude *= octave_weight;
    const double weight = std::clamp(signal * a.p(4), 0.0, 1.0);
    signal = ridge(point) * weight;
    result += signal * amplitude;
  }
  return result;
}

// f_rounded_box (60): the distance to a box of half sizes p1, p2, p3 with edges rounded by p0.
double rounded_box(InternalArguments a) {
  const auto outside = [&](double v, double half) {
    const double inner = half - a.p(0);
    return std::max(v > inner ? v - inner : 0.0, v < -inner ? -inner - v : 0.0);
  };
  const double x = outside(a.x(), a.p(1)), y = outside(a.y(), a.p(2)), z = outside(a.z(), a.p(3));
  return -a.p(0) + std::sqrt(x * x + y * y + z * z) - 1e-6;
}

// f_superellipsoid (68): 1 - the superellipsoid's implicit function, p0 east-west (e), p1
// north-south (n) exponents, as the `superellipsoid` object.
double superellipsoid(InternalArguments a) {
  const double e = a.p(0), n = a.p(1);
  const double xy = std::pow(std::abs(a.x()), 2 / e) + std::pow(std::abs(a.y()), 2 / e);
  return 1 - std::pow(std::pow(xy, e / n) + std::pow(std::abs(a.z()), 2 / n), n / 2);
}

// f_torus (70): the distance to a torus about y of major radius p0 and minor radius p1.
double torus(InternalArguments a) {
  return -a.p(1) + std::hypot(std::hypot(a.x(), a.z()) - a.p(0), a.y());
}

// The parameters besides x, y, z of every internal(N), N = 0 ... 78 (POV-Ray 3.7's table), so
// that a call of one filmback does not evaluate still reads its arguments.
constexpr int kInternalParameters[] = {5, 5, 5, 5, 2,  2, 5, 4, 2, 1, 4, 1, 1, 1, 1, 6, 6, 3, 1, 4,
                                       3, 6, 1, 1, 10, 7, 7, 1, 1, 6, 1, 3, 4, 3, 6, 1, 1, 4, 1, 6,
                                       5, 1, 1, 1, 4,  1, 3, 0, 1, 1, 7, 5, 6, 1, 1, 1, 3, 0, 6, 6,
                                       4, 1, 5, 4, 6,  1, 4, 7, 2, 0, 2, 3, 1, 1, 2, 6, 0, 0, 1};
constexpr int kInternalCount = int(std::size(kInternalParameters));

struct InternalFunction {
  int number;
  double (*evaluate)(InternalArguments);
};

constexpr InternalFunction kInternalFunctions[] = {
    {17, ellipsoid},
    {25, helix1},
    // f_ph (47): the angle from +y
    {47, [](InternalArguments a) { return std::atan2(std::hypot(a.x(), a.z()), a.y()); }},
    // f_r (57): the distance from the origin
    {57,
     [](InternalArguments a) { return std::sqrt(a.x() * a.x() + a.y() * a.y() + a.z() * a.z()); }},
    {59, ridged_multifractal},
    {60, rounded_box},
    // f_sphere (61): the distance to a sphere of radius p0
    {61,
     [](InternalArguments a) {
       return -a.p(0) + std::sqrt(a.x() * a.x() + a.y() * a.y() + a.z() * a.z());
     }},
    {68, superellipsoid},
    // f_th (69): the angle about y from +z
    {69, [](InternalArguments a) { return std::atan2(a.x(), a.z()); }},
    {70, torus},
    // f_noise3d (76) and f_noise_generator (78): the lattice noise in [0, 1] (filmback has one
    // generator, so p0 of f_noise_generator is read and not used)
    {76,
     [](InternalArguments a) {
       return solid::noise({a.x(), a.y(), a.z()});
     }},
    {78,
     [](InternalArguments a) {
       return solid::noise({a.x(), a.y(), a.z()});
     }},
};

const InternalFunction* find_internal(int number) {
  for (const InternalFunction& f : kInternalFunctions)
    if (f.number == number) return &f;
  return nullptr;
}

}  // namespace

bool internal_function_known(int number) {
  return find_internal(number) != nullptr;
}

bool internal_function_exists(int number) {
  return number >= 0 && number < kInternalCount;
}

int internal_function_arguments(int number) {
  return internal_function_exists(number) ? 3 + kInternalParameters[number] : 0;
}

double internal_function(int number, const double* arguments) {
  const InternalFunction* f = find_internal(number);
  return f ? f->evaluate({arguments}) : 0;
}

}  // namespace fb
