// POV-Ray's own renders against filmback's conversion of its objects (docs/pov.md "Geometry"),
// label `pov`. Each shot is one object (or CSG) flat white (`finish { ambient 1 diffuse 0 }`) on
// black, seen by one camera, rendered by Debian's `povray` (anti-aliased: each pixel's centre and
// an 8 x 8 grid, linear output) and by filmback (the SDL evaluator, pov_camera, pov_geometry,
// RenderJob at 256 samples with a 1 px box filter). The white blobs' centroids agree within
// 0.1 px and their areas within 2 %, and few pixels differ by more than a quarter. Skips when
// `povray` is not on PATH; work files go to work/geometry/<shot>/ in this build folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>

#include "core/image/image_io.h"
#include "core/render/render_job.h"
#include "importers/pov/pov_camera.h"
#include "importers/pov/pov_geometry.h"
#include "importers/pov/sdl/evaluate.h"
#include "support/blobs.h"
#include "support/commands.h"
#include "support/plugins.h"
#include "tests/pov/marker_tolerances.h"

namespace fb::test {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kGeometryWidth = 160, kGeometryHeight = 120;
// Pixels whose values differ by more than this: sampling noise at 256 spp leaves few.
constexpr double kLargePixelError = 0.25;

struct SolidShot {
  const char* name;
  const char* sdl;       // the objects; the white texture is the #default
  bool several = false;  // separate blobs (a text's glyphs), measured together
};

const SolidShot kSolidShots[] = {
    {"sphere_minus_sphere",
     "difference { sphere { 0, 1 } sphere { <0.6, 0.4, -0.6>, 0.7 } rotate y * 20 }"},
    // Only the cut is white: it wears the subtracted sphere's texture, as in POV-Ray.
    {"cut_wears_subtracted_texture",
     "difference { sphere { 0, 1 pigment { rgb 0 } } sphere { <0.6, 0.4, -0.6>, 0.7 } }"},
    {"box_and_sphere",
     "intersection { box { -1, 1 } sphere { 0, 1.3 } rotate <30, 40, 0> translate x * 0.3 }"},
    {"torus", "torus { 1.2, 0.35 rotate <60, 20, 0> scale <1, 0.8, 1.2> }"},
    {"cone", "cone { <0, -1, 0>, 1, <0, 1, 0>, 0.3 rotate z * 30 }"},
    {"open_cylinder", "cylinder { <-1, 0, 0>, <1, 0, 0>, 0.6 open rotate y * 50 rotate x * -30 }"},
    {"disc", "disc { <0, 0, 0>, <0, 1, -1>, 1.4, 0.6 }"},
    {"clipped_sphere", "sphere { 0, 1.2 clipped_by { plane { <1, 1, -1>, 0.2 } } }"},
    {"plane_to_the_horizon", "plane { y, -1 }"},
    {"inverse_shell",
     "intersection { sphere { 0, 1.4 } sphere { 0, 1 inverse } box { <-2, -2, -2>, <2, 2, 0.3> }"
     " rotate y * -60 }"},
    {"mesh",
     "mesh { triangle { <-1, -1, 0>, <1, -1, 0.5>, <0, 1.2, -0.5> }"
     " triangle { <1, -1, 0.5>, <1.5, 1, 1>, <0, 1.2, -0.5> } rotate y * 30 }"},
    {"sheared_sphere",
     "sphere { 0, 1 matrix <1, 0, 0, 0.5, 1, 0, 0, 0, 1, 0, 0, 0> scale <1.2, 0.8, 1> }"},
    // Polynomial solids: a tilted ellipsoid with a mixed term, an unbounded quadric cylinder cut
    // by a box, and a torus written as a quartic (R = 1, r = 0.4, about POV-Ray's y axis).
    {"quadric_ellipsoid", "quadric { <1, 2.5, 1.5>, <0.4, 0, 0>, 0, -1.2 rotate <20, 30, 0> }"},
    {"quadric_cylinder_in_box",
     "intersection { quadric { <1, 0, 1>, 0, 0, -0.49 } box { -1, 1 } rotate <30, 20, 0> }"},
    {"quartic_torus",
     "quartic { <1,0,0,0,2,0,0,2,0,-2.32,0,0,0,0,0,0,0,0,0,0,1,0,0,2,0,1.68,0,0,0,0,1,0,-2.32,0,"
     "0.7056> rotate <60, 20, 0> }"},
    // Prisms (extruded outlines): a square ring (two linear sub-polygons, even-odd), a closed
    // cubic_spline through six points, a bezier_spline lens swept open.
    {"prism_linear_ring",
     "prism { -0.4, 0.6, 10, <-1.2, -1>, <1.2, -1>, <1.2, 1>, <-1.2, 1>, <-1.2, -1>,"
     " <-0.5, -0.4>, <0.6, -0.4>, <0.6, 0.5>, <-0.5, 0.5>, <-0.5, -0.4> rotate <-70, 25, 0> }"},
    {"prism_cubic_spline",
     "prism { cubic_spline 0, 0.8, 9, <0, -1.3>, <1.4, -0.6>, <1, 0.9>, <-0.2, 1.1>, <-1.3, 0.2>,"
     " <-0.6, -1>, <0, -1.3>, <1.4, -0.6>, <1, 0.9> rotate <-50, -30, 0> translate y * -0.3 }"},
    {"prism_bezier_open",
     "prism { bezier_spline -0.7, 0.7, 8, <-1.5, 0>, <-0.8, 1.6>, <0.8, 1.6>, <1.5, 0>,"
     " <1.5, 0>, <0.8, -1.6>, <-0.8, -1.6>, <-1.5, 0> open rotate <-35, 40, 10> }"},
    // conic_sweep: a quadratic_spline outline scaled by y from the origin (a frustum, apex below).
    {"prism_conic_quadratic",
     "prism { conic_sweep quadratic_spline 0.4, 1, 6, <-1, 0>, <0, -1>, <1, 0>, <0, 1>, <-1, 0>,"
     " <0, -1> scale 1.6 translate -y * 1.1 rotate <-30, 20, 0> }"},
    // Text from the fonts POV-Ray ships: a kerned pair (AV), holes (o, g), quadratic outlines,
    // and the per-character offset.
    {"text_timrom",
     "text { ttf \"timrom.ttf\" \"AVog\" 0.1, <0.05, 0.02, 0> scale 1.4"
     " translate <-1.4, -0.4, 0> rotate <-10, 15, 0> }",
     true},
    {"text_cyrvetic",
     "text { ttf \"cyrvetic.ttf\" \"R&B\" 0.15, 0 scale 1.5"
     " translate <-1.3, -0.5, 0> rotate <5, -10, 0> }",
     true},
    // Superellipsoids: a rounded box, and a pinched star cut by a box (CSG through its spans).
    {"superellipsoid_rounded_box",
     "superellipsoid { <0.25, 0.5> scale <1.3, 0.9, 1> rotate <30, 40, 0> }"},
    {"superellipsoid_star_cut",
     "difference { superellipsoid { <2.5, 2.2> scale 1.6 rotate <20, 30, 0> } box { 0, 2 } }"},
    // A height field from POV-Ray's own colour-mapped plasma3.png (its include folder), cut by
    // water_level: the palette index is the height.
    {"height_field_plasma",
     "height_field { png \"plasma3.png\" smooth water_level 0.3 translate <-0.5, -0.5, -0.5> "
     "scale <3, 1.5, 3> rotate <-30, 20, 0> }"},
    // A blob: two spheres, a turned capsule squashed by its own scale, a subtracting sphere.
    {"blob_mixed",
     "blob { threshold 0.6 sphere { 0, 1, 1 } sphere { <1, 0.3, 0>, 0.9, 1 } "
     "cylinder { <-1, -0.8, 0>, <1, -0.8, 0.4>, 0.6, 1.5 scale <1, 0.7, 1> rotate z * 20 } "
     "sphere { <0.4, 0.4, -0.6>, 0.5, -1 } rotate y * 30 }"},
    // A surface of revolution with a wavy profile, its caps seen from above.
    {"sor_wavy",
     "sor { 7, <0.5, -0.5>, <0.8, 0>, <0.4, 0.5>, <1.0, 1.1>, <0.6, 1.6>, <0.7, 2.0>, <0.3, 2.4> "
     "translate -y scale 1.3 rotate <-20, 0, 15> }"},
    // A lathe's open cubic profile, its loose ends at two heights: the inside between them is
    // what the wall bounds, and the rim is seen from above.
    {"lathe_cubic_open",
     "lathe { cubic_spline 7, <0.2, -1>, <0.5, -1>, <1.0, -0.3>, <0.4, 0.3>, <0.8, 1>, "
     "<0.3, 1.2>, <0, 1.5> rotate <-25, 0, 10> }"},
    // A degree-6 polynomial, |x|^6 + |y|^6 + |z|^6 <= 1.2: bounded, a rounded cube.
    {"polynomial_sextic",
     "polynomial { 6, xyz(6, 0, 0): 1, xyz(0, 6, 0): 1, xyz(0, 0, 6): 1, xyz(0, 0, 0): -1.2 "
     "rotate <30, 40, 0> }"},
};

std::string scene_sdl(const SolidShot& shot) {
  return std::string(
             "#version 3.7;\n"
             "global_settings { assumed_gamma 1.0 }\n"
             "background { rgb 0 }\n"
             "camera { location <0.5, 1.5, -6> look_at <0, 0, 0> angle 45 }\n"
             "#default { pigment { rgb 1 } finish { ambient 1 diffuse 0 } }\n") +
         shot.sdl + "\n";
}

Image povray_render(const fs::path& povray, const fs::path& work) {
  run_logged("cd " + quoted(work) + " && " + quoted(povray) +
                 " +Iscene.pov +Opovray.png +FN16 File_Gamma=1.0 -D -V +A0.0 +AM1 +R8 -J +W" +
                 std::to_string(kGeometryWidth) + " +H" + std::to_string(kGeometryHeight),
             work / "povray.log");
  return read_image(work / "povray.png");
}

// The scene through filmback's converters, each texture a material emitting its pigment colour
// (ambient 1 under POV-Ray's ambient_light 1, and nothing else).
Image filmback_render(const fs::path& work) {
  pov::EvaluateOptions evaluate;
  evaluate.scene_file = work / "scene.pov";
  evaluate.library_paths = {"/usr/share/povray-3.7/include"};  // the fonts, as POV-Ray's +L
  evaluate.image_width = kGeometryWidth, evaluate.image_height = kGeometryHeight;
  // POV-Ray's include folder, where `povray` finds the height field's image too (its povray.ini's
  // Library_Path)
  const fs::path includes = "/usr/share/povray-3.7/include";
  if (fs::is_directory(includes)) evaluate.library_paths = {includes};
  const pov::Scene pov = pov::evaluate_pov(evaluate);
  Diagnostics diagnostics;
  Scene scene;
  scene.cameras.push_back(
      pov::convert_camera(pov.camera, kGeometryWidth, kGeometryHeight, diagnostics).camera);
  const auto material_for = [&](const pov::Texture& t, const std::optional<pov::Interior>&) {
    Material m;
    m.base_color = {0, 0, 0};
    m.double_sided = true;  // POV-Ray surfaces have no back (pov_appearance does the same)
    m.emission =
        Rgb{float(t.pigment.colour.r), float(t.pigment.colour.g), float(t.pigment.colour.b)};
    scene.materials.push_back(m);
    return uint32_t(scene.materials.size() - 1);
  };
  pov::convert_objects(pov, material_for, scene, diagnostics);
  EXPECT_EQ(diagnostics.count(), 0u) << (diagnostics.count() ? diagnostics.messages().front() : "");
  RenderOptions options;
  options.width = kGeometryWidth, options.height = kGeometryHeight, options.samples_per_pixel = 256;
  options.filter = "box";
  options.show_progress = false;
  return RenderJob(scene, options, loader()).run().image;
}

const Blob& largest(const std::vector<Blob>& blobs) {
  return *std::max_element(blobs.begin(), blobs.end(),
                           [](const Blob& a, const Blob& b) { return a.flux < b.flux; });
}

// Every blob as one: the flux-weighted centroid of them all.
Blob together(const std::vector<Blob>& blobs) {
  Blob all;
  for (const Blob& b : blobs) {
    all.x_px += b.x_px * b.flux, all.y_px += b.y_px * b.flux;
    all.flux += b.flux;
  }
  all.x_px /= all.flux, all.y_px /= all.flux;
  return all;
}

double sum_rgb(const Image& image, uint32_t x, uint32_t y) {
  return image.at(x, y, 0) + image.at(x, y, 1) + image.at(x, y, 2);
}

// Each shot rendered by POV-Ray and by filmback: the white blobs' centroids, areas and the pixels
// that differ much.
void expect_on_povrays_pixels(std::span<const SolidShot> shots) {
  const std::optional<fs::path> povray = find_on_path("povray");
  if (!povray)
    GTEST_SKIP() << "POV-Ray is not installed: no `povray` on PATH (Debian package `povray`)";
  std::printf("%-30s %9s %9s %8s %8s %9s %8s %7s\n", "shot", "pov_x", "pov_y", "dx_px", "dy_px",
              "area_px", "area", "large");
  for (const SolidShot& shot : shots) {
    SCOPED_TRACE(shot.name);
    const fs::path work = fs::path(FILMBACK_POV_WORK_DIR) / "geometry" / shot.name;
    fs::remove_all(work);
    fs::create_directories(work);
    std::ofstream(work / "scene.pov") << scene_sdl(shot);
    const Image reference = povray_render(*povray, work);
    const Image image = filmback_render(work);
    write_images(image, {work / "filmback.exr"}, {});
    ASSERT_EQ(reference.width, image.width);
    ASSERT_EQ(reference.height, image.height);
    const std::vector<Blob> pov_blobs = find_blobs(reference, 0.0), blobs = find_blobs(image, 0.0);
    ASSERT_FALSE(pov_blobs.empty());
    ASSERT_FALSE(blobs.empty());
    const Blob p = shot.several ? together(pov_blobs) : largest(pov_blobs);
    const Blob b = shot.several ? together(blobs) : largest(blobs);
    const double dx = b.x_px - p.x_px, dy = b.y_px - p.y_px, area = b.flux / p.flux;
    int large = 0;
    for (uint32_t y = 0; y < kGeometryHeight; ++y)
      for (uint32_t x = 0; x < kGeometryWidth; ++x)
        large += std::abs(sum_rgb(image, x, y) - sum_rgb(reference, x, y)) > 3 * kLargePixelError;
    std::printf("%-30s %9.4f %9.4f %+8.4f %+8.4f %9.1f %8.4f %7d\n", shot.name, p.x_px, p.y_px, dx,
                dy, p.flux / 3, area, large);
    EXPECT_LT(std::hypot(dx, dy), kMaxCentroidErrorPx);
    EXPECT_NEAR(area, 1.0, kMaxAreaError);
    EXPECT_LT(large, 1 + int(0.01 * p.flux / 3)) << "pixels off by more than " << kLargePixelError;
  }
}

TEST(PovGeometryRender, FilmbackDrawsEachObjectOnPovRaysPixels) {
  expect_on_povrays_pixels(kSolidShots);
}

// The shapes of issue 19's last batch, in a test of their own so that it runs alone. (Debian's
// POV-Ray 3.7.0 has no lemon, so the lemon has no shot: PovGeometry.LemonRunsBetweenItsRims.)
const SolidShot kEggSweepAndPatchShots[] = {
    // An egg, Parse_Ovus's first case (bottom radius the larger), turned to show its collar.
    {"ovus", "ovus { 1.0, 0.65 translate -0.4 * y rotate <-20, 0, 35> scale 1.2 }"},
    // The second case (top radius the larger), cut by a box so its inside shows.
    {"ovus_top_larger_cut",
     "difference { ovus { 0.6, 0.9 } box { <0, -1, -2>, <2, 2, 0> } translate -0.7 * y "
     "rotate <0, -30, 10> }"},
    // Sphere sweeps of varying radius along each of their splines.
    {"sphere_sweep_linear",
     "sphere_sweep { linear_spline 4, <-1.6, -0.6, 0>, 0.3, <-0.5, 0.6, 0.3>, 0.5, "
     "<0.5, -0.5, -0.2>, 0.15, <1.6, 0.5, 0>, 0.35 rotate <20, 30, 0> }"},
    {"sphere_sweep_b_spline",
     "sphere_sweep { b_spline 6, <-2.2, 0, 0>, 0.2, <-1.4, 0.9, 0.2>, 0.3, <-0.4, -0.7, 0>, 0.5, "
     "<0.6, 0.8, -0.4>, 0.25, <1.5, -0.3, 0>, 0.35, <2.2, 0.4, 0>, 0.2 rotate <-10, 20, 0> }"},
    {"sphere_sweep_cubic_spline",
     "sphere_sweep { cubic_spline 6, <-2.2, -0.5, 0>, 0.1, <-1.4, 0, 0>, 0.25, <-0.3, 0.7, 0>, "
     "0.4, <0.6, -0.5, 0>, 0.2, <1.4, 0.4, 0>, 0.35, <2.2, 0, 0>, 0.1 rotate <30, 0, 10> }"},
    // objects/primitiv.pov's patch (type 1, 2^4 x 2^4 sub-patches), turned to show its bend.
    {"bicubic_patch",
     "bicubic_patch { type 1 flatness 0.01 u_steps 4 v_steps 4, "
     "<0, -1.5, 2>, <1, -1.5, 0>, <2, -1.5, 0>, <3, -1.5, -2>, "
     "<0, -0.5, 0>, <1, -0.5, 0>, <2, -0.5, 0>, <3, -0.5, 0>, "
     "<0, 0.5, 0>, <1, 0.5, 0>, <2, 0.5, 0>, <3, 0.5, 0>, "
     "<0, 1.5, 2>, <1, 1.5, 0>, <2, 1.5, 0>, <3, 1.5, -2> "
     "translate -1.5 * x rotate <10, -50, 0> scale 0.8 }"},
};

TEST(PovGeometryRender, FilmbackDrawsOvusSweepsAndPatchesOnPovRaysPixels) {
  expect_on_povrays_pixels(kEggSweepAndPatchShots);
}

// Isosurfaces (walked by their gradient bound) and a parametric surface (a 256 x 256 mesh), their
// own test so that they can be run alone: the same tolerances as the exact solids.
const SolidShot kFunctionShots[] = {
    // A wavy ball, turned and squashed, in a box container that cuts it on one side.
    {"isosurface_wavy_ball",
     "isosurface { function { sqrt(x*x + y*y + z*z) + 0.1 * sin(5*x) * sin(5*y) * sin(5*z) }"
     " threshold 0.8 max_gradient 1.9 contained_by { box { -1, <1, 1, 0.6> } }"
     " scale <1.5, 1.2, 1.4> rotate <30, 40, 0> }"},
    // An open wavy sheet in a sphere container, minus a box: CSG through the walk's spans.
    {"isosurface_open_sheet_csg",
     "difference { isosurface { function { y - 0.3 * sin(3 * x) * cos(2 * z) } max_gradient 1.2"
     " contained_by { sphere { 0, 1.4 } } open } box { <0, -2, -2>, <2, 2, 0> } rotate <-40, 20, "
     "0> }"},
    // A torus over u, v in [0, 2 pi]: POV-Ray subdivides it, filmback meshes it.
    {"parametric_torus",
     "parametric { function { (1 + 0.4 * cos(v)) * cos(u) }, function { 0.4 * sin(v) },"
     " function { (1 + 0.4 * cos(v)) * sin(u) } <0, 0>, <2 * pi, 2 * pi>"
     " contained_by { box { -1.5, 1.5 } } accuracy 0.0001 precompute 15, x, y, z"
     " rotate <-50, 20, 0> }"},
};

TEST(PovGeometryRender, IsosurfaceAndParametricOnPovRaysPixels) {
  expect_on_povrays_pixels(kFunctionShots);
}

// Julia fractals (marched by their distance estimate): objects/fractal1.pov's quaternion set and
// fractal4.pov's hypercomplex one, with a precision fine enough that POV-Ray's own march misses
// no thin part, so the silhouettes compare at the exact solids' tolerances.
const SolidShot kJuliaShots[] = {
    {"julia_quaternion_sqr",
     "julia_fractal { <-0.083, 0.0, -0.83, -0.025> quaternion sqr max_iteration 8 precision 200"
     " rotate <30, 40, 0> scale 1.3 }"},
    {"julia_hypercomplex_sqr",
     "julia_fractal { <-0.745, 0, 0.113, 0.05> hypercomplex sqr max_iteration 9 precision 200"
     " scale <1, 2, 1> rotate <135, -30, 0> }"},
};

TEST(PovGeometryRender, JuliaFractalsOnPovRaysPixels) {
  expect_on_povrays_pixels(kJuliaShots);
}

}  // namespace
}  // namespace fb::test
