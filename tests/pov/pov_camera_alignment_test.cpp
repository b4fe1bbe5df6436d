// POV-Ray's own renders against filmback's camera conversion (docs/pov.md "Camera"), label `pov`.
// Each shot is a camera statement and nine small spheres, flat white (`finish { ambient 1
// diffuse 0 }`) on black, placed on a 3 x 3 grid of the image at three depths. The test writes the
// .pov (camera keywords deliberately out of POV-Ray's evaluation order), renders it with Debian's
// `povray` at 160 x 120 or so without anti-aliasing (one ray through each pixel centre), and
// renders the same spheres through the converted camera: the camera plugin filmback would use
// (perspective, orthographic, thinlens) set up by make_camera_setup, its rays placed by
// world_from_camera, intersected with the spheres analytically. For each sphere:
//  - the image centroids agree within 0.1 px and the pixel areas within 2 %;
//  - with focal blur, against the thin lens's coverage over random points of the pixel and the
//    lens (POV-Ray jitters both): the same, and the blur diameters agree within 3 %;
//  - a camera whose right and up are not perpendicular, which POV-Ray renders skewed and
//    filmback cannot, is warned about, and no centroid is further off than the warning says.
// Skips, naming the package, when `povray` is not on PATH. Work files go to work/<shot>/ in this
// build folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "core/image/image_io.h"
#include "importers/pov/pov_space.h"
#include "support/blobs.h"
#include "support/commands.h"
#include "support/pov_rays.h"

namespace fb::test {
namespace {

namespace fs = std::filesystem;

constexpr double kMaxCentroidErrorPx = 0.1;
constexpr double kMaxAreaError = 0.02;
constexpr double kMaxBlurDiameterError = 0.03;
// A blob is a sphere's when their centroids are this close; spheres are > 25 px apart.
constexpr double kMatchRadiusPx = 2.0;
constexpr double kSphereRadiusPx = 5.0;  // in the image, about

struct Op {
  enum Kind { kRotate, kTranslate, kScale } kind;
  Vec3d v;
};

// One camera statement, given once: written as SDL for POV-Ray and built as the CameraStatement
// the SDL evaluator would produce from it.
struct Shot {
  const char* name;
  uint32_t width = 160, height = 120;
  bool has_camera = true;  // false: no camera statement, POV-Ray's default camera
  bool orthographic = false;
  std::optional<Vec3d> location{}, look_at{}, direction{}, right{}, up{}, sky{}, focal_point{};
  std::optional<double> angle{};
  double aperture = 0;
  int blur_samples = 0;
  std::vector<Op> transforms{};  // in the order written
  bool skewed = false;           // right not perpendicular to up: a warning and a stated error
};

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
     .angle = 50},
    {.name = "mismatched_aspect",  // a square view on a 4:3 image: non-square pixels
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
     .orthographic = true,
     .location = Vec3d{1, 2, -10},
     .look_at = Vec3d{0, 0, 0}},
    {.name = "orthographic_right_up",
     .orthographic = true,
     .location = Vec3d{0, 3, -10},
     .look_at = Vec3d{0, 0, 0},
     .right = Vec3d{8, 0, 0},
     .up = Vec3d{0, 6, 0}},
    {.name = "orthographic_angle",
     .orthographic = true,
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
};

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

pov::CameraStatement statement(const Shot& shot) {
  pov::CameraStatement s;
  s.type = shot.orthographic ? pov::CameraType::kOrthographic : pov::CameraType::kPerspective;
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
    const Transform m = op.kind == Op::kRotate      ? pov_rotate(op.v)
                        : op.kind == Op::kTranslate ? Transform::translate(op.v)
                                                    : Transform::scale(op.v);
    s.transform = m * s.transform;  // written later, applied later
  }
  return s;
}

