// POV-Ray's own renders against filmback's camera conversion (docs/pov.md "Camera"), label `pov`.
// Each shot is a camera statement and nine small spheres, flat white (`finish { ambient 1
// diffuse 0 }`) on black, placed on a 3 x 3 grid of the image at three depths. The test writes the
// .pov (camera keywords deliberately out of POV-Ray's evaluation order) and renders it with
// Debian's `povray` at 160 x 120 or so, anti-aliased with every pixel's centre and an 8 x 8 grid
// (+A0.0 +AM1 +R8 -J), or with focal blur, POV-Ray's own jittered pixel and lens samples. The SDL
// evaluator reads the camera back from the .pov (its vectors must be the shot's), and
//  (a) the same spheres are seen through its conversion: the camera plugin filmback would use
//      (perspective, orthographic, thinlens) set up by make_camera_setup, its rays placed by
//      world_from_camera, intersected with the spheres analytically, with POV-Ray's samples (with
//      focal blur, 1024 random points of the pixel and the lens, as POV-Ray jitters both);
//  (b) filmback renders the .pov: the importer's parts (evaluator, pov_camera, pov_geometry,
//      pov_appearance) and RenderJob, 256 spp (1024 with focal blur), 1 px box filter.
// For each sphere the image centroids agree with POV-Ray's within 0.1 px and the pixel areas
// within 2 %; with focal blur (POV-Ray's 1/32 px sampling shift taken off, kPovFocalBlurShiftPx)
// the blur diameters too, within 3 %. A camera whose right and up are
// not perpendicular, which POV-Ray renders skewed and filmback cannot, is warned about, and no
// centroid is further off than the warning says. Skips, naming the package, when `povray` is not
// on PATH. Work files go to work/<shot>/ in this build folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "core/image/image_io.h"
#include "core/render/render_job.h"
#include "importers/pov/pov_importer.h"
#include "importers/pov/pov_space.h"
#include "importers/pov/sdl/evaluate.h"
#include "support/blobs.h"
#include "support/commands.h"
#include "support/plugins.h"
#include "support/pov_rays.h"
#include "tests/pov/marker_tolerances.h"

