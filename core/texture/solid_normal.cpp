#include "core/texture/solid_normal.h"

#include <cmath>

#include "core/math/constants.h"
#include "core/texture/solid_pattern.h"

namespace fb {
namespace {

// POV-Ray's Pyramid_Vect: the unit corners of a regular tetrahedron about the origin. For a
// linear h, sum_k h(p + d v_k) v_k = (4/3) d grad h, since sum_k v_k = 0 and
// sum_k v_k v_k^T = (4/3) I.
constexpr Vec3d kNormalPyramid[4] = {{0.942809042, -0.333333333, 0.0},
                                     {-0.471404521, -0.333333333, 0.816496581},
                                     {-0.471404521, -0.333333333, -0.816496581},
                                     {0.0, 1.0, 0.0}};

// POV-Ray's ripples and waves normals: each source pushes the normal along the direction from it
// by amount sin(2 pi (|d| f + phase)) / sources (waves: f times the source's frequency, and the
// push divided by it).
Vec3d wave_normal_perturbation(const SolidNormal& n, Vec3d p, bool waves) {
  const SolidPattern& s = n.pattern;
  Vec3d sum{0, 0, 0};
  for (const solid::WaveSource& source : solid::wave_sources()) {
    const Vec3d d = p - source.centre;
    double len = std::sqrt(dot(d, d));
    if (len == 0) len = 1;
    const double f = waves ? source.frequency : 1.0;
    const double push = std::sin(2 * kPi * (len * s.frequency * f + s.phase)) * n.amount / f;
    sum += d * (push / (len * solid::kWaveSources));
  }
  return sum;
}

// POV-Ray's wrinkles normal: the absolute vector noise summed over ten octaves.
Vec3d wrinkles_normal_perturbation(const SolidNormal& n, Vec3d p) {
  Vec3d sum{0, 0, 0};
  double scale = 1;
  for (int i = 0; i < 10; ++i, scale *= 2) {
    const Vec3d v = solid::vector_noise(p * scale);
    sum += Vec3d{std::abs(v.x), std::abs(v.y), std::abs(v.z)} / scale;
  }
  return sum * n.amount;
}

// Any other pattern: its value differentiated over the tetrahedron, with POV-Ray's two fudge
// factors (-5, and 0.02 / accuracy so that the step does not change the depth).
Vec3d numeric_normal_perturbation(const SolidNormal& n, Vec3d p) {
  const double delta = n.accuracy > 0 ? n.accuracy : 0.02;
  const double scale = n.amount * -5.0 * (0.02 / delta);
  Vec3d sum{0, 0, 0};
  for (const Vec3d& v : kNormalPyramid) {
    const double value = solid::shape_value(n.pattern, solid::raw_value(n.pattern, p + v * delta));
    sum += v * (solid::slope_height(n.slope_map, value) * scale);
  }
  return sum;
}

}  // namespace

namespace solid {

double slope_height(const std::vector<SolidSlopeStop>& map, double value) {
  if (map.empty()) return value;
  if (!(value > map.front().value)) return map.front().height;
  for (size_t i = 1; i < map.size(); ++i) {
    const SolidSlopeStop &a = map[i - 1], &b = map[i];
    if (value > b.value) continue;
    const double t = b.value > a.value ? (value - a.value) / (b.value - a.value) : 1.0;
    // POV-Ray's Hermite_Cubic: height a.height at t = 0 and b.height at t = 1, with POV-Ray's
    // own mix of the slopes.
    const double dh = a.height - b.height;
    return t * t * t * (a.slope + b.slope + 2 * dh) - t * t * (2 * a.slope + b.slope + 3 * dh) +
           t * a.slope + a.height;
  }
  return map.back().height;
}

Vec3d normal_perturbation(const SolidNormal& n, Vec3d p) {
  using K = SolidPatternKind;
  switch (n.pattern.kind) {
    case K::kBumps:
      return vector_noise(p) * n.amount;
    case K::kDents: {
      const double v = noise(p);
      return vector_noise(p) * (v * v * v * n.amount);
    }
    case K::kWrinkles:
      return wrinkles_normal_perturbation(n, p);
    case K::kRipples:
      return wave_normal_perturbation(n, p, false);
    case K::kWaves:
      return wave_normal_perturbation(n, p, true);
    default:
      return numeric_normal_perturbation(n, p);
  }
}

}  // namespace solid

namespace {

// POV-Ray's Perturb_Normal for `n` at a point and normal of the space around it (the world, or
// the pattern space of the normal whose normal_map holds n): the normal bent, made unit. Normals
// go into pattern space by the inverse transpose of pattern_from_world and back by its transpose
// (POV-Ray's Warp_Normal and UnWarp_Normal). A normal_map entry lives in its map's pattern space,
// so the recursion is as deep as the maps nest (the SDL reader allows 6 levels).
Vec3d bend_solid_normal(const SolidNormal& n, Vec3d outer_point, Vec3d outer_normal) {
  const Transform& m = n.pattern.pattern_from_world;
  Vec3d normal = m.normal_transform().vector(outer_normal);
  const double len = std::sqrt(dot(normal, normal));
  if (n.scale_bumps && len > 0) normal = normal / len;
  const Vec3d p = solid::warped_point(n.pattern, m.point(outer_point));
  if (n.normal_map.empty()) {
    normal += solid::normal_perturbation(n, p);
  } else {
    // POV-Ray's NormalBlendMap: the entries about the pattern's value, blended linearly; the end
    // entries' normals beyond them.
    const double value = solid::shape_value(n.pattern, solid::raw_value(n.pattern, p));
    const std::vector<SolidNormalStop>& map = n.normal_map;
    size_t above = 0;
    while (above < map.size() && value > map[above].value)
      ++above;
    if (above == 0 || above == map.size()) {
      normal = bend_solid_normal(map[above == 0 ? 0 : map.size() - 1].normal, p, normal);
    } else {
      const SolidNormalStop &a = map[above - 1], &b = map[above];
      const double t = b.value > a.value ? (value - a.value) / (b.value - a.value) : 1.0;
      normal = bend_solid_normal(a.normal, p, normal) * (1 - t) +
               bend_solid_normal(b.normal, p, normal) * t;
    }
  }
  const Vec3d back{m(0, 0) * normal.x + m(1, 0) * normal.y + m(2, 0) * normal.z,
                   m(0, 1) * normal.x + m(1, 1) * normal.y + m(2, 1) * normal.z,
                   m(0, 2) * normal.x + m(1, 2) * normal.y + m(2, 2) * normal.z};
  const double back_len = std::sqrt(dot(back, back));
  if (!(back_len > 0) || !std::isfinite(back_len)) return outer_normal;
  return back / back_len;
}

}  // namespace

Vec3d perturbed_normal(const SolidNormal& n, Vec3d world_point, Vec3d world_normal) {
  return bend_solid_normal(n, world_point, world_normal);
}

}  // namespace fb
