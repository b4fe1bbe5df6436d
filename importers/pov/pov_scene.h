// A POV-Ray scene as the SDL evaluator leaves it (importers/pov/sdl/): every directive, macro and
// expression already evaluated, every #declare'd object copied in place, in POV-Ray's own
// left-handed, +Y-up coordinates and units. The converters turn it into an fb::Scene:
// pov_camera (the camera), pov_geometry (objects), pov_appearance (textures, lights, sky).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <filmback/vec.h>

#include "core/math/julia_fractal.h"
#include "core/math/sphere_sweep.h"
#include "core/math/transform.h"
#include "core/scene/isosurface.h"
#include "core/scene/outline.h"
#include "core/scene/solid_texture.h"

namespace fb::pov {

// Where a statement starts: "file:line:column" in messages, with the include chain that led there.
struct SourceLocation {
  std::string file;  // as the user would find it: relative to the scene, or the library file
  uint32_t line = 0, column = 0;
  std::string text() const;  // "scene.pov:12:5"
};

// POV-Ray's row-vector matrices (p' = p M) held in column-vector form (p' = T p), so that
// "A written before B" composes as B * A. Always in POV-Ray's coordinates.
using Matrix = Transform;

// A colour with POV-Ray's filter (coloured, refracting transparency) and transmit (plain
// transparency) channels, as written (decoded by assumed_gamma in the converter, not here).
struct Colour {
  double r = 0, g = 0, b = 0, filter = 0, transmit = 0;
};

// ---- Appearance -------------------------------------------------------------------------------

// The patterns filmback evaluates are the scene model's (core/scene/solid_texture.h, whose table
// names them); a pigment of any other pattern is `averaged`.
using Pattern = SolidPatternKind;
using Wave = SolidWave;

struct ColourMapEntry {
  double value = 0;  // in [0, 1]
  Colour colour;
};

// The modifiers as written: the converter normalises the gradient and picks each pattern's
// default wave (pov_appearance).
struct Pigment : SolidPatternModifiers {
  Pattern pattern = Pattern::kSolid;
  // A pattern the evaluator knows only by name: not evaluated, the converter uses `colour`, the
  // parser's estimate of its average (see pov_appearance)
  bool averaged = false;
  SolidImageMap image_map;  // kImageMap: its image indexes Scene::images
  std::string name;         // the pattern's keyword, for messages
  Colour colour;            // kSolid; otherwise the pattern's average, as the parser estimates it
  std::vector<ColourMapEntry> colour_map;  // value patterns; empty: POV-Ray's default grey ramp
  std::vector<Pigment> list;               // list patterns (checker A, B ...)
  // Pattern space from POV world space: the pigment's own transforms and every transform applied
  // to the object after the pigment was attached, composed by the evaluator.
  Matrix pattern_from_world;
  SourceLocation where;
};

struct Finish {
  Colour ambient{0.1, 0.1, 0.1};  // POV-Ray 3.7 defaults (the #default finish can change them)
  Colour emission{0, 0, 0};
  double diffuse = 0.6, brilliance = 1;
  double specular = 0, roughness = 0.05;
  double phong = 0, phong_size = 40;
  Colour reflection_min{0, 0, 0}, reflection_max{0, 0, 0};
  bool reflection_fresnel = false;
  double reflection_metallic = 0;
  double reflection_falloff = 1, reflection_exponent = 1;
  double metallic = 0;
  bool conserve_energy = false;
};

// media { ... } inside an interior (POV-Ray 3.7 reference, "Media"), homogeneous: coefficients
// per POV-Ray unit of length, each already times the product of the constant densities. A
// density with a pattern is taken as 1 (reported); method, intervals and samples are read and
// left to the integrator (docs/pov.md, "Media").
struct Media {
  Colour absorption{0, 0, 0}, emission{0, 0, 0}, scattering{0, 0, 0};
  double extinction = 1;  // scattering's share in the attenuation (POV-Ray's `extinction`)
  int samples = 10, intervals = 1;  // POV-Ray 3.7's defaults (its least samples, with method 3)
  SourceLocation where;
};

struct Interior {
  double ior = 1;
  double fade_distance = 0, fade_power = 0;
  Colour fade_colour{0, 0, 0};
  std::vector<Media> media;  // summed: POV-Ray adds the coefficients of an interior's media
};

struct SlopeMapEntry {
  double value = 0, height = 0, slope = 0;  // [value, <height, slope>]
};

struct NormalMapEntry;

// normal { pattern [amount] modifiers }: the pattern as a pigment's, with the normal's own
// keywords; `pattern_from_world` composed as a pigment's is.
struct Normal : SolidPatternModifiers {
  Pattern pattern = Pattern::kSolid;
  std::string name;       // the pattern's keyword; empty: none given yet (a #default's bump_size)
  bool rendered = false;  // a pattern filmback evaluates, without a normal_map or normal list
  double amount = 0.5;    // the float after the pattern, or bump_size
  double accuracy = 0.02;
  bool scale_bumps = true;  // no_bump_scale clears it
  std::vector<SlopeMapEntry> slope_map;
  // normal_map { [value normal-body] ... }: the entries' pattern_from_world take points of this
  // normal's pattern space (transforms after the map move this normal, not its entries).
  std::vector<NormalMapEntry> normal_map;
  Matrix pattern_from_world;
  SourceLocation where;
};

struct NormalMapEntry {
  double value = 0;
  Normal normal;
};

struct Texture {
  Pigment pigment;
  Finish finish;
  std::optional<Normal> normal;
  // Layered textures (`texture {A} texture {B}`): the textures over this one, each over the one
  // before; none of them has layers of its own.
  std::vector<Texture> layers;
  SourceLocation where;