namespace fb::test {
namespace {

namespace fs = std::filesystem;

constexpr double kMaxBlurDiameterError = 0.03;
// A blob is a sphere's when their centroids are this close; spheres are > 25 px apart.
constexpr double kMatchRadiusPx = 2.0;
constexpr double kSphereRadiusPx = 5.0;  // in the image, about
constexpr uint32_t kFilmbackSpp = 256, kFilmbackBlurSpp = 1024;
// The projection types' shots, many and in CI: their centroids' noise floor stays below 0.02 px.
constexpr uint32_t kFilmbackProjectionSpp = 128;

struct Op {
  // kShear: shear.pov's `matrix <1,0,0, 0,1,-s, 0,0,1, 0,0,0>`, z -= s y, with s = v.x
  enum Kind { kRotate, kTranslate, kScale, kShear } kind;
  Vec3d v;
};

// A marker of a projection type's shot: a sphere seen at POV-Ray's image point (x0, y0)
// (x0 = x / W - 1/2 right, y0 = 1/2 - y / H up), making `images` blobs (2 where a seam cuts it or
// a wide angle shows it twice).
struct Marker {
  double x0, y0;
  int images = 1;
};

// Markers at every (x0, y0) of xs x ys, then `extra` ones.
std::vector<Marker> grid(std::initializer_list<double> xs, std::initializer_list<double> ys,
                         std::initializer_list<Marker> extra = {}) {
  std::vector<Marker> out;
  for (const double y0 : ys)
    for (const double x0 : xs)
      out.push_back({x0, y0});
  out.insert(out.end(), extra.begin(), extra.end());
  return out;
}

// One camera statement, given once: written as SDL for POV-Ray and built as the CameraStatement
// the SDL evaluator would produce from it.
struct Shot {
  const char* name;
  uint32_t width = 160, height = 120;
  bool has_camera = true;  // false: no camera statement, POV-Ray's default camera
  pov::CameraType type = pov::CameraType::kPerspective;
  int cylinder = 0;  // `cylinder 1` to `cylinder 4`
  std::optional<Vec3d> location{}, look_at{}, direction{}, right{}, up{}, sky{}, focal_point{};
  std::optional<double> angle{}, angle_v{};  // angle_v: spherical's `angle H, V`
  double aperture = 0;
  int blur_samples = 0;
  std::vector<Op> transforms{};     // in the order written
  bool skewed = false;              // right not perpendicular to up: a warning and a stated error
  const char* right_sdl = nullptr;  // how the .pov writes right, if not as the number
  // Projection types: where the markers are; those POV-Ray does not trace all round are dropped.
  std::vector<Marker> markers{};
};

using pov::CameraType;

const Shot kShots[] = {
    {.name = "default_camera", .has_camera = false},
    {.name = "angle_30", .location = Vec3d{0, 1, -10}, .look_at = Vec3d{0, 0.5, 0}, .angle = 30},
    {.name = "angle_60", .location = Vec3d{2, 3, -9}, .look_at = Vec3d{0, 0, 0}, .angle = 60},
    {.name = "angle_100", .location = Vec3d{0, 0, -5}, .look_at = Vec3d{0, 0, 0}, .angle = 100},
    {.name = "right_up_16_9",
     .width = 192,
     .height = 108,
     .location = Vec3d{1, 2, -8},
     .look_at = Vec3d{0, 0, 0},
     .right = Vec3d{16.0 / 9, 0, 0},
     .up = Vec3d{0, 1, 0},
     .angle = 70},
    {.name = "portrait",
     .width = 90,
     .height = 160,
     .location = Vec3d{0, 2, -9},
     .look_at = Vec3d{0, 1, 0},
     .right = Vec3d{90.0 / 160, 0, 0},
     .angle = 50,
     .right_sdl = "x*image_width/image_height"},  // the 3.7 templates' idiom
    {.name = "mismatched_aspect",                 // a square view on a 4:3 image: non-square pixels
     .location = Vec3d{0, 0, -8},
     .look_at = Vec3d{0, 0, 0},
     .right = Vec3d{1, 0, 0},
     .up = Vec3d{0, 1, 0},
     .angle = 60},
    {.name = "tilted_sky",
     .location = Vec3d{-2, 1, -8},
     .look_at = Vec3d{0, 0, 0},
     .sky = Vec3d{0.4, 1, 0.1},
     .angle = 55},
    {.name = "direction_without_angle", .location = Vec3d{0, 0, -6}, .direction = Vec3d{0, 0, 2.5}},
    {.name = "direction_oblique",  // not perpendicular to right and up: a lens shift
     .location = Vec3d{0, 0, -6},
     .direction = Vec3d{0.3, -0.2, 1.5}},
    {.name = "transforms",
     .location = Vec3d{0, 0, -8},
     .look_at = Vec3d{0, 0, 0},
     .angle = 50,
     .transforms = {{Op::kScale, {1.2, 1, 1}},  // wider: right grows, up and direction do not
                    {Op::kRotate, {10, 30, 0}},
                    {Op::kTranslate, {1, -0.5, 2}}}},
    {.name = "shear_sample",  // camera/shear.pov: a sheared camera keeps verticals vertical
     .location = Vec3d{0, 1, 25},
     .look_at = Vec3d{0, 10, 0},
     .right = Vec3d{4.0 / 3, 0, 0},
     .angle = 90,
     .transforms = {{Op::kShear, {9.0 / 25, 0, 0}}, {Op::kRotate, {0, 45, 0}}}},
    {.name = "skewed_up",  // POV-Ray renders the skew; filmback warns
     .location = Vec3d{0, 0, -6},
     .up = Vec3d{0.05, 1, 0},
     .skewed = true},
    {.name = "mirrored_right", .location = Vec3d{0, 0, -6}, .right = Vec3d{-1.33, 0, 0}},
    {.name = "benchmark_handedness",  // advanced/benchmark/benchmark.pov: not mirrored
     .location = Vec3d{1, -7, 2},
     .look_at = Vec3d{0, 0, 0.5},
     .direction = Vec3d{0, 1, 0},
     .right = Vec3d{-4.0 / 3, 0, 0},
     .up = Vec3d{0, 0, 1},
     .sky = Vec3d{0, 0, 1}},
    {.name = "orthographic_auto",
     .type = CameraType::kOrthographic,
     .location = Vec3d{1, 2, -10},
     .look_at = Vec3d{0, 0, 0}},
    {.name = "orthographic_right_up",
     .type = CameraType::kOrthographic,
     .location = Vec3d{0, 3, -10},
     .look_at = Vec3d{0, 0, 0},
     .right = Vec3d{8, 0, 0},
     .up = Vec3d{0, 6, 0}},
    {.name = "orthographic_angle",
     .type = CameraType::kOrthographic,
     .location = Vec3d{0, 0, -10},
     .look_at = Vec3d{0, 0, 0},
     .angle = 40},
    {.name = "focal_blur",
     .location = Vec3d{0, 0, -10},
     .look_at = Vec3d{0, 0, 0},
     .focal_point = Vec3d{2, 0, -3.3},
     .angle = 45,
     .aperture = 2,
     .blur_samples = 1024},
    {.name = "focal_blur_default_focus",  // no focal_point: Direction_Length 1, not |direction| 3
     .location = Vec3d{0, 0, -6},
     .direction = Vec3d{0, 0, 3},
     .aperture = 0.07,
     .blur_samples = 1024},
    // POV-Ray's other projections (plugins/cameras/pov_*): markers all over the frame, at the
    // rim of a fisheye, the poles and the seam of a spherical camera.
    {.name = "fisheye_180",
     .type = CameraType::kFisheye,
     .location = Vec3d{0, 1, -2},
     .look_at = Vec3d{0, 0.5, 3},
     .angle = 180,
     .markers = grid({-0.3, -0.15, 0, 0.15, 0.3}, {-0.3, -0.1, 0.1, 0.3},
                     {{0.33, 0.12}, {-0.12, -0.42}, {-0.34, 0.1}, {0.05, 0.44}})},
    {.name = "fisheye_360_square",  // the rim looks straight back
     .width = 120,
     .height = 120,
     .type = CameraType::kFisheye,
     .location = Vec3d{0, 0, 0},
     .look_at = Vec3d{1, 0, 3},
     .right = Vec3d{1, 0, 0},
     .angle = 360,
     .markers = grid({-0.3, -0.1, 0.1, 0.3}, {-0.3, -0.1, 0.1, 0.3},
                     {{0.43, 0.1}, {-0.1, 0.43}, {-0.43, -0.05}})},
    {.name = "ultra_wide_angle_200",
     .type = CameraType::kUltraWideAngle,
     .location = Vec3d{0, 0, -1},
     .look_at = Vec3d{0, 0, 0},
     .angle = 200,
     .markers = grid({-0.42, -0.21, 0, 0.21, 0.42}, {-0.36, -0.12, 0.12, 0.36})},
    {.name = "omnimax",
     .type = CameraType::kOmnimax,
     .location = Vec3d{0, 0, 0},
     .look_at = Vec3d{0, 1, 4},
     .markers = grid({-0.36, -0.18, 0, 0.18, 0.36}, {-0.3, -0.1, 0.1, 0.3, 0.45})},
    {.name = "panoramic",
     .type = CameraType::kPanoramic,
     .location = Vec3d{0, 0, 0},
     .look_at = Vec3d{0, 0, 1},
     .markers = grid({-0.45, -0.3, -0.15, 0, 0.15, 0.3, 0.45}, {-0.2, 0, 0.2},
                     {{-0.3, 0.4}, {0.05, 0.4}, {0.35, 0.4}, {-0.4, -0.42}, {0.3, -0.42}})},
    {.name = "cylinder_1",
     .type = CameraType::kCylinder,
     .cylinder = 1,
     .location = Vec3d{0, 1, 0},
     .look_at = Vec3d{1, 1, 2},
     .angle = 270,
     .markers = grid({-0.42, -0.21, 0, 0.21, 0.42}, {-0.35, 0, 0.35})},
    {.name = "cylinder_2",
     .width = 120,
     .height = 160,
     .type = CameraType::kCylinder,
     .cylinder = 2,
     .location = Vec3d{0, 0, -1},
     .right = Vec3d{0.75, 0, 0},
     .angle = 150,
     .markers = grid({-0.3, 0, 0.3}, {-0.42, -0.21, 0, 0.21, 0.42})},
    {.name = "cylinder_3",
     .type = CameraType::kCylinder,
     .cylinder = 3,
     .location = Vec3d{0, 0, 0},
     .up = Vec3d{0, 3, 0},
     .angle = 180,
     .markers = grid({-0.4, -0.2, 0, 0.2, 0.4}, {-0.35, 0, 0.35})},
    {.name = "cylinder_4",
     .type = CameraType::kCylinder,
     .cylinder = 4,
     .location = Vec3d{0.5, 0, 0},
     .right = Vec3d{4, 0, 0},
     .angle = 100,
     .markers = grid({-0.4, -0.2, 0, 0.2, 0.4}, {-0.35, 0, 0.35})},
    {.name = "spherical_poles_seam",  // 360 x 180: markers at latitude +-77 and astride the seam
     .width = 160,
     .height = 80,
     .type = CameraType::kSpherical,
     .location = Vec3d{0, 0, 0},
     .markers = grid({-0.375, -0.125, 0.125, 0.375}, {-0.25, 0, 0.25},
                     {{0.1, 0.43}, {-0.2, -0.43}, {0.5, 0.1, 2}})},
    {.name = "spherical_posed",  // angle H, V; look_at with a tilted sky, then a rotation
     .type = CameraType::kSpherical,
     .location = Vec3d{1, 2, -3},
     .look_at = Vec3d{0, 1, 0},
     .sky = Vec3d{0.3, 1, 0},
     .angle = 120,
     .angle_v = 80,
     .transforms = {{Op::kRotate, {0, 20, 10}}},
     .markers = grid({-0.4, -0.2, 0, 0.2, 0.4}, {-0.35, 0, 0.35})},
    {.name = "spherical_400",  // more than a turn: what is behind shows at both sides
     .type = CameraType::kSpherical,
     .location = Vec3d{0, 0, 0},
     .angle = 400,
     .angle_v = 180,
     .markers = grid({-0.3, -0.1, 0.1, 0.3}, {-0.3, 0, 0.3}, {{0.45, 0.15, 2}})},
    {.name = "spherical_mirrored",  // right -x without look_at: turns the other way round
     .type = CameraType::kSpherical,
     .location = Vec3d{0, 0, 0},
     .right = Vec3d{-1.33, 0, 0},
     .angle = 240,
     .markers = grid({-0.4, -0.2, 0.2, 0.4}, {-0.3, 0, 0.3}, {{0.1, 0.42}, {-0.3, -0.44}})},
};

// gtest names the case by this rather than by the struct's bytes.
void PrintTo(const Shot& shot, std::ostream* out) {
  *out << shot.name;
}

std::string vec(Vec3d v) {
  char text[96];
  std::snprintf(text, sizeof text, "<%.17g, %.17g, %.17g>", v.x, v.y, v.z);
  return text;
}

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

Transform transform_of(const Op& op) {
  switch (op.kind) {
    case Op::kRotate:
      return pov_rotate(op.v);
    case Op::kTranslate:
      return Transform::translate(op.v);
    case Op::kScale:
      return Transform::scale(op.v);
    case Op::kShear:
      return Transform::from_rows({1, 0, 0, 0, 0, 1, 0, 0, 0, -op.v.x, 1, 0, 0, 0, 0, 1});
  }
  return {};
}

std::string sdl_of(const Op& op) {
  switch (op.kind) {
    case Op::kRotate:
      return "rotate " + vec(op.v);
    case Op::kTranslate:
      return "translate " + vec(op.v);
    case Op::kScale:
      return "scale " + vec(op.v);
    case Op::kShear:
      return "matrix <1, 0, 0, 0, 1, " + number(-op.v.x) + ", 0, 0, 1, 0, 0, 0>";
  }
  return {};
}

pov::CameraStatement statement(const Shot& shot) {
  pov::CameraStatement s;
  s.type = shot.type;
  s.cylinder_type = shot.cylinder;
  s.angle_v_deg = shot.angle_v;
  s.location = shot.location.value_or(s.location);
  s.direction = shot.direction.value_or(s.direction);
  s.right = shot.right.value_or(s.right);
  s.up = shot.up.value_or(s.up);
  s.sky = shot.sky.value_or(s.sky);
  s.right_given = shot.right.has_value();
  s.up_given = shot.up.has_value();
  s.look_at = shot.look_at;
  s.angle_deg = shot.angle;
  s.focal_point = shot.focal_point;
  s.aperture = shot.aperture;
  s.blur_samples = shot.blur_samples;
  for (const Op& op : shot.transforms) {
    s.transform = transform_of(op) * s.transform;  // written later, applied later
  }
  return s;
}

std::string type_sdl(const Shot& shot) {
  const std::string keyword = pov::keyword_of(shot.type);
  return shot.type == CameraType::kCylinder ? keyword + " " + std::to_string(shot.cylinder)
                                            : keyword;
}

// The camera block with its keywords in an order unlike POV-Ray's evaluation order (transforms
// first, look_at before location, angle after look_at): the fixed order must not care.
std::string camera_sdl(const Shot& shot) {
  std::string out = "camera {\n  " + type_sdl(shot) + "\n";
  for (const Op& op : shot.transforms)
    out += "  " + sdl_of(op) + "\n";
  if (shot.focal_point) out += "  focal_point " + vec(*shot.focal_point) + "\n";
  if (shot.aperture != 0) out += "  aperture " + number(shot.aperture) + "\n";
  if (shot.blur_samples > 0)  // at least as many as at most: no adaptive early stop
    out += "  blur_samples " + std::to_string(shot.blur_samples) + ", " +
           std::to_string(shot.blur_samples) + "\n";
  if (shot.look_at) out += "  look_at " + vec(*shot.look_at) + "\n";
  if (shot.angle)
    out += "  angle " + number(*shot.angle) + (shot.angle_v ? ", " + number(*shot.angle_v) : "") +
           "\n";
  if (shot.location) out += "  location " + vec(*shot.location) + "\n";
  if (shot.sky) out += "  sky " + vec(*shot.sky) + "\n";
  if (shot.up) out += "  up " + vec(*shot.up) + "\n";
  if (shot.right) out += "  right " + (shot.right_sdl ? shot.right_sdl : vec(*shot.right)) + "\n";
  if (shot.direction) out += "  direction " + vec(*shot.direction) + "\n";
  return out + "}\n";
}

struct Sphere {
  Vec3d centre;  // POV-Ray's space
  double radius;
  int images = 1;  // blobs it makes
};

bool is_projection_type(CameraType type) {
  return type != CameraType::kPerspective && type != CameraType::kOrthographic;
}

constexpr double kMarkerRadiusPx = 4.0;  // projection types' markers, about

// A projection type's markers: a sphere at distance 4 to 7 along POV-Ray's ray through each
// marker's image point, sized kMarkerRadiusPx by the larger footprint of a pixel there (the
// spacing of the rays half a pixel either side, across and up). A marker whose surroundings POV-Ray
// does not all trace (near a fisheye's rim, omnimax's edge) is dropped.
std::vector<Sphere> markers_for(const Shot& shot, const pov::PovCameraVectors& c) {
  const uint32_t w = shot.width, h = shot.height;
  std::vector<Sphere> out;
  int k = 0;
  for (const Marker& m : shot.markers) {
    const double x = (m.x0 + 0.5) * w, y = (0.5 - m.y0) * h;
    const double distance = 4 + (k++ % 4);
    const auto at = [&](double dx, double dy) {
      const WorldRay r = pov_ray(c, x + dx, y + dy, w, h);
      return r.weight > 0 ? std::optional(r.origin + r.direction * distance) : std::nullopt;
    };
    const auto centre = at(0, 0), left = at(-0.5, 0), right = at(0.5, 0), up = at(0, -0.5),
               down = at(0, 0.5);
    if (!centre || !left || !right || !up || !down) continue;
    const double radius = kMarkerRadiusPx * std::max(length(*right - *left), length(*down - *up));
    const double reach = radius / std::min(length(*right - *left), length(*down - *up)) + 3;
    bool traced = true;
    for (const auto& [dx, dy] : {std::pair{-1, -1}, {-1, 1}, {1, -1}, {1, 1}, {0, 1}, {1, 0}})
      traced = traced && at(dx * reach, dy * reach).has_value();
    // world_from_pov, a mirror, is its own inverse
    if (traced) out.push_back({pov::world_from_pov(*centre), radius, m.images});
  }
  return out;
}

// Nine spheres on a 3 x 3 grid of the image, at depths 5, 7 and 10 along the view, each about
// kSphereRadiusPx in radius; placed by POV-Ray's own ray model from the evaluated vectors.
std::vector<Sphere> spheres_for(const Shot& shot, const pov::PovCameraVectors& c) {
  if (is_projection_type(c.type)) return markers_for(shot, c);
  const uint32_t width = shot.width, height = shot.height;
  const double depths[] = {5, 7, 10};
  const double px = std::min(length(c.right) / width, length(c.up) / height);
  std::vector<Sphere> out;
  int k = 0;
  for (const double y0 : {-0.3, 0.0, 0.3})
    for (const double x0 : {-0.3, 0.0, 0.3}) {
      const double depth = depths[k++ % 3];
      const Vec3d across = c.right * x0 + c.up * y0;
      if (c.type == CameraType::kOrthographic) {
        out.push_back({c.location + across + normalize(c.direction) * depth, kSphereRadiusPx * px});
      } else {
        const double t = depth / length(c.direction);
        out.push_back({c.location + (c.direction + across) * t, kSphereRadiusPx * px * t});
      }
    }
  return out;
}

std::string scene_sdl(const Shot& shot, const std::vector<Sphere>& spheres) {
  std::string out =
      "// Written by tests/pov/pov_camera_alignment_test.cpp: shot " + std::string(shot.name) +
      "\n#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\nbackground { rgb 0 }\n";
  if (shot.has_camera) out += camera_sdl(shot);
  for (const Sphere& s : spheres)
    out += "sphere { " + vec(s.centre) + ", " + number(s.radius) +
           " pigment { rgb 1 } finish { ambient 1 diffuse 0 } }\n";
  return out;
}

// Whether the ray (a traced one) meets any sphere (world space) in front of its origin.
bool hits_any(const WorldRay& ray, const std::vector<Sphere>& spheres) {
  if (ray.weight <= 0) return false;
  for (const Sphere& s : spheres) {
    const Vec3d oc = pov::world_from_pov(s.centre) - ray.origin;
    const double along = dot(oc, ray.direction);
    const double miss2 = dot(oc, oc) - along * along;
    if (miss2 < s.radius * s.radius && along + std::sqrt(s.radius * s.radius - miss2) > 0)
      return true;
  }
  return false;
}

Image blank(uint32_t width, uint32_t height) {
  Image image;
  image.width = width;
  image.height = height;
  image.channels = {"R", "G", "B"};
  image.pixels.assign(size_t(width) * height * 3, 0.f);
  return image;
}

void set(Image& image, uint32_t x, uint32_t y, float value) {
  for (size_t c = 0; c < 3; ++c)
    image.pixels[(size_t(y) * image.width + x) * 3 + c] = value;
}

// The spheres through filmback's thin lens: the pixel's coverage over random points of the pixel
// and the lens (POV-Ray's focal blur jitters both).
Image lens_render(const pov::PovCamera& camera, const std::vector<Sphere>& spheres, uint32_t width,
                  uint32_t height, int samples) {
  const auto plugin = make_camera_plugin(camera, width, height);
  Image image = blank(width, height);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      int hit = 0;
      for (int i = 0; i < samples; ++i) {
        const fb_camera_sample sample{float(x) + u(random), float(y) + u(random), u(random),
                                      u(random), 0.f};
        hit += hits_any(filmback_ray(*plugin, camera.camera, sample), spheres);
      }
      set(image, x, y, float(hit) / float(samples));
    }
  return image;
}

// POV-Ray's anti-aliasing with +A0.0 +AM1 +R<n> -J: every pixel differs from its neighbours by
// at least the threshold 0, so every pixel averages its centre and an n x n grid
// (tracetask.cpp SupersampleOnePixel). The same samples through filmback's camera.
constexpr int kAntialiasGrid = 8;

Image supersampled_render(const pov::PovCamera& camera, const std::vector<Sphere>& spheres,
                          uint32_t width, uint32_t height) {
  const auto plugin = make_camera_plugin(camera, width, height);
  const double step = 1.0 / kAntialiasGrid, range = 0.5 - step / 2;
  Image image = blank(width, height);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const auto hit = [&](double dx, double dy) {
        const fb_camera_sample sample{float(x + 0.5 + dx), float(y + 0.5 + dy), 0.f, 0.f, 0.f};
        return hits_any(filmback_ray(*plugin, camera.camera, sample), spheres) ? 1 : 0;
      };
      int hits = hit(0, 0);
      for (int j = 0; j < kAntialiasGrid; ++j)
        for (int i = 0; i < kAntialiasGrid; ++i)
          hits += hit(-range + i * step, -range + j * step);
      set(image, x, y, float(hits) / float(kAntialiasGrid * kAntialiasGrid + 1));
    }
  return image;
}

