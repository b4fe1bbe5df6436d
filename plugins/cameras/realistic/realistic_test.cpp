// The lens optics of the `realistic` camera (core/sdk/filmback/lens_optics.h) against analytic
// thick-lens formulas, the shipped lenses' focal lengths against their published ones and their
// paraxial values against exact rays near the axis, the lens file parser's errors, and the plugin
// on a lens that vignettes to nothing at the film's corners.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include <filmback/lens_optics.h>

#include "exit_pupil.h"

#include "core/plugin/instances.h"
#include "core/scene/camera.h"
#include "support/plugins.h"

namespace fb {
namespace {

const std::string kLensFolder = FILMBACK_SOURCE_DIR "/scenes/lenses/";

// The focal length and back focus of a ray parallel to the axis at height h (mm) entering the
// front, traced exactly: as h -> 0 they converge to the paraxial values (spherical aberration
// grows as h^2).
struct RealFocus {
  double efl_mm, bfl_mm;
};
RealFocus real_focus(const LensPrescription& lens, double h) {
  const LensStack stack(lens, 0);  // rear vertex at z = 0
  LensRay ray{{0, h, stack.front_z_mm() + 1}, {0, 0, -1}};
  EXPECT_TRUE(stack.trace(ray));
  const Vec3d o = ray.origin, d = ray.direction;
  return {h * -d.z / -d.y, -(o.z + -o.y / d.y * d.z)};
}

TEST(LensOptics, ThickSingletMatchesTheLensmakersEquation) {
  // n = 1.5, R1 = 50, R2 = -80, centre thickness 6 mm, the stop in contact in front.
  const double n = 1.5, r1 = 50, r2 = -80, d = 6;
  const LensPrescription lens =
      parse_lens_prescription("0 0 0 10\n50 6 1.5 20\n-80 0 1 20\n", "singlet");
  const ParaxialLens p = paraxial_lens(lens);
  // 1/f = (n - 1) (1/R1 - 1/R2 + (n - 1) d / (n R1 R2)) (Hecht, Optics, eq. 6.2).
  const double f = 1 / ((n - 1) * (1 / r1 - 1 / r2 + (n - 1) * d / (n * r1 * r2)));
  EXPECT_NEAR(p.efl_mm, f, 1e-9 * f);
  // Back and front focal distances: f (1 - (n - 1) d / (n R1)), f (1 + (n - 1) d / (n R2)).
  EXPECT_NEAR(p.bfl_mm, f * (1 - (n - 1) * d / (n * r1)), 1e-9 * f);
  EXPECT_NEAR(p.ffd_mm, f * (1 + (n - 1) * d / (n * r2)), 1e-9 * f);
  // The stop in front, in contact: the entrance pupil is the stop itself.
  EXPECT_NEAR(p.entrance_pupil_diameter_mm, 10, 1e-12);
  EXPECT_NEAR(p.fnumber, f / 10, 1e-9);
}

// Each shipped lens' focal length is the one its file names (Smith's prescriptions scaled to it,
// scenes/lenses/*.dat), within 0.1 %; the paraxial focal length and back focus agree with exact
// rays 1e-4 of the entrance pupil's radius off the axis within 0.1 %, two independent paths.
TEST(LensOptics, ShippedLensesHaveTheirPublishedFocalLengths) {
  const std::pair<const char*, double> kLenses[] = {
      {"dgauss50.dat", 50}, {"wide22.dat", 22}, {"telephoto250.dat", 250}, {"fisheye10.dat", 10}};
  for (const auto& [file, focal_mm] : kLenses) {
    SCOPED_TRACE(file);
    const LensPrescription lens = read_lens_file(kLensFolder + file);
    const ParaxialLens p = paraxial_lens(lens);
    EXPECT_NEAR(p.efl_mm, focal_mm, 1e-3 * focal_mm);
    const RealFocus real = real_focus(lens, 1e-4 * p.entrance_pupil_diameter_mm / 2);
    EXPECT_NEAR(real.efl_mm, p.efl_mm, 1e-3 * p.efl_mm);
    EXPECT_NEAR(real.bfl_mm, p.bfl_mm, 1e-3 * std::abs(p.bfl_mm));
    EXPECT_GT(p.bfl_mm, 0);  // a film fits behind each
  }
}

TEST(LensOptics, TheDoubleGaussIsAnFTwoLensAndItsStopCloses) {
  const LensPrescription lens = read_lens_file(kLensFolder + "dgauss50.dat");
  const ParaxialLens open = paraxial_lens(lens);
  EXPECT_GT(open.fnumber, 1.9);  // Smith: f/2
  EXPECT_LT(open.fnumber, 2.1);
  const ParaxialLens closed = paraxial_lens(stopped_down(lens, open, 8));
  EXPECT_NEAR(closed.fnumber, 8, 1e-9);
  EXPECT_EQ(closed.efl_mm, open.efl_mm);
  EXPECT_THROW(stopped_down(lens, open, 1.4), std::invalid_argument);  // never opens beyond
}

// Focusing moves the film: an object point at distance D from the front principal point, traced
// exactly through a small aperture, meets the film at the axis.
TEST(LensOptics, FocusingPutsTheFilmWhereAnAxialPointImages) {
  const LensPrescription open = read_lens_file(kLensFolder + "dgauss50.dat");
  const LensPrescription lens = stopped_down(open, paraxial_lens(open), 64);
  const ParaxialLens p = paraxial_lens(lens);
  for (const double focus_mm : {500.0, 2000.0, 1e5}) {
    const double back = back_distance_for_focus_mm(p, focus_mm);
    const LensStack stack(lens, back);
    const double object_z = front_principal_z_mm(p, back) + focus_mm;
    const double h = 1e-3;  // aim at the front vertex, just off the axis
    LensRay ray{{0, 0, object_z}, normalize(Vec3d{0, h, stack.front_z_mm() - object_z})};
    ASSERT_TRUE(stack.trace(ray));
    const double y_at_film = ray.origin.y + ray.direction.y * -ray.origin.z / ray.direction.z;
    EXPECT_NEAR(y_at_film, 0, 1e-6) << focus_mm;  // h = 1e-3 mm: paraxial to ~h^3
  }
}

// The exit pupil's bounds are the sampling domain: a ray that passes the lens outside its film
// radius' bounds would be light the camera never gathers (a bias, not noise). Every shipped lens,
// wide open and focused at 1 m, film points every 0.6 mm out to a 36 x 24 mm film's corner, rays
// on an 80 x 80 grid over the rear element's 1.5x square, off the bounds' own grid: all that pass
// lie inside.
TEST(RealisticCamera, ExitPupilBoundsHoldEveryRayThatPasses) {
  for (const char* file : {"dgauss50.dat", "wide22.dat", "telephoto250.dat", "fisheye10.dat"}) {
    SCOPED_TRACE(file);
    const LensPrescription lens = read_lens_file(kLensFolder + file);
    const LensStack stack(lens, back_distance_for_focus_mm(paraxial_lens(lens), 1000));
    const double corner_mm = std::hypot(18.0, 12.0);
    const ExitPupil pupil(stack, corner_mm);
    const double half = 1.5 * stack.rear_aperture_radius_mm();
    size_t passed = 0, outside = 0;
    for (double r = 0; r <= corner_mm; r += 0.6) {
      const PupilBounds& b = pupil.at(r);
      for (int i = 0; i < 80; ++i)
        for (int j = 0; j < 80; ++j) {
          const double x = -half + (i + 0.25) * half / 40, y = -half + (j + 0.75) * half / 40;
          LensRay ray{{r, 0, 0}, normalize(Vec3d{x - r, y, stack.rear_z_mm()})};
          if (!stack.trace(ray)) continue;
          ++passed;
          outside += !(x >= b.x0 && x <= b.x1 && y >= b.y0 && y <= b.y1);
        }
    }
    EXPECT_GT(passed, 0u);
    EXPECT_EQ(outside, 0u) << "of " << passed;
  }
}

void expect_parse_error(const std::string& text, const std::string& where_and_what) {
  try {
    parse_lens_prescription(text, "bad.dat");
    ADD_FAILURE() << "accepted: " << text;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(where_and_what), std::string::npos) << e.what();
  }
}

TEST(LensPrescription, BadLinesAreNamedByLineAndColumn) {
  const std::string good = "# a lens\n50 6 1.5 20\n";
  expect_parse_error(good + "-80 x 1 20\n0 0 0 10\n", "bad.dat:3:5: expected a number (thickness");
  expect_parse_error(good + "-80 nan 1 20\n0 0 0 10\n", "bad.dat:3:5: expected a finite number");
  expect_parse_error(good + "-80 6 1\n0 0 0 10\n", "bad.dat:3:8: expected 4 numbers, missing");
  expect_parse_error(good + "-80 6 1 20 5\n", "bad.dat:3:12: expected 4 numbers on a line");
  expect_parse_error(good + "-80 6 0.5 20\n", "bad.dat:3:7: expected an index of refraction");
  expect_parse_error(good + "-8 6 1 20\n", "bad.dat:3:8: expected an aperture diameter within");
  expect_parse_error(good + "-80 -1 1 20\n", "bad.dat:3:5: expected a thickness");
  expect_parse_error(good + "-80 6 1 20\n", "bad.dat:4:1: expected an aperture stop");
  expect_parse_error(good + "0 0 0 10\n0 0 0 10\n", "bad.dat:4:1: a lens has one aperture stop");
  expect_parse_error(std::string(kMaxLensFileBytes + 1, ' '), "bad.dat:1:1: a lens file holds");
  std::string many;
  for (size_t i = 0; i <= kMaxLensInterfaces; ++i)
    many += "0 0 0 10\n";
  expect_parse_error(many, "a lens has one aperture stop");
  std::string long_lens = "0 1 0 10\n";
  for (size_t i = 0; i < kMaxLensInterfaces; ++i)
    long_lens += "1e5 1 1 20\n";
  expect_parse_error(long_lens, "bad.dat:65:1: a lens has at most 64 interfaces");
  EXPECT_THROW(read_lens_file(kLensFolder + "no_such_lens.dat"), std::invalid_argument);
}

// Mutated lens files (bytes replaced, dropped, repeated; a fixed pseudo-random sequence): the
// parser accepts or throws std::invalid_argument naming the file, and whatever it accepts has
// finite paraxial numbers or is refused as such, and traces rays to finite ends or blocks them.
TEST(LensPrescription, MutatedFilesAreAcceptedOrRefusedCleanly) {
  std::ifstream in(kLensFolder + "dgauss50.dat");
  const std::string original((std::istreambuf_iterator<char>(in)), {});
  const std::string alphabet = "0123456789.-+eE #\n\t nanif,x";
  uint64_t state = 0x9e3779b97f4a7c15u;
  const auto next = [&state] {
    state = state * 6364136223846793005u + 1442695040888963407u;  // Knuth's MMIX LCG
    return uint32_t(state >> 33);
  };
  size_t accepted = 0;
  for (int round = 0; round < 3000; ++round) {
    std::string text = original;
    for (int k = 0, edits = 1 + next() % 4; k < edits; ++k) {
      const size_t at = next() % text.size();
      switch (next() % 3) {
        case 0:
          text[at] = alphabet[next() % alphabet.size()];
          break;
        case 1:
          text.erase(at, 1 + next() % 8);
          break;
        default:
          text = text.substr(0, at) + text.substr(at, next() % 40) + text.substr(at);
          break;
      }
      if (text.empty()) text.push_back('#');
    }
    LensPrescription lens;
    try {
      lens = parse_lens_prescription(text, "mutated.dat");
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("mutated.dat:", 0), 0u) << e.what();
      continue;
    }
    ++accepted;
    ParaxialLens p;
    try {
      p = paraxial_lens(lens);
    } catch (const std::invalid_argument&) {
      continue;  // no positive power
    }
    ASSERT_TRUE(std::isfinite(p.efl_mm) && std::isfinite(p.bfl_mm) && std::isfinite(p.fnumber));
    const LensStack stack(lens, std::max(p.bfl_mm, 1.0));
    for (const double h : {0.0, 0.3, 0.9}) {
      LensRay ray{{h, 0, 0}, normalize(Vec3d{-h, h, stack.rear_z_mm()})};
      if (stack.trace(ray)) {
        EXPECT_TRUE(std::isfinite(ray.origin.z) && std::isfinite(ray.direction.z)) << text;
      }
    }
  }
  EXPECT_GT(accepted, 100u);  // the mutations reach the optics, not only the parser
}

