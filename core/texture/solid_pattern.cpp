#include "core/texture/solid_pattern.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "core/function/user_function.h"
#include "core/math/constants.h"
#include "core/texture/solid_defaults.h"
#include "core/texture/solid_image_map.h"

namespace fb {
namespace {

// POV-Ray's EPSILON (source/core/configcore.h): nudges lattice patterns off exact cell borders.
constexpr double kEpsilon = 1e-10;
// What filmback's lattice patterns (checker, cells, brick) nudge by instead. POV-Ray's EPSILON
// works on its double-precision hit points; filmback's are floats in world space (relative error
// 6e-8: 1.2e-6 at 20 m), so a surface lying on a cell border in pattern space falls on either
// side of it at random, a speckle POV-Ray does not draw (a mesh square at z = 0 moved to z = 20
// under `checker`, 160 x 120 at 1 spp: 1022 lone pixels with EPSILON, 12 with this, the edges'
// own). 1e-4 exceeds that error up to about a kilometre and shifts no border visibly.
constexpr double kLatticeNudge = 1e-4;

double frac(double v) {
  return v - std::floor(v);
}

// POV-Ray's cycloidal(): sin(2 pi v).
double cycloidal(double v) {
  return std::sin(2 * kPi * v);
}

// POV-Ray's Triangle_Wave(): 0 -> 1 -> 0 over each unit interval.
double triangle_wave(double v) {
  double f = frac(v);
  if (f > 0.5) f = 1 - f;
  return 2 * f;
}

uint64_t mix(uint64_t h) {  // splitmix64's finaliser (Steele et al. 2014)
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ull;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebull;
  return h ^ (h >> 31);
}

uint64_t hash_cell(int64_t x, int64_t y, int64_t z) {
  return mix(mix(mix(uint64_t(x) + 0x9e3779b97f4a7c15ull) ^ uint64_t(y)) ^ uint64_t(z));
}

double unit_from_hash(uint64_t h) {
  return double(h >> 11) * 0x1p-53;
}  // [0, 1)

// Perlin's permutation, drawn once by a fixed shuffle so that every run sees the same noise.
const std::array<uint8_t, 512>& permutation() {
  static const std::array<uint8_t, 512> table = [] {
    std::array<uint8_t, 256> p;
    for (int i = 0; i < 256; ++i)
      p[i] = uint8_t(i);
    uint64_t state = 0x5eed;
    for (int i = 255; i > 0; --i) {
      state = mix(state + 0x9e3779b97f4a7c15ull);
      std::swap(p[i], p[state % uint64_t(i + 1)]);
    }
    std::array<uint8_t, 512> doubled;
    for (int i = 0; i < 512; ++i)
      doubled[i] = p[i & 255];
    return doubled;
  }();
  return table;
}

double fade(double t) {
  return t * t * t * (t * (t * 6 - 15) + 10);
}

double grad(uint8_t hash, double x, double y, double z) {
  const int h = hash & 15;
  const double u = h < 8 ? x : y;
  const double v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

// Perlin 2002, "Improving Noise": gradient noise in about [-1, 1], zero at lattice points.
double perlin(Vec3d p) {
  const auto& perm = permutation();
  const double fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  const int X = int(int64_t(fx) & 255), Y = int(int64_t(fy) & 255), Z = int(int64_t(fz) & 255);
  const double x = p.x - fx, y = p.y - fy, z = p.z - fz;
  const double u = fade(x), v = fade(y), w = fade(z);
  const int A = perm[X] + Y, AA = perm[A] + Z, AB = perm[A + 1] + Z;
  const int B = perm[X + 1] + Y, BA = perm[B] + Z, BB = perm[B + 1] + Z;
  const auto lerp = [](double t, double a, double b) { return a + t * (b - a); };
  return lerp(
      w,
      lerp(v, lerp(u, grad(perm[AA], x, y, z), grad(perm[BA], x - 1, y, z)),
           lerp(u, grad(perm[AB], x, y - 1, z), grad(perm[BB], x - 1, y - 1, z))),
      lerp(v, lerp(u, grad(perm[AA + 1], x, y, z - 1), grad(perm[BA + 1], x - 1, y, z - 1)),
           lerp(u, grad(perm[AB + 1], x, y - 1, z - 1), grad(perm[BB + 1], x - 1, y - 1, z - 1))));
}

// Scales perlin() (standard deviation 0.258 over a 40 x 40 plane, as solid_pattern_test measures)
// to POV-Ray's Noise(), whose standard deviation is 0.132 about 0.5.
constexpr double kNoiseScale = 0.132 / 0.258;

// POV-Ray's default colour maps and list colours (source/core/material/pattern.cpp).
SolidColourStop stop(float v, float r, float g, float b) {
  return {v, {{r, g, b}, 0.f, 0.f}};
}

}  // namespace

namespace solid {

const std::vector<SolidColourStop>& default_map(SolidPatternKind kind) {
  using K = SolidPatternKind;
  static const std::vector<SolidColourStop> grey = {stop(0, 0, 0, 0), stop(1, 1, 1, 1)};
  static const std::vector<SolidColourStop> agate = {
      stop(0, 1, 1, 1),         stop(0.5, 0.95, 0.75, 0.5), stop(0.5, 0.9, 0.7, 0.5),
      stop(0.6, 0.9, 0.7, 0.4), stop(0.6, 1, 0.7, 0.4),     stop(1, 0.6, 0.3, 0)};
  static const std::vector<SolidColourStop> bozo = {stop(0.4, 1, 1, 1), stop(0.4, 0, 1, 0),
                                                    stop(0.6, 0, 1, 0), stop(0.6, 0, 0, 1),
                                                    stop(0.8, 0, 0, 1), stop(0.8, 1, 0, 0)};
  static const std::vector<SolidColourStop> marble = {
      stop(0, 0.9, 0.8, 0.8), stop(0.9, 0.9, 0.08, 0.08), stop(0.9, 0, 0, 0)};
  static const std::vector<SolidColourStop> radial = {stop(0, 0, 1, 1), stop(0.333f, 1, 1, 0),
                                                      stop(0.666f, 1, 0, 1), stop(1, 0, 1, 1)};
  static const std::vector<SolidColourStop> wood = {stop(0.6f, 0.666f, 0.312f, 0.2f),
                                                    stop(0.6f, 0.4f, 0.1333f, 0.066f)};
  switch (kind) {
    case K::kAgate:
      return agate;
    case K::kBozo:
      return bozo;
    case K::kMarble:
      return marble;
    case K::kRadial:
      return radial;
    case K::kWood:
      return wood;
    default:
      return grey;
  }
}

SolidColour default_list_colour(SolidPatternKind kind, int index) {
  using K = SolidPatternKind;
  static const Rgb checker[2] = {{0, 0, 1}, {0, 1, 0}};
  static const Rgb hexagon[3] = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}};
  static const Rgb brick[2] = {{0.5f, 0.5f, 0.5f}, {0.6f, 0.15f, 0.15f}};  // mortar, brick
  const Rgb* table = kind == K::kChecker ? checker : kind == K::kHexagon ? hexagon : brick;
  return {table[index], 0.f, 0.f};
}

int list_size(SolidPatternKind kind) {
  return kind == SolidPatternKind::kHexagon ? 3 : 2;
}

bool is_list(SolidPatternKind kind) {
  using K = SolidPatternKind;
  return kind == K::kChecker || kind == K::kHexagon || kind == K::kBrick;
}

}  // namespace solid