// POV-Ray's render of work/scene.pov, anti-aliased as above, or not: with focal blur POV-Ray
// takes its own jittered samples of each pixel and does not anti-alias it. File_Gamma=1.0: linear
// values; +FN16 keeps the faint edges of focal blur. POV-Ray writes only below its working folder
// (povray.conf): run there.
Image povray_render(const fs::path& povray, const fs::path& work, const Shot& shot,
                    bool antialiased) {
  const std::string out = antialiased ? "povray_aa.png" : "povray.png";
  const std::string sampling =
      antialiased ? " +A0.0 +AM1 +R" + std::to_string(kAntialiasGrid) + " -J" : " -A";
  run_logged("cd " + quoted(work) + " && " + quoted(povray) + " +Iscene.pov +O" + out +
                 " +FN16 File_Gamma=1.0 -D -V" + sampling + " +W" + std::to_string(shot.width) +
                 " +H" + std::to_string(shot.height),
             work / (out + ".log"));
  return read_image(work / out);
}

const Blob* blob_near(const std::vector<Blob>& blobs, double x, double y) {
  for (const Blob& blob : blobs)
    if (std::hypot(blob.x_px - x, blob.y_px - y) < kMatchRadiusPx) return &blob;
  return nullptr;
}

// Coverage in pixels: R+G+B is 3 where a sphere covers the whole pixel.
double area_px(const Blob& blob) {
  return blob.flux / 3;
}