// A lens that passes light only near the axis: a 2 mm rear element 60 mm behind the stop. The
// film's corners see nothing: weight 0 and finite rays, never NaN; the centre sees light.
TEST(RealisticCamera, ALensThatVignettesToNothingGivesBlackCorners) {
  const std::string path = ::testing::TempDir() + "realistic_test_vignetting_lens.dat";
  std::ofstream(path) << "40 4 1.5 20\n0 60 0 10\n-1e4 0 1 2\n";
  PhysicalCamera physical;
  physical.focal_length_mm = 50;
  const fb_camera_setup setup = make_camera_setup(physical, 96, 64);
  auto library = test::loader().load(FB_KIND_CAMERA, "realistic");
  const CameraInstance camera(library, BoundParams(library->descriptor(), {{"lens", path}}), setup);
  EXPECT_EQ(camera.needs(), uint32_t(FB_CAMERA_NEEDS_LENS));
  const auto light = [&](float x, float y) {
    double sum = 0;
    for (int i = 0; i < 32; ++i)
      for (int j = 0; j < 32; ++j) {
        const fb_camera_sample s{x, y, (i + 0.5f) / 32, (j + 0.5f) / 32, 0.f};
        fb_camera_ray ray;
        camera.generate_rays({&s, 1}, &ray);
        for (const float v : {ray.origin[0], ray.origin[1], ray.origin[2], ray.direction[0],
                              ray.direction[1], ray.direction[2], ray.t_min})
          EXPECT_TRUE(std::isfinite(v));
        EXPECT_FALSE(std::isnan(ray.t_max));  // +inf: no far clip
        EXPECT_TRUE(std::isfinite(ray.weight) && ray.weight >= 0);
        sum += ray.weight;
      }
    return sum / (32 * 32);
  };
  EXPECT_NEAR(light(48, 32), 1, 0.05);  // SIMPLE: the centre's radiance, whole
  for (const auto& [x, y] : {std::pair{0.f, 0.f}, {96.f, 0.f}, {0.f, 64.f}, {96.f, 64.f}})
    EXPECT_EQ(light(x, y), 0) << x << "," << y;
}