namespace {

// Patterns that apply their turbulence themselves instead of warping the point first
// (HasSpecialTurbulenceHandling in POV-Ray's source).
bool special_turbulence(SolidPatternKind kind) {
  using K = SolidPatternKind;
  return kind == K::kMarble || kind == K::kWood || kind == K::kAgate || kind == K::kSpiral1 ||
         kind == K::kSpiral2;
}

// POV-Ray's checker_pattern: the parity of the unit cube.
double checker(Vec3d p) {
  const int64_t sum = int64_t(std::floor(p.x + kLatticeNudge)) +
                      int64_t(std::floor(p.y + kLatticeNudge)) +
                      int64_t(std::floor(p.z + kLatticeNudge));
  return (sum & 1) ? 1 : 0;
}

// POV-Ray's hexagon_pattern (Ernest MacDougal Campbell III): hexagons of unit side in the XZ
// plane, three colours; the plane is folded into a 6 x 6 grid of half-triangle cells.
double hexagon(Vec3d p) {
  constexpr double kCellX = 0.5, kCellZ = 0.866025404;  // half a side, a triangle's height
  const double x = std::abs(p.x);
  const double z = p.z < 0 ? 5.196152424 - std::abs(p.z) : p.z;  // no mirror across the x axis
  double xs = x / kCellX, zs = z / kCellZ;
  xs -= std::floor(xs / 6) * 6;
  zs -= std::floor(zs / 6) * 6;
  const int xm = int(std::floor(xs)) % 6, zm = int(std::floor(zs)) % 6;
  // Rows of the 6 x 6 grid by zm: the colour of whole cells in columns 0/5 and 2/3, and of the
  // lower and upper halves of the diagonally split cells in columns 1/4.
  static constexpr int kEdge[6] = {0, 1, 1, 2, 2, 0};
  static constexpr int kMiddle[6] = {2, 2, 0, 0, 1, 1};
  static constexpr int kBelow[6] = {0, 2, 1, 0, 2, 1};
  static constexpr int kAbove[6] = {2, 1, 0, 2, 1, 0};
  if (xm == 0 || xm == 5) return kEdge[zm];
  if (xm == 2 || xm == 3) return kMiddle[zm];
  double xl = xs - xm;
  const double zl = zs - zm;
  if ((xm + zm) % 2 == 1) xl = 1 - xl;  // negatively sloped cells, flipped
  if (xl == 0) xl = 1e-4;
  return zl / xl < 1 ? kBelow[zm] : kAbove[zm];
}

// POV-Ray's brick_pattern (Dan Farmer): 0 in the mortar, 1 in a brick; courses alternate by half
// a brick.
double brick(Vec3d p, Vec3d size, double mortar) {
  const double nudge = kLatticeNudge + mortar;
  const double x = p.x + nudge, y = p.y + nudge, z = p.z + nudge;
  if (frac(y / size.y) <= mortar / size.y) return 0;
  const double course = frac(y / size.y * 0.5);  // <= 0.5: odd courses
  const double width = mortar / size.x, depth = mortar / size.z;
  if (course <= 0.5 ? frac(x / size.x) <= width : frac(x / size.x + 0.5) <= width) return 0;
  if (course > 0.5 ? frac(z / size.z) <= depth : frac(z / size.z + 0.5) <= depth) return 0;
  return 1;
}

// Angle about the z axis in [0, 2 pi), as POV-Ray's spiral patterns measure it.
double spiral_angle(double x, double y, double radius) {
  if (radius == 0) return 0;
  return x < 0 ? 1.5 * kPi - std::asin(y / radius) : 0.5 * kPi + std::asin(y / radius);
}

// Crackle (Jim McElhiney): the distance to the second-nearest of one random point per unit cube
// minus the distance to the nearest (POV-Ray's default form <-1, 1, 0>, metric 2). The nearest
// two lie within two cubes of the point's.
double crackle(Vec3d p) {
  const int64_t cx = int64_t(std::floor(p.x - kEpsilon)), cy = int64_t(std::floor(p.y - kEpsilon)),
                cz = int64_t(std::floor(p.z - kEpsilon));
  double d1 = HUGE_VAL, d2 = HUGE_VAL;
  for (int64_t i = -2; i <= 2; ++i)
    for (int64_t j = -2; j <= 2; ++j)
      for (int64_t k = -2; k <= 2; ++k) {
        if (std::abs(i) + std::abs(j) + std::abs(k) > 4) continue;  // the far corners never win
        const uint64_t h = hash_cell(cx + i, cy + j, cz + k);
        const Vec3d nucleus{double(cx + i) + unit_from_hash(mix(h)),
                            double(cy + j) + unit_from_hash(mix(h + 1)),
                            double(cz + k) + unit_from_hash(mix(h + 2))};
        const Vec3d d = nucleus - p;
        const double dist = std::sqrt(dot(d, d));
        if (dist < d1) {
          d2 = d1, d1 = dist;
        } else if (dist < d2) {
          d2 = dist;
        }
      }
  return std::clamp(d2 - d1, 0.0, 1.0);
}

}  // namespace