// What a comparison asserts.
struct Checks {
  double max_centroid_px = kMaxCentroidErrorPx;  // and areas within kMaxAreaError
  bool blur = false;                             // blur diameters within kMaxBlurDiameterError
  double pov_shift_px = 0;  // of POV-Ray's image, right and down: taken off its centroids
  uint32_t spp = 0;         // the candidate's samples per pixel, for its noise floor; 0: noise-free
};

// The noise floor of a render's blob centroid: the standard deviation of its distance from where
// the blob would be without noise, were each pixel's coverage p the mean of `spp` independent
// 0-or-1 samples (variance p (1 - p) / spp; stratified samples do better, so this bounds it):
// sigma^2 = sum over pixels of |pixel - centroid|^2 var(pixel) / flux^2.
double centroid_noise_px(const Blob& blob, uint32_t spp) {
  double variance = 0;
  for (const BlobPixel& q : blob.pixels) {
    const double p = std::clamp(q.value / 3, 0.0, 1.0);
    const double dx = q.x + 0.5 - blob.x_px, dy = q.y + 0.5 - blob.y_px;
    variance += (dx * dx + dy * dy) * 9 * p * (1 - p) / spp;  // R+G+B: 3 times the coverage
  }
  return std::sqrt(variance) / blob.flux;
}