// The camera block with its keywords in an order unlike POV-Ray's evaluation order (transforms
// first, look_at before location, angle after look_at): the fixed order must not care.
std::string camera_sdl(const Shot& shot) {
  std::string out = "camera {\n  ";
  out += shot.orthographic ? "orthographic\n" : "perspective\n";
  for (const Op& op : shot.transforms)
    out += std::string("  ") +
           (op.kind == Op::kRotate      ? "rotate "
            : op.kind == Op::kTranslate ? "translate "
                                        : "scale ") +
           vec(op.v) + "\n";
  if (shot.focal_point) out += "  focal_point " + vec(*shot.focal_point) + "\n";
  if (shot.aperture != 0) out += "  aperture " + number(shot.aperture) + "\n";
  if (shot.blur_samples > 0)  // at least as many as at most: no adaptive early stop
    out += "  blur_samples " + std::to_string(shot.blur_samples) + ", " +
           std::to_string(shot.blur_samples) + "\n";
  if (shot.look_at) out += "  look_at " + vec(*shot.look_at) + "\n";
  if (shot.angle) out += "  angle " + number(*shot.angle) + "\n";
  if (shot.location) out += "  location " + vec(*shot.location) + "\n";
  if (shot.sky) out += "  sky " + vec(*shot.sky) + "\n";
  if (shot.up) out += "  up " + vec(*shot.up) + "\n";
  if (shot.right) out += "  right " + vec(*shot.right) + "\n";
  if (shot.direction) out += "  direction " + vec(*shot.direction) + "\n";
  return out + "}\n";
}

struct Sphere {
  Vec3d centre;  // POV-Ray's space
  double radius;
};