namespace solid {

// POV-Ray's sources are drawn from its own random sequence; ours from a fixed hash, so the rings
// sit elsewhere than in POV-Ray.
const std::array<WaveSource, kWaveSources>& wave_sources() {
  static const std::array<WaveSource, kWaveSources> sources = [] {
    std::array<WaveSource, kWaveSources> s;
    for (int i = 0; i < kWaveSources; ++i) {
      const double u = unit_from_hash(hash_cell(i, 1, 7)), v = unit_from_hash(hash_cell(i, 2, 7));
      const double z = 2 * u - 1, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * kPi * v;
      s[i] = {{r * std::cos(phi), r * std::sin(phi), z}, 0.5 + unit_from_hash(hash_cell(i, 3, 7))};
    }
    return s;
  }();
  return sources;
}

double noise(Vec3d p) {
  return std::clamp(0.5 + kNoiseScale * perlin(p), 0.0, 1.0);
}

Vec3d vector_noise(Vec3d p) {
  // Three decorrelated scalar noises: POV-Ray's DNoise components have a standard deviation of
  // 0.26 (measured on a turbulent gradient), twice its Noise()'s, as 2 (noise - 0.5) has.
  return {2 * (noise(p) - 0.5), 2 * (noise(p + Vec3d{31.416, -17.2, 9.7}) - 0.5),
          2 * (noise(p + Vec3d{-7.3, 23.9, -41.1}) - 0.5)};
}

double turbulence(Vec3d p, int octaves, double omega, double lambda) {
  double value = noise(p), l = lambda, o = omega;
  for (int i = 2; i <= std::clamp(octaves, 1, 10); ++i) {
    value += o * noise(p * l);
    l *= lambda, o *= omega;
  }
  return value;
}

Vec3d vector_turbulence(Vec3d p, int octaves, double omega, double lambda) {
  Vec3d value = vector_noise(p);
  double l = lambda, o = omega;
  for (int i = 2; i <= std::clamp(octaves, 1, 10); ++i) {
    value += vector_noise(p * l) * o;
    l *= lambda, o *= omega;
  }
  return value;
}

double raw_value(const SolidPattern& s, Vec3d p) {
  using K = SolidPatternKind;
  const auto turb = [&] { return turbulence(p, s.octaves, s.omega, s.lambda); };
  switch (s.kind) {
    case K::kSolid:
      return 0;
    case K::kChecker:
      return checker(p);
    case K::kHexagon:
      return hexagon(p);
    case K::kBrick:
      return brick(p, s.brick_size, s.mortar);
    case K::kGradient: {
      const double v = dot(p, s.gradient);
      return v > 1 ? std::fmod(v, 1.0) : v;
    }
    case K::kBozo:
    case K::kSpotted:
    case K::kBumps:
      return noise(p);
    case K::kGranite: {
      double value = 0, f = 1;
      for (int i = 0; i < 6; ++i, f *= 2)
        value += std::abs(0.5 - noise(p * (4 * f))) / f;
      return value;
    }
    case K::kMarble:
      return p.x + s.turbulence.x * (s.turbulence.x != 0 ? turb() : 0);
    case K::kWood: {
      double x = p.x, y = p.y;
      if (s.turbulence.x != 0 || s.turbulence.y != 0 || s.turbulence.z != 0) {
        const Vec3d t = vector_turbulence(p, s.octaves, s.omega, s.lambda);
        x += cycloidal((p.x + t.x) * s.turbulence.x);
        y += cycloidal((p.y + t.y) * s.turbulence.y);
      }
      return std::sqrt(x * x + y * y);
    }
    case K::kAgate: {
      const double v = 0.5 * (cycloidal(1.3 * s.agate_turbulence * turb() + 1.1 * p.z) + 1);
      return std::pow(std::clamp(v, 0.0, 1.0), 0.77);
    }
    case K::kLeopard: {
      const double v = (std::sin(p.x) + std::sin(p.y) + std::sin(p.z)) / 3;
      return v * v;
    }
    case K::kOnion:
      return std::fmod(std::sqrt(dot(p, p)), 1.0);
    case K::kRadial:
      if (std::abs(p.x) < 0.001 && std::abs(p.z) < 0.001) return 0.25;
      return 0.25 + (std::atan2(p.x, p.z) + kPi) / (2 * kPi);
    case K::kSpiral1:
    case K::kSpiral2: {
      const double t = s.turbulence.x != 0 ? s.turbulence.x * turb() : 0;
      const double r = std::sqrt(p.x * p.x + p.y * p.y);
      const double v = p.z + r + s.spiral_arms * spiral_angle(p.x, p.y, r) / (2 * kPi) + t;
      return s.kind == K::kSpiral1 ? v : triangle_wave(r) + triangle_wave(v);
    }
    case K::kWaves:
    case K::kRipples: {
      double sum = 0;
      for (const WaveSource& w : wave_sources()) {
        const Vec3d d = p - w.centre;
        double len = std::sqrt(dot(d, d));
        if (len == 0) len = 1;
        sum += s.kind == K::kRipples
                   ? cycloidal(len * s.frequency + s.phase)
                   : cycloidal(len * s.frequency * w.frequency + s.phase) / w.frequency;
      }
      sum /= kWaveSources;
      return s.kind == K::kRipples ? 0.5 * (1 + sum) : 0.2 * (2.5 + sum);
    }
    case K::kWrinkles: {
      double value = noise(p), lambda = 2, omega = 0.5;
      for (int i = 1; i < 10; ++i, lambda *= 2, omega *= 0.5)
        value += omega * noise(p * lambda);
      return value / 2;
    }
    case K::kDents: {
      const double n = noise(p);
      return n * n * n;
    }
    case K::kCrackle:
      return crackle(p);
    case K::kImageMap:  // a colour, not a value (evaluate_solid)
      return 0;
    case K::kCells:
      return unit_from_hash(hash_cell(int64_t(std::floor(p.x + kLatticeNudge)),
                                      int64_t(std::floor(p.y + kLatticeNudge)),
                                      int64_t(std::floor(p.z + kLatticeNudge))));
    case K::kFunction: {
      if (!s.function) return 0;
      // POV-Ray's FunctionPattern wraps values above 1 (fmod) and keeps the others
      const double value = s.function->evaluate(p.x, p.y, p.z);
      return value > 1 ? std::fmod(value, 1.0) : value;
    }
  }
  return 0;
}

double shape_value(const SolidPattern& s, double value) {
  if (s.frequency != 0) value = std::fmod(value * s.frequency + s.phase, 1.00001);
  if (value < 0) value -= std::floor(value);
  switch (s.wave) {
    case SolidWave::kRamp:
      return value;
    case SolidWave::kSine:
      return (1 + cycloidal(value)) * 0.5;
    case SolidWave::kTriangle:
      return triangle_wave(value);
    case SolidWave::kScallop:
      return std::abs(cycloidal(value * 0.5));
    case SolidWave::kCubic:
      return value * value * (3 - 2 * value);
    case SolidWave::kPoly:
      return std::pow(value, s.wave_exponent);
  }
  return value;
}

SolidColour colour_at(const std::vector<SolidColourStop>& map, double value) {
  if (map.empty()) return {};
  if (!(value > map.front().value)) return map.front().colour;
  for (size_t i = 1; i < map.size(); ++i) {
    const SolidColourStop &a = map[i - 1], &b = map[i];
    if (value > b.value) continue;
    const float t = b.value > a.value ? float((value - a.value) / (b.value - a.value)) : 1.f;
    return {a.colour.rgb * (1 - t) + b.colour.rgb * t,
            a.colour.filter * (1 - t) + b.colour.filter * t,
            a.colour.transmit * (1 - t) + b.colour.transmit * t};
  }
  return map.back().colour;
}

Vec3d warped_point(const SolidPattern& s, Vec3d p) {
  // POV-Ray's classic turbulence warp: the point moves before the pattern is evaluated.
  if (!special_turbulence(s.kind) &&
      (s.turbulence.x != 0 || s.turbulence.y != 0 || s.turbulence.z != 0))
    p += vector_turbulence(p, s.octaves, s.omega, s.lambda) * s.turbulence;
  return p;
}

}  // namespace solid

SolidColour evaluate_solid(const SolidPattern& s, Vec3d world_point, const TextureImages* images) {
  if (s.kind == SolidPatternKind::kSolid) return s.colour;
  const Vec3d p = solid::warped_point(s, s.pattern_from_world.point(world_point));
  if (s.kind == SolidPatternKind::kImageMap)
    return images ? image_map_colour(s.image_map, p, *images, s.colour) : s.colour;
  if (solid::is_list(s.kind)) {
    const int index = std::clamp(int(solid::raw_value(s, p)), 0, solid::list_size(s.kind) - 1);
    return size_t(index) < s.list.size() ? evaluate_solid(s.list[index], world_point, images)
                                         : solid::default_list_colour(s.kind, index);
  }
  const double value = solid::shape_value(s, solid::raw_value(s, p));
  return solid::colour_at(s.colour_map.empty() ? solid::default_map(s.kind) : s.colour_map, value);
}

}  // namespace fb