// POV-Ray's focal blur draws each sample's offset in the pixel as (2i + 1) / 32 - 1/2 + (j - 1/2)
// / 16 with j from its JitterTable, which spans [-1/2, 1/2] (tracepixel.cpp
// TraceRayWithFocalBlur, jitter.cpp): the samples sit 1/32 px left of and above the pixel's
// centre on average, so its blurred image lies 1/32 px right of and below where its camera puts
// it.
constexpr double kPovFocalBlurShiftPx = 1.0 / 32;

// Each sphere's blob in `candidate` against POV-Ray's at the same place; prints a table.
void compare_blobs(const char* title, const Image& povray, const Image& candidate,
                   size_t blob_count, const Checks& checks) {
  SCOPED_TRACE(title);
  ASSERT_EQ(povray.width, candidate.width);
  ASSERT_EQ(povray.height, candidate.height);
  const std::vector<Blob> pov_blobs = find_blobs(povray, 0.0);
  const std::vector<Blob> blobs = find_blobs(candidate, 0.0);
  ASSERT_EQ(blobs.size(), blob_count) << "every sphere is in view, apart";
  EXPECT_EQ(pov_blobs.size(), blob_count) << "blobs in POV-Ray's render";

  std::printf("%s\n%6s %9s %9s %8s %8s %8s %8s %8s %8s", title, "sphere", "pov_x", "pov_y", "dx_px",
              "dy_px", "|d|_px", "noise_px", "area_px", "area");
  std::printf(checks.blur ? " %8s %8s\n" : "\n", "blur_px", "blur");
  double worst_px = 0, worst_area = 0, worst_blur = 0, worst_noise = 0;
  for (size_t i = 0; i < blobs.size(); ++i) {
    const Blob& b = blobs[i];
    const Blob* p = blob_near(pov_blobs, b.x_px, b.y_px);
    if (!p) {
      ADD_FAILURE() << "no POV-Ray blob within " << kMatchRadiusPx << " px of (" << b.x_px << ", "
                    << b.y_px << ")";
      continue;
    }
    const double pov_x = p->x_px - checks.pov_shift_px, pov_y = p->y_px - checks.pov_shift_px;
    const double dx = b.x_px - pov_x, dy = b.y_px - pov_y, d = std::hypot(dx, dy);
    const double area = area_px(b) / area_px(*p);
    worst_px = std::max(worst_px, d);
    worst_area = std::max(worst_area, std::abs(area - 1));
    const double noise = checks.spp ? centroid_noise_px(b, checks.spp) : 0;
    worst_noise = std::max(worst_noise, noise);
    std::printf("%6zu %9.4f %9.4f %+8.4f %+8.4f %8.4f %8.4f %8.2f %8.4f", i, pov_x, pov_y, dx, dy,
                d, noise, area_px(*p), area);
    EXPECT_LT(d, checks.max_centroid_px) << "sphere " << i << ": centroids differ";
    EXPECT_NEAR(area, 1.0, kMaxAreaError) << "sphere " << i << ": area / POV-Ray's";
    if (checks.blur) {
      // Blur diameter: the disk whose spread, along the wider axis, the blob has.
      const Spread sp = spread(*p), sb = spread(b);
      const double pov_d = disk_diameter_px(std::max(sp.xx, sp.yy));
      const double ratio = disk_diameter_px(std::max(sb.xx, sb.yy)) / pov_d;
      worst_blur = std::max(worst_blur, std::abs(ratio - 1));
      std::printf(" %8.3f %8.4f\n", pov_d, ratio);
      EXPECT_NEAR(ratio, 1.0, kMaxBlurDiameterError) << "sphere " << i << ": blur diameter";
    } else {
      std::printf("\n");
    }
  }
  std::printf("%s: worst centroid %.4f px (noise floor up to %.4f px), worst area %.2f %%", title,
              worst_px, worst_noise, 100 * worst_area);
  std::printf(checks.blur ? ", worst blur diameter %.2f %%\n" : "\n", 100 * worst_blur);
}