// The number after "name: " in a camera's description (fb_camera_api::describe), NaN if absent.
double described(const std::string& lines, const std::string& name) {
  const size_t at = lines.find(name + ": ");
  return at == std::string::npos ? NAN : std::strtod(lines.c_str() + at + name.size() + 2, nullptr);
}

// What `filmback info` prints for the camera: the lens' paraxial numbers, with its stop closed.
TEST(RealisticCamera, DescribesTheLensFirstOrderNumbers) {
  const std::string path = kLensFolder + "dgauss50.dat";
  const LensPrescription lens = read_lens_file(path);
  const ParaxialLens p = paraxial_lens(lens);
  PhysicalCamera physical;
  auto library = test::loader().load(FB_KIND_CAMERA, "realistic");
  const CameraInstance camera(library,
                              BoundParams(library->descriptor(), {{"lens", path}, {"fstop", "8"}}),
                              make_camera_setup(physical, 96, 64));
  const std::string lines = camera.describe();
  EXPECT_NEAR(described(lines, "effective focal length"), p.efl_mm, 1e-4) << lines;
  EXPECT_NEAR(described(lines, "back focal distance"), p.bfl_mm, 1e-4) << lines;
  EXPECT_NEAR(described(lines, "f-number"), 8, 1e-3) << lines;
  EXPECT_NEAR(described(lines, "entrance pupil diameter"), p.efl_mm / 8, 1e-4) << lines;
  // Focused at infinity the film sits at the back focus; the working f-number, from the centre's
  // irradiance, is the paraxial one up to the pupil's aberrations (1 %).
  EXPECT_NEAR(described(lines, "film"), p.bfl_mm, 1e-4) << lines;
  EXPECT_NEAR(described(lines, "working f-number at the film's centre"), 8, 0.08) << lines;
}

TEST(RealisticCamera, NeedsALensFileAndAPerspectiveShot) {
  PhysicalCamera physical;
  auto library = test::loader().load(FB_KIND_CAMERA, "realistic");
  EXPECT_THROW(CameraInstance(library, BoundParams(library->descriptor(), {}),
                              make_camera_setup(physical, 10, 10)),
               std::runtime_error);
  physical.projection = FB_PROJECTION_ORTHOGRAPHIC;
  const BoundParams lens(library->descriptor(), {{"lens", kLensFolder + "dgauss50.dat"}});
  EXPECT_THROW(CameraInstance(library, lens, make_camera_setup(physical, 10, 10)),
               std::runtime_error);
}

}  // namespace
}  // namespace fb