  // The layer a later pigment, finish or normal changes: the topmost, as POV-Ray's
  // Parse_Texture and Parse_Object_Mods change the head of its layer list, which is the last
  // layer written.
  Texture& top() { return layers.empty() ? *this : layers.back(); }
};

// ---- Objects ----------------------------------------------------------------------------------

enum class Shape {
  // analytic, parameters in object space
  kSphere,    // centre a, radius r0
  kBox,       // corners a, b
  kPlane,     // normal a, distance r0: dot(p, a / |a|) = r0 (Parse_Plane); inside is dot < r0
  kCylinder,  // base a, cap b, radius r0; open: no end caps
  kCone,      // base a radius r0, cap b radius r1; open
  kTorus,     // major r0, minor r1, in the XZ plane about the origin
  kDisc,      // centre a, normal b, radius r0, hole radius r1
  // quadric, cubic, quartic, poly: `coefficients` of x^i y^j z^k in POV-Ray's poly order (i from
  // the degree down, then j, then k), degree `order`; inside where the polynomial is < 0
  kPolynomial,
  // prism: `outline` (absent when POV-Ray leaves it out) in POV's xz plane swept in y from r0 to
  // r1, straight up or, `conic`, scaled by y from the origin
  kPrism,
  kSuperellipsoid,  // exponents e = r0, n = r1 (> 0), within the unit box
  kBlob,            // threshold r0 (> 0), `blob_components`
  kSor,             // `profile` points (radius, height), height increasing; open
  kLathe,           // `outline`: its curve in the (radius, height) plane, about the y axis
  kOvus,            // bottom radius r0, top radius r1 (>= 0)
  kLemon,           // apex a radius r0, base b radius r1, inner radius r2 (bounded as POV-Ray's)
  kSphereSweep,     // `sweep`, its segments as the parser built them
  kIsosurface,      // `isosurface`: its function, threshold and container; open
  kJuliaFractal,    // `julia`: its parameter, algebra, function and slice
  // triangles (triangle, smooth_triangle, mesh, mesh2, polygon): `vertices`, `indices`
  kMesh,
  // constructive solid geometry over `children`
  kUnion,
  kMerge,
  kIntersection,
  kDifference,
};

// A blob's component as written: sphere { a, radius, strength } or cylinder { a, b, radius,
// strength }, placed in the blob's space by its own transforms.
struct BlobComponentStatement {
  bool cylinder = false;
  Vec3d a{0, 0, 0}, b{0, 0, 0};
  double radius = 0, strength = 0;
  Matrix blob_from_component;
};

struct Object {
  Shape shape = Shape::kSphere;
  std::string keyword;  // as written ("smooth_triangle", "mesh2", ...), for messages
  SourceLocation where;
  Vec3d a{0, 0, 0}, b{0, 0, 0};
  double r0 = 0, r1 = 0;
  double r2 = 0;  // kLemon
  bool open = false;
  int order = 0;                                        // kPolynomial
  std::vector<double> coefficients;                     // kPolynomial
  std::shared_ptr<const Outline> outline;               // kPrism, kLathe
  std::shared_ptr<const SphereSweep> sweep;             // kSphereSweep
  bool conic = false;                                   // kPrism: conic_sweep
  std::vector<BlobComponentStatement> blob_components;  // kBlob
  std::vector<std::pair<double, double>> profile;       // kSor
  std::shared_ptr<const Isosurface> isosurface;         // kIsosurface
  std::shared_ptr<const JuliaFractal> julia;            // kJuliaFractal
  // kMesh: triangles; `normals` empty or one per vertex; `triangle_textures` empty or one index
  // into `textures` per triangle (mesh2 texture_list), otherwise `texture` applies.
  std::vector<Vec3d> vertices, normals;
  std::vector<uint32_t> indices;
  std::vector<uint32_t> triangle_textures;
  std::vector<Texture> textures;
  std::vector<Object> children;  // CSG; the first is the base of a difference
  std::vector<Object> clipped_by;
  // POV world from object, with every enclosing CSG's transforms folded in: a CSG node's own
  // transforms are pushed into its children, so leaves carry the whole placement.
  Matrix world_from_object;
  bool inverse = false;
  bool hollow = false, no_shadow = false, no_image = false, no_reflection = false;
  bool double_illuminate = false;
  // Every leaf ends up with a texture: its own, else the enclosing CSG's, else the #default one.
  Texture texture;
  bool texture_given = false;  // the evaluator's bookkeeping: written here, not yet inherited
  std::optional<Interior> interior;
};

// ---- Lights, camera, environment ---------------------------------------------------------------

enum class LightKind { kPoint, kSpot, kCylinder, kParallel };

struct LightSource {
  LightKind kind = LightKind::kPoint;
  SourceLocation where;
  Vec3d location{0, 0, 0};  // POV world space, transforms applied
  Colour colour{1, 1, 1};
  Vec3d point_at{0, 0, 1};
  double radius_deg = 30, falloff_deg = 45, tightness = 0;  // kSpot, kCylinder
  // area_light: a grid of size1 x size2 point lights spread over axis1 and axis2
  bool area = false;
  Vec3d axis1{0, 0, 0}, axis2{0, 0, 0};
  int size1 = 0, size2 = 0;
  bool circular = false, orient = false;
  double fade_distance = 0, fade_power = 0;  // 0: no fading (POV-Ray's default)
  bool shadowless = false;
  bool has_looks_like = false;
};

enum class CameraType {
  kPerspective,
  kOrthographic,
  kFisheye,
  kUltraWideAngle,
  kOmnimax,
  kPanoramic,
  kCylinder,
  kSpherical,
  kMeshCamera
};

// A camera statement as written; pov_camera applies POV-Ray's fixed evaluation order
// (docs/pov.md "Camera"). Keywords not given keep POV-Ray's defaults here.
struct CameraStatement {
  CameraType type = CameraType::kPerspective;
  int cylinder_type = 0;
  SourceLocation where;
  Vec3d location{0, 0, 0}, direction{0, 0, 1}, right{1.33, 0, 0}, up{0, 1, 0}, sky{0, 1, 0};
  bool right_given = false, up_given = false;
  std::optional<Vec3d> look_at;
  std::optional<double> angle_deg;    // horizontal field of view
  std::optional<double> angle_v_deg;  // the second angle of `spherical`
  SourceLocation angle_where;         // of the `angle` keyword, when given
  std::optional<Vec3d> focal_point;
  double aperture = 0;
  int blur_samples = 0;
  Matrix transform;  // camera transforms in the order written
  bool has_normal = false;
};

// sky_sphere: pigments layered outside-in, evaluated on the unit direction.
struct SkySphere {
  std::vector<Pigment> pigments;
  Matrix transform;
};

// fog { ... } (POV-Ray 3.7 reference, "Fog"): constant, or ground fog thinning above fog_offset.
struct Fog {
  bool ground = false;  // fog_type 2
  double distance = 0;  // 0: no fog (POV-Ray ignores it)
  Colour colour;        // with the fog's filter and transmit
  Vec3d up{0, 1, 0};    // POV-Ray space, after the fog's transforms
  double offset = 0, altitude = 0;
  SourceLocation where;
};

struct Unsupported {
  std::string feature;  // "media", "photons", "isosurface", ...
  SourceLocation where;
  // An unsupported object is reported when it is placed in the scene: the top-level statement
  // that placed it, when that is not where it was written (`object { Declared }`, a CSG).
  std::optional<SourceLocation> placed;
};

// What evaluating the scene used, to compare with pov::EvaluateLimits (docs/pov.md "The
// language": the sample scenes' largest counts set the limits' defaults).
struct EvaluationCounts {
  uint64_t tokens = 0, loop_iterations = 0, array_elements = 0, objects = 0;
  uint32_t include_depth = 0, macro_depth = 0, nesting = 0;  // deepest reached
};

struct Scene {
  std::optional<CameraStatement> camera;  // the last one executed; none: POV-Ray's default
  std::vector<Object> objects;
  std::vector<LightSource> lights;
  std::optional<Colour> background;
  std::optional<SkySphere> sky_sphere;
  std::vector<Fog> fogs;
  std::optional<double> assumed_gamma;
  Colour ambient_light{1, 1, 1};
  std::vector<std::filesystem::path> images;           // image_map files, found; each once
  std::optional<double> max_trace_level, adc_bailout;  // global_settings, as written
  double version = 3.7;
  // Features met but not rendered, in the order met; the converters report each once per scene.
  std::vector<Unsupported> unsupported;
  std::vector<std::string> warnings;  // #warning and the evaluator's own, with file:line:column
  EvaluationCounts counts;
};

}  // namespace fb::pov