// A shot's scene, written to work/<name>/scene.pov, and its camera as filmback converts it.
struct Prepared {
  fs::path work;
  pov::PovCamera camera;
  std::vector<Sphere> spheres;
  Checks checks;
};

Prepared prepare(const Shot& shot, const std::string& folder) {
  Prepared p;
  p.work = fs::path(FILMBACK_POV_WORK_DIR) / folder;
  fs::remove_all(p.work);
  fs::create_directories(p.work);
  const pov::CameraStatement s = statement(shot);  // POV-Ray's defaults without a camera
  Diagnostics diagnostics;
  const pov::PovCameraVectors vectors = pov::evaluate_camera(s, diagnostics);
  p.spheres = spheres_for(shot, vectors);
  if (is_projection_type(shot.type)) {
    std::printf("Shot %s: %zu of %zu markers traced all round\n", shot.name, p.spheres.size(),
                shot.markers.size());
    EXPECT_GE(p.spheres.size(), 12u) << "markers all over the frame";
  }
  {
    std::ofstream out(p.work / "scene.pov");
    out << scene_sdl(shot, p.spheres);
  }

  // The camera filmback renders with is the one the SDL evaluator reads from that file: it must
  // be the statement the shot describes.
  pov::EvaluateOptions options;
  options.scene_file = p.work / "scene.pov";
  options.image_width = shot.width;
  options.image_height = shot.height;
  const pov::Scene scene = pov::evaluate_pov(options);
  EXPECT_EQ(scene.camera.has_value(), shot.has_camera);
  const pov::PovCameraVectors read =
      pov::evaluate_camera(scene.camera.value_or(pov::CameraStatement()), diagnostics);
  EXPECT_EQ(read.type, vectors.type);
  EXPECT_EQ(read.cylinder_type, vectors.cylinder_type);
  EXPECT_EQ(read.angle_deg, vectors.angle_deg);
  EXPECT_EQ(read.angle_h_deg, vectors.angle_h_deg);
  EXPECT_EQ(read.angle_v_deg, vectors.angle_v_deg);
  for (const auto& [a, b] : {std::pair{read.location, vectors.location},
                             {read.direction, vectors.direction},
                             {read.right, vectors.right},
                             {read.up, vectors.up}})
    EXPECT_LT(length(a - b), 1e-12 * std::max(1.0, length(b))) << "the camera as read";
  EXPECT_NEAR(read.focal_distance, vectors.focal_distance, 1e-12);
  EXPECT_EQ(read.focal_blur, vectors.focal_blur);
  diagnostics = Diagnostics();
  p.camera = pov::convert_camera(scene.camera, shot.width, shot.height, diagnostics);
  EXPECT_EQ(diagnostics.count(), shot.skewed ? 1u : 0u)
      << (diagnostics.count() ? diagnostics.messages().front() : "no warning");
  p.checks.blur = p.camera.camera.physical.has_aperture();
  if (p.checks.blur) p.checks.pov_shift_px = kPovFocalBlurShiftPx;
  if (shot.skewed) {
    // The error a skew leaves: up's component along right is dropped (pov_camera.cpp), which
    // moves the top and bottom edges by half of it. A shear keeps areas.
    const double skew_px = 0.5 * std::abs(dot(vectors.up, normalize(vectors.right))) * shot.width /
                           length(vectors.right);
    std::printf("Shot %s: the skew is warned as up to %.4f px\n", shot.name, skew_px);
    p.checks.max_centroid_px += skew_px;
  }
  std::printf("Shot %s, %ux%u, pixel aspect %.6f%s\n", shot.name, shot.width, shot.height,
              p.camera.pixel_aspect, p.checks.blur ? ", focal blur" : "");
  return p;
}

