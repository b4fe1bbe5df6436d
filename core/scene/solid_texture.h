// A solid (3-D) texture: a colour as a function of the position in the texture's own space, as
// POV-Ray's pigments define it (POV-Ray 3.7 manual, "Patterns"). importers/pov makes them;
// core/texture/solid_pattern.h evaluates them at every hit (docs/pov.md, "Appearance").
#pragma once

#include <cstddef>
#include <iterator>
#include <memory>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include <filmback/vec.h>

#include "core/math/transform.h"
#include "core/scene/material_textures.h"

namespace fb {

// A colour with POV-Ray's two transparencies: `filter` lets light through tinted by the colour,
// `transmit` lets it through unchanged. Linear.
struct SolidColour {
  Rgb rgb{0.f, 0.f, 0.f};
  float filter = 0.f, transmit = 0.f;
};

struct SolidColourStop {
  float value = 0.f;  // in [0, 1], non-decreasing along the map
  SolidColour colour;
};

enum class SolidPatternKind {
  kSolid,  // `colour` everywhere
  // List patterns: the value picks an entry of `list` (checker 2, hexagon 3, brick 2).
  kChecker,
  kHexagon,
  kBrick,
  // Value patterns in [0, 1], looked up in `colour_map`.
  kGradient,
  kBozo,
  kSpotted,
  kBumps,
  kGranite,
  kMarble,
  kWood,
  kAgate,
  kLeopard,
  kOnion,
  kRadial,
  kSpiral1,
  kSpiral2,
  kWaves,
  kRipples,
  kWrinkles,
  kDents,
  kCrackle,
  kCells,
  // An image projected onto the pattern space (SolidPattern::image_map), not a value pattern.
  kImageMap,
  kFunction,  // a user function's value (SolidPatternModifiers::function); the last kind
};

// The one list of the patterns filmback evaluates, with POV-Ray's keyword for each ("solid" is
// ours: a plain colour), in the enum's order. The POV-Ray reader, its converter and the glTF
// extension (importers/gltf/gltf_povray_pattern.cpp) all read the pattern's name here.
inline constexpr std::pair<SolidPatternKind, const char*> kSolidPatternNames[] = {
    {SolidPatternKind::kSolid, "solid"},       {SolidPatternKind::kChecker, "checker"},
    {SolidPatternKind::kHexagon, "hexagon"},   {SolidPatternKind::kBrick, "brick"},
    {SolidPatternKind::kGradient, "gradient"}, {SolidPatternKind::kBozo, "bozo"},
    {SolidPatternKind::kSpotted, "spotted"},   {SolidPatternKind::kBumps, "bumps"},
    {SolidPatternKind::kGranite, "granite"},   {SolidPatternKind::kMarble, "marble"},
    {SolidPatternKind::kWood, "wood"},         {SolidPatternKind::kAgate, "agate"},
    {SolidPatternKind::kLeopard, "leopard"},   {SolidPatternKind::kOnion, "onion"},
    {SolidPatternKind::kRadial, "radial"},     {SolidPatternKind::kSpiral1, "spiral1"},
    {SolidPatternKind::kSpiral2, "spiral2"},   {SolidPatternKind::kWaves, "waves"},
    {SolidPatternKind::kRipples, "ripples"},   {SolidPatternKind::kWrinkles, "wrinkles"},
    {SolidPatternKind::kDents, "dents"},       {SolidPatternKind::kCrackle, "crackle"},
    {SolidPatternKind::kCells, "cells"},       {SolidPatternKind::kImageMap, "image_map"},
    {SolidPatternKind::kFunction, "function"}};

// Every kind once, in order, so that a kind added to the enum must be named here too.
constexpr bool solid_pattern_names_cover_the_enum() {
  for (size_t i = 0; i < std::size(kSolidPatternNames); ++i)
    if (size_t(kSolidPatternNames[i].first) != i) return false;
  return size_t(SolidPatternKind::kFunction) + 1 == std::size(kSolidPatternNames);
}
static_assert(solid_pattern_names_cover_the_enum());

// The kind POV-Ray's keyword `name` names, if filmback evaluates it.
constexpr std::optional<SolidPatternKind> solid_pattern_named(std::string_view name) {
  for (const auto& [kind, keyword] : kSolidPatternNames)
    if (name == keyword) return kind;
  return std::nullopt;
}

class UserFunction;  // core/function/user_function.h

// POV-Ray's wave types: how a value pattern's raw value becomes the colour map's index.
enum class SolidWave { kRamp, kTriangle, kSine, kScallop, kCubic, kPoly };

// A pattern's modifiers (POV-Ray 3.7 manual, "Pattern Modifiers"), as the SDL reader's pigment
// (importers/pov/pov_scene.h) holds them and as the scene model's pattern does.
struct SolidPatternModifiers {
  // Turbulence (POV-Ray's classic warp): the point moves by `turbulence` times a fractal vector
  // noise of `octaves` octaves, each `lambda` times the frequency and `omega` times the amplitude
  // of the last. Marble, wood, agate and the spirals use it inside the pattern instead.
  Vec3d turbulence{0, 0, 0};
  int octaves = 6;
  double omega = 0.5, lambda = 2.0;
  double frequency = 1, phase = 0;
  SolidWave wave = SolidWave::kRamp;
  double wave_exponent = 1;  // kPoly
  Vec3d gradient{0, 1, 0};   // kGradient's direction (unit in a SolidPattern)
  Vec3d brick_size{8, 3, 4.5};
  double mortar = 0.5;
  int spiral_arms = 1;          // spiral1 / spiral2 N
  double agate_turbulence = 1;  // agate_turb
  // kFunction: f(x, y, z) of the pattern point (none: 0 everywhere), shared by the copies
  std::shared_ptr<const UserFunction> function;
};

// How POV-Ray's image_map wraps its image around the pattern space (POV-Ray 3.7 reference,
// "Image Map"; the map_type numbers): planar projects along z onto the unit square of x and y;
// spherical and cylindrical wrap the longitude about y; the torus wraps both angles of a torus
// of major radius `major_radius` about y.
enum class SolidImageProjection { kPlanar = 0, kSpherical = 1, kCylindrical = 2, kTorus = 5 };

// pigment { image_map { "file" ... } }: core/texture/solid_image_map.h evaluates it.
struct SolidImageMap {
  uint32_t image = kNoImage;  // in Scene::images; none: the pattern's `colour` stands in
  SolidImageProjection projection = SolidImageProjection::kPlanar;
  bool once = false;  // one copy of the image; outside it, fully transmitting white
  TextureInterpolation interpolation = TextureInterpolation::kClosest;  // POV-Ray's default
  // How the file's values become linear: the sRGB curve, or v^decode_gamma.
  bool srgb = true;
  float decode_gamma = 1.f;
  float filter_all = 0.f, transmit_all = 0.f;  // added to every texel (transmit to 1 - alpha)
  double major_radius = 1;                     // kTorus
};

struct SolidPattern : SolidPatternModifiers {
  SolidPatternKind kind = SolidPatternKind::kSolid;
  SolidColour colour;                       // kSolid
  std::vector<SolidColourStop> colour_map;  // value patterns; empty: black to white
  std::vector<SolidPattern> list;           // list patterns, each with its own pattern space
  SolidImageMap image_map;                  // kImageMap
  Transform pattern_from_world;             // world: filmback's right-handed world, metres
};

// A slope_map entry (POV-Ray 3.7 manual, "Slope Maps"): at pattern value `value` the surface
// stands at `height` and rises by `slope`; between entries a cubic Hermite curve joins them.
struct SolidSlopeStop {
  float value = 0.f, height = 0.f, slope = 0.f;
};

struct SolidNormalStop;

// A POV-Ray `normal` (POV-Ray 3.7 manual, "Normal"): the shading normal bent by a pattern of
// `pattern` (its kind, modifiers and space; its colours unused), core/texture/solid_normal.h
// evaluates it. bumps, dents, ripples, waves and wrinkles have their own normal functions; any
// other kind is differentiated numerically over `accuracy`. With a `normal_map`, the pattern's
// value picks the entries instead, whose normals blend.
struct SolidNormal {
  SolidPattern pattern;
  double amount = 0.5;      // the pattern's float or bump_size
  double accuracy = 0.02;   // the numeric derivative's step, in pattern space
  bool scale_bumps = true;  // false: no_bump_scale (the pattern's scale changes the bumps' depth)
  std::vector<SolidSlopeStop> slope_map;  // empty: the pattern's value is the height
  // Entries by non-decreasing value, each evaluated in this normal's pattern space (their
  // pattern_from_world take this pattern's points).
  std::vector<SolidNormalStop> normal_map;
};

struct SolidNormalStop {
  float value = 0.f;
  SolidNormal normal;
};

}  // namespace fb