// Nine spheres on a 3 x 3 grid of the image, at depths 5, 7 and 10 along the view, each about
// kSphereRadiusPx in radius; placed by POV-Ray's own ray model from the evaluated vectors.
std::vector<Sphere> spheres_for(const pov::PovCameraVectors& c, uint32_t width, uint32_t height) {
  const double depths[] = {5, 7, 10};
  const double px = std::min(length(c.right) / width, length(c.up) / height);
  std::vector<Sphere> out;
  int k = 0;
  for (const double y0 : {-0.3, 0.0, 0.3})
    for (const double x0 : {-0.3, 0.0, 0.3}) {
      const double depth = depths[k++ % 3];
      const Vec3d across = c.right * x0 + c.up * y0;
      if (c.type == pov::CameraType::kOrthographic) {
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

// Whether the ray meets any sphere (world space) in front of its origin.
bool hits_any(const WorldRay& ray, const std::vector<Sphere>& spheres) {
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

// The spheres through filmback's camera, one ray through each pixel centre.
Image pinhole_render(const pov::PovCamera& camera, const std::vector<Sphere>& spheres,
                     uint32_t width, uint32_t height) {
  const auto plugin = make_camera_plugin(camera, width, height);
  Image image = blank(width, height);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const fb_camera_sample sample{float(x + 0.5), float(y + 0.5), 0.f, 0.f, 0.f};
      if (hits_any(filmback_ray(*plugin, camera.camera, sample), spheres)) set(image, x, y, 1.f);
    }
  return image;
}

// The same with the thin lens: the pixel's coverage over random points of the pixel and the lens
// (POV-Ray's focal blur jitters both).
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

Image povray_render(const fs::path& povray, const fs::path& work, const Shot& shot,
                    const std::string& sdl) {
  {
    std::ofstream out(work / "scene.pov");
    out << sdl;
  }
  // -A: one ray through each pixel centre; File_Gamma=1.0: linear values; +FN16 keeps the faint
  // edges of focal blur. POV-Ray writes only below its working folder (povray.conf): run there.
  run_logged("cd " + quoted(work) + " && " + quoted(povray) +
                 " +Iscene.pov +Opovray.png +FN16 File_Gamma=1.0 -D -V -A +W" +
                 std::to_string(shot.width) + " +H" + std::to_string(shot.height),
             work / "povray.log");
  return read_image(work / "povray.png");
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

class PovCameraShot : public testing::TestWithParam<Shot> {};

TEST_P(PovCameraShot, SpheresLandWherePovRayPutsThem) {
  const std::optional<fs::path> povray = find_on_path("povray");
  if (!povray)
    GTEST_SKIP() << "POV-Ray is not installed: no `povray` on PATH. Install Debian's package "
                    "`povray` (apt-get install povray) to run the tests against POV-Ray.";
  const Shot& shot = GetParam();
  const fs::path work = fs::path(FILMBACK_POV_WORK_DIR) / shot.name;
  fs::remove_all(work);
  fs::create_directories(work);

  const pov::CameraStatement s = statement(shot);  // POV-Ray's defaults without a camera
  Diagnostics diagnostics;
  const pov::PovCameraVectors vectors = pov::evaluate_camera(s, diagnostics);
  const pov::PovCamera camera = pov::convert_camera(
      shot.has_camera ? std::optional(s) : std::nullopt, shot.width, shot.height, diagnostics);
  // The error a skew leaves: right's x is exact, up's component along right is dropped
  // (pov_camera.cpp), which moves the top and bottom edges by half of it.
  const double skew_px = 0.5 * std::abs(dot(vectors.up, normalize(vectors.right))) * shot.width /
                         length(vectors.right);
  EXPECT_EQ(diagnostics.count(), shot.skewed ? 1u : 0u)
      << (diagnostics.count() ? diagnostics.messages().front() : "no warning");
  const double max_centroid_error_px = kMaxCentroidErrorPx + (shot.skewed ? skew_px : 0);
  const std::vector<Sphere> spheres = spheres_for(vectors, shot.width, shot.height);

  const Image reference = povray_render(*povray, work, shot, scene_sdl(shot, spheres));
  ASSERT_EQ(reference.width, shot.width);
  ASSERT_EQ(reference.height, shot.height);
  // Without blur POV-Ray traces one ray through each pixel centre: so does the model. With blur
  // it jitters the ray within the pixel and over the lens: the model averages random ones.
  const bool blurred = camera.camera.physical.has_aperture();
  const Image model = blurred ? lens_render(camera, spheres, shot.width, shot.height, 1024)
                              : pinhole_render(camera, spheres, shot.width, shot.height);
  const std::vector<Blob> pov_blobs = find_blobs(reference, 0.0);
  const std::vector<Blob> model_blobs = find_blobs(model, 0.0);
  ASSERT_EQ(model_blobs.size(), spheres.size()) << "every sphere is in view, apart";
  EXPECT_EQ(pov_blobs.size(), spheres.size()) << "blobs in POV-Ray's render";

  std::printf("Shot %s, %ux%u, pixel aspect %.6f%s\n", shot.name, shot.width, shot.height,
              camera.pixel_aspect, blurred ? ", focal blur" : "");
  std::printf("%6s %9s %9s %8s %8s %8s %8s %8s", "sphere", "pov_x", "pov_y", "dx_px", "dy_px",
              "|d|_px", "area_px", "area");
  std::printf(blurred ? " %8s %8s\n" : "\n", "blur_px", "lens");
  double worst_px = 0, worst_area = 0, worst_blur = 0;
  for (size_t i = 0; i < model_blobs.size(); ++i) {
    const Blob& m = model_blobs[i];
    const Blob* p = blob_near(pov_blobs, m.x_px, m.y_px);
    if (!p) {
      ADD_FAILURE() << "no POV-Ray blob within " << kMatchRadiusPx << " px of (" << m.x_px << ", "
                    << m.y_px << ")";
      continue;
    }
    const double dx = m.x_px - p->x_px, dy = m.y_px - p->y_px, d = std::hypot(dx, dy);
    const double area = area_px(m) / area_px(*p);
    worst_px = std::max(worst_px, d);
    worst_area = std::max(worst_area, std::abs(area - 1));
    std::printf("%6zu %9.4f %9.4f %+8.4f %+8.4f %8.4f %8.2f %8.4f", i, p->x_px, p->y_px, dx, dy, d,
                area_px(*p), area);
    EXPECT_LT(d, max_centroid_error_px) << "sphere " << i << ": centroids differ";
    if (!shot.skewed) {  // a sheared disc covers other pixel centres
      EXPECT_NEAR(area, 1.0, kMaxAreaError) << "sphere " << i << ": area filmback / POV-Ray";
    }
    if (blurred) {
      // Blur diameter: the disk whose spread, along the wider axis, the blob has.
      const Spread sp = spread(*p), sl = spread(m);
      const double pov_d = disk_diameter_px(std::max(sp.xx, sp.yy));
      const double lens_d = disk_diameter_px(std::max(sl.xx, sl.yy));
      worst_blur = std::max(worst_blur, std::abs(lens_d / pov_d - 1));
      std::printf(" %8.3f %8.4f\n", pov_d, lens_d / pov_d);
      EXPECT_NEAR(lens_d / pov_d, 1.0, kMaxBlurDiameterError) << "sphere " << i << ": blur";
    } else {
      std::printf("\n");
    }
  }
  std::printf("Shot %s: worst centroid %.4f px, worst area %.2f %%", shot.name, worst_px,
              100 * worst_area);
  if (shot.skewed) std::printf(", skew warned as up to %.4f px", skew_px);
  std::printf(blurred ? ", worst blur diameter %.2f %%\n" : "\n", 100 * worst_blur);
}

INSTANTIATE_TEST_SUITE_P(Povray, PovCameraShot, testing::ValuesIn(kShots),
                         [](const testing::TestParamInfo<Shot>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace fb::test