constexpr const char* kNoPovray =
    "POV-Ray is not installed: no `povray` on PATH. Install Debian's package `povray` (apt-get "
    "install povray) to run the tests against POV-Ray.";

// The .pov through filmback's importer parts (the SDL evaluator, pov_camera, pov_geometry,
// pov_appearance) and renderer (RenderJob: the camera plugin, Embree's analytic spheres, the
// emitting materials), 1 px box filter.
Image filmback_render(const fs::path& scene_file, uint32_t width, uint32_t height, uint32_t spp) {
  Diagnostics diagnostics;
  ImportOptions import;
  import.resolution = {width, height};
  const Scene scene = import_pov(scene_file, import, diagnostics);
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.samples_per_pixel = spp;
  options.filter = "box";
  options.show_progress = false;
  return RenderJob(scene, options, loader()).run().image;
}

class PovCameraShot : public testing::TestWithParam<Shot> {};

// POV-Ray's render of each shot against (a) the converted camera's model render and (b)
// filmback's render of the .pov.
TEST_P(PovCameraShot, SpheresLandOnPovRaysPixels) {
  const std::optional<fs::path> povray = find_on_path("povray");
  if (!povray) GTEST_SKIP() << kNoPovray;
  const Shot& shot = GetParam();
  const Prepared p = prepare(shot, shot.name);
  size_t n = 0;  // blobs
  for (const Sphere& sphere : p.spheres)
    n += size_t(sphere.images);
  Checks rendered = p.checks;
  rendered.spp = p.checks.blur                   ? kFilmbackBlurSpp
                 : is_projection_type(shot.type) ? kFilmbackProjectionSpp
                                                 : kFilmbackSpp;
  const Image image = filmback_render(p.work / "scene.pov", shot.width, shot.height, rendered.spp);
  write_images(image, {p.work / "filmback.exr"}, {});
  if (p.checks.blur) {
    // POV-Ray jitters the ray within the pixel and over the lens: the model averages random ones.
    const Image reference = povray_render(*povray, p.work, shot, false);
    compare_blobs("(a) focal blur, thin lens over 1024 random pixel and lens points", reference,
                  lens_render(p.camera, p.spheres, shot.width, shot.height, 1024), n, p.checks);
    compare_blobs("(b) filmback, focal blur", reference, image, n, rendered);
    return;
  }
  const Image reference = povray_render(*povray, p.work, shot, true);
  compare_blobs("(a) anti-aliased: pixel centre and an 8 x 8 grid", reference,
                supersampled_render(p.camera, p.spheres, shot.width, shot.height), n, p.checks);
  compare_blobs("(b) filmback against POV-Ray anti-aliased", reference, image, n, rendered);
}

INSTANTIATE_TEST_SUITE_P(Povray, PovCameraShot, testing::ValuesIn(kShots),
                         [](const testing::TestParamInfo<Shot>& info) {
                           return std::string(info.param.name);
                         });

// Where POV-Ray traces no ray (outside a fisheye's and omnimax's circle, below omnimax's floor)
// its pixel is black whatever the background; filmback's too, and finite. POV-Ray renders one ray
// per pixel centre (-A) on a coloured background; filmback 16 samples a pixel. A pixel whose
// centre and corners POV-Ray's formula all leaves untraced must be 0 in both; one they all trace
// must be the background in both (POV-Ray's 16-bit PNG: within 1e-4).
TEST(PovProjection, UntracedPixelsAreBlackAsPovRays) {
  const std::optional<fs::path> povray = find_on_path("povray");
  if (!povray) GTEST_SKIP() << kNoPovray;
  constexpr uint32_t kWidth = 48, kHeight = 36;
  const float background[3] = {1.f, 0.5f, 0.25f};
  for (const char* type : {"fisheye angle 200", "omnimax"}) {
    SCOPED_TRACE(type);
    const fs::path work =
        fs::path(FILMBACK_POV_WORK_DIR) / "untraced" / std::string(type).substr(0, 7);
    fs::remove_all(work);
    fs::create_directories(work);
    {
      std::ofstream out(work / "scene.pov");
      out << "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\nbackground { rgb <1, 0.5, "
             "0.25> }\ncamera { "
          << type << " location <0, 0, 0> look_at <0, 1, 3> }\n";
    }
    run_logged("cd " + quoted(work) + " && " + quoted(*povray) +
                   " +Iscene.pov +Opovray.png +FN16 File_Gamma=1.0 -D -V -A +W" +
                   std::to_string(kWidth) + " +H" + std::to_string(kHeight),
               work / "povray.log");
    const Image pov_image = read_image(work / "povray.png");
    const Image image = filmback_render(work / "scene.pov", kWidth, kHeight, 16);
    Diagnostics diagnostics;
    pov::EvaluateOptions options;
    options.scene_file = work / "scene.pov";
    options.image_width = kWidth;
    options.image_height = kHeight;
    const pov::PovCameraVectors camera =
        pov::evaluate_camera(*pov::evaluate_pov(options).camera, diagnostics);
    int untraced = 0, traced = 0;
    for (uint32_t y = 0; y < kHeight; ++y)
      for (uint32_t x = 0; x < kWidth; ++x) {
        int hits = 0;
        for (const auto& [dx, dy] :
             {std::pair{0.5, 0.5}, {0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}})
          hits += pov_ray(camera, x + dx, y + dy, kWidth, kHeight).weight > 0;
        for (size_t c = 0; c < 3; ++c) {
          const float ours = image.pixels[(size_t(y) * kWidth + x) * 3 + c];
          const float theirs = pov_image.pixels[(size_t(y) * kWidth + x) * 3 + c];
          ASSERT_TRUE(std::isfinite(ours)) << "pixel " << x << ", " << y;
          if (hits == 0) {
            EXPECT_EQ(ours, 0.f) << "pixel " << x << ", " << y;
            EXPECT_EQ(theirs, 0.f) << "pixel " << x << ", " << y;
          } else if (hits == 5) {
            EXPECT_NEAR(ours, background[c], 1e-5) << "pixel " << x << ", " << y;
            EXPECT_NEAR(theirs, background[c], 1e-4) << "pixel " << x << ", " << y;
          }
        }
        untraced += hits == 0;
        traced += hits == 5;
      }
    std::printf("%s: %d pixels untraced, %d traced all over, of %u\n", type, untraced, traced,
                kWidth * kHeight);
    EXPECT_GT(untraced, 100);
    EXPECT_GT(traced, 500);
  }
}

}  // namespace
}  // namespace fb::test
