// `filmback convert in.pov out.gltf` end to end (docs/pov.md "Conversion"), label `pov`: scenes
// the test writes (CSG, patterns, every light kind, glass, a mirrored camera) and some of
// Debian's POV-Ray sample scenes that convert with no warning. For each:
// - the .gltf passes the Khronos glTF validator (npm gltf-validator) with no error and no
//   warning (infos: the two extensions it cannot check, unused objects);
// - filmback renders the .pov and the .gltf alike within noise: each is rendered twice with
//   different seeds, and every 8 x 8 block's mean (per channel) of the .gltf's renders must agree
//   with the .pov's within what their noise allows, a z-score from the pixels' seed-to-seed
//   differences (the two files may have different noise: the .pov's analytic shapes and the
//   .gltf's meshes are sampled differently);
// - silhouettes agree but for tessellation-tolerance pixels: rendered at one sample per pixel
//   with the same seed (so the same rays), the depth differs by more than 2 % in few pixels.
// Work files go to work/convert/<scene>/ in this build folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include "core/image/image_io.h"
#include "support/commands.h"

namespace fb::test {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kConvertWidth = 128, kConvertHeight = 96, kBlock = 8;
constexpr int kSamples = 64;
// The conversion's tolerance, m: a fifth of the default for these metre-sized shapes. At the
// default (a thousandth of each shape's size) the shading of the mirrored_camera shot's cone
// differs by 1 to 2 % in the blocks at its base, 14 to 21 standard errors at 64 spp; at 2e-5 m
// the difference is lost in the noise.
const char* const kTolerance = "0.0002";
// A block mean more than kOutlierZ standard errors from the other file's counts as an outlier;
// at most kOutlierShare of the blocks may be (edges where the tessellation's tolerance shows,
// and the heavy tail of caustic paths' noise); the mean of z^2 over all blocks, 1 for pure
// noise, may be at most kMeanZ2.
constexpr double kOutlierZ = 4, kOutlierShare = 0.02, kMeanZ2 = 2;
// Pixels whose depth differs by more than 2 % between the .pov and the .gltf at the same rays,
// as a fraction of the pixels on a depth edge of the .pov's render.
constexpr double kDepthEdgeShare = 0.25;

struct Shot {
  const char* name;
  const char* sdl;     // written by the test, or
  const char* sample;  // a scene under /usr/share/doc/povray/examples
  // The one warning convert may give, or none.
  const char* expected_warning = nullptr;
  // Whether every surface is opaque, so that the same rays meet the same surfaces (stochastic
  // transparency decides by a hash of the hit, which tessellation moves).
  bool opaque = true;
};

const char* kHeader =
    "#version 3.7;\n"
    "global_settings { assumed_gamma 1.0 }\n"
    "background { rgb <0.10, 0.12, 0.15> }\n";

const Shot kShots[] = {
    {"csg",
     "camera { location <1.5, 2.5, -5> look_at <0, 0.3, 0> angle 40 }\n"
     "light_source { <4, 6, -3> rgb 1 }\n"
     "light_source { <-3, 4, -4> rgb 0.6 spotlight point_at <0, 0, 0> radius 12 falloff 20"
     " tightness 5 fade_distance 4 fade_power 2 }\n"
     "plane { y, -1 pigment { rgb 0.7 } finish { diffuse 0.8 } }\n"
     "difference {\n"
     "  box { -0.8, 0.8 pigment { rgb <0.9, 0.4, 0.2> } }\n"
     "  sphere { <0.5, 0.5, -0.5>, 0.6 pigment { rgb <0.2, 0.6, 0.9> } }\n"
     "  cylinder { <-2, 0.1, 0.2>, <2, 0.1, 0.2>, 0.35 pigment { rgb <0.3, 0.8, 0.3> } }\n"
     "  rotate y * 25\n"
     "}\n"
     "intersection { sphere { 0, 1 } box { -0.75, 0.75 } pigment { rgb <0.8, 0.8, 0.3> }"
     " translate <-1.9, -0.2, 1> }\n"
     "sphere { <1.6, -0.4, 0.8>, 0.6 clipped_by { plane { <0.3, 1, -0.2>, 0.1 } }"
     " pigment { rgb <0.6, 0.3, 0.7> } }\n"
     "torus { 0.5, 0.15 rotate x * 70 translate <1.8, 0.6, 1.6> pigment { rgb 0.9 } }\n",
     nullptr},
    {"patterns",
     "camera { location <0, 3, -7> look_at <0, 0, 0> angle 50 }\n"
     "light_source { <3, 8, -6> rgb 1 }\n"
     "plane { y, -1 pigment { checker rgb 0.9, rgb 0.2 } }\n"
     "sphere { <-2.2, 0, 0>, 0.9 pigment { marble turbulence 0.6"
     " color_map { [0 rgb <0.9, 0.9, 0.8>] [1 rgb <0.2, 0.2, 0.3>] } scale 0.5 } }\n"
     "sphere { <0, 0, 0>, 0.9 pigment { wood color_map { [0 rgb <0.6, 0.3, 0.1>]"
     " [1 rgb <0.9, 0.7, 0.4>] } scale 0.2 rotate x * 80 } }\n"
     "sphere { <2.2, 0, 0>, 0.9 pigment { hexagon rgb <0.9, 0.2, 0.2>, rgb <0.2, 0.9, 0.2>,"
     " rgb <0.2, 0.2, 0.9> scale 0.25 rotate x * -90 } }\n"
     "box { <-3, -1, 1.5>, <-1.5, 0.2, 2.5> pigment { brick rgb 0.8, rgb <0.7, 0.3, 0.2>"
     " scale 0.05 } }\n"
     "box { <-1, -1, 1.5>, <1, 0.2, 2.5> pigment { gradient x sine_wave frequency 3"
     " color_map { [0 rgb <0.1, 0.3, 0.8>] [1 rgb <0.9, 0.9, 0.2>] } } }\n"
     "box { <1.5, -1, 1.5>, <3, 0.2, 2.5> pigment { onion"
     " color_map { [0 rgb <0.9, 0.5, 0.1>] [1 rgb <0.1, 0.5, 0.3>] } scale 0.4 } }\n",
     nullptr},
    {"lights",
     "camera { location <0, 4, -8> look_at <0, 0, 0> angle 55 }\n"
     "light_source { <-3, 3, -2> rgb <1, 0.8, 0.6> fade_distance 2 fade_power 2 }\n"
     "light_source { <3, 5, -3> rgb <0.4, 0.6, 1> spotlight point_at <2, -1, 0> radius 15"
     " falloff 30 tightness 10 }\n"
     "light_source { <0, 10, 0> rgb 0.25 parallel point_at <1, 0, 1> }\n"
     "light_source { <0, 4, 3> rgb 0.5 area_light <2, 0, 0>, <0, 0, 2>, 4, 4 circular orient }\n"
     "light_source { <0, 2, -6> rgb 0.3 shadowless }\n"
     "plane { y, -1 pigment { rgb 0.8 } }\n"
     "sphere { <-1.5, 0, 0>, 1 pigment { rgb 0.9 } }\n"
     "box { <0.8, -1, -0.7>, <2.4, 0.6, 0.9> pigment { rgb <0.9, 0.9, 0.8> } }\n"
     "cylinder { <0, -1, 2.5>, <0, 1.5, 2.5>, 0.4 pigment { rgb 0.7 } }\n",
     nullptr},
    {"glass",
     "camera { location <0, 2, -6> look_at <0, 0.2, 0> angle 45 }\n"
     "light_source { <4, 7, -5> rgb 1 }\n"
     "plane { y, -1 pigment { checker rgb 0.9, rgb 0.3 } }\n"
     "plane { z, 4 pigment { rgb <0.5, 0.6, 0.8> } }\n"
     "sphere { <-1.2, 0, 0>, 1 pigment { rgbf <0.95, 0.95, 1, 0.9> }"
     " finish { specular 0.6 roughness 0.01 } interior { ior 1.5 } }\n"
     "box { <0.4, -1, -0.5>, <1.6, 0.3, 0.7> pigment { rgbt <0.9, 0.3, 0.2, 0.5> } }\n"
     "sphere { <1.6, 0.8, 1.5>, 0.7 pigment { rgb <0.9, 0.8, 0.6> }"
     " finish { reflection 0.6 metallic phong 0.5 } }\n",
     nullptr, nullptr, /*opaque=*/false},
    // cornell.pov's kind of camera: right -1.33 x without look_at renders mirrored. Tilted down
    // so that the horizon is out of the frame: there the square an infinite plane becomes
    // (docs/pov.md, "Conversion") ends 0.01 degrees short of the .pov's.
    {"mirrored_camera",
     "camera { location <0, 1, -6> direction z right -1.33 * x up y rotate x * 35 }\n"
     "light_source { <-3, 5, -4> rgb 1 }\n"
     "plane { y, -1 pigment { rgb 0.7 } }\n"
     "sphere { <-1.5, 0, 0>, 1 pigment { rgb <0.9, 0.2, 0.2> } }\n"
     "cone { <1.5, -1, 0>, 1, <1.5, 1, 0>, 0.2 pigment { rgb <0.2, 0.4, 0.9> } }\n",
     nullptr, "a mirrored camera cannot be written to glTF"},
    {"sample_laser", nullptr, "lights/laser.pov"},
    {"sample_filtfun", nullptr, "textures/pigments/filtfun.pov"},
    {"sample_macro1", nullptr, "language/macros/macro1.pov"},
    {"sample_debug", nullptr, "incdemo/debug.pov"},
};

// Names the shot in test output (and keeps GoogleTest from printing its bytes, which would
// change CTest's test names from one build to the next).
void PrintTo(const Shot& shot, std::ostream* out) {
  *out << shot.name;
}

const fs::path kSampleScenes = "/usr/share/doc/povray/examples";

std::string filmback() {
  return quoted(FILMBACK_EXE);
}

// The scene's .pov and the folder to run filmback in (a sample's own, for its includes).
struct ShotFiles {
  fs::path pov, folder, work;
};

ShotFiles prepare(const Shot& shot) {
  ShotFiles s;
  s.work = fs::path(FILMBACK_POV_WORK_DIR) / "convert" / shot.name;
  fs::create_directories(s.work);
  if (shot.sdl) {
    s.pov = s.work / "scene.pov";
    std::ofstream(s.pov) << kHeader << shot.sdl;
  } else {
    s.pov = kSampleScenes / shot.sample;
  }
  s.folder = s.pov.parent_path();
  return s;
}

std::string res() {
  return " --res " + std::to_string(kConvertWidth) + "x" + std::to_string(kConvertHeight);
}

void convert(const ShotFiles& s) {
  run_logged("cd " + quoted(s.folder) + " && " + filmback() + " convert " + quoted(s.pov) + " " +
                 quoted(s.work / "scene.gltf") + res() + " --tolerance " + kTolerance,
             s.work / "convert.log");
}

Image render(const ShotFiles& s, const fs::path& input, const std::string& name, int spp, int seed,
             const std::string& extra = "") {
  const fs::path out = s.work / (name + ".exr");
  run_logged("cd " + quoted(s.folder) + " && " + filmback() + " render " + quoted(input) + " -o " +
                 quoted(out) + res() + " --spp " + std::to_string(spp) + " --seed " +
                 std::to_string(seed) + " --filter box -q" + extra,
             s.work / (name + ".log"));
  return read_image(out);
}

// z-scores of the difference of the 8 x 8 block means (per channel) of a's and b's renders,
// each rendered twice with different seeds. A block mean's variance is estimated from the
// seed-to-seed differences of its pixels: Var(mean of (x1 + x2) / 2) = sum (x1 - x2)^2 / 4 / n^2.
std::vector<double> block_z_scores(const Image& a1, const Image& a2, const Image& b1,
                                   const Image& b2) {
  std::vector<double> z;
  const double n = kBlock * kBlock;
  for (uint32_t by = 0; by + kBlock <= kConvertHeight; by += kBlock)
    for (uint32_t bx = 0; bx + kBlock <= kConvertWidth; bx += kBlock)
      for (int c = 0; c < 3; ++c) {
        double difference = 0, variance = 0;
        for (uint32_t y = by; y < by + kBlock; ++y)
          for (uint32_t x = bx; x < bx + kBlock; ++x) {
            const double x1 = a1.at(x, y, c), x2 = a2.at(x, y, c);
            const double y1 = b1.at(x, y, c), y2 = b2.at(x, y, c);
            difference += (x1 + x2 - y1 - y2) / 2;
            variance += ((x1 - x2) * (x1 - x2) + (y1 - y2) * (y1 - y2)) / 4;
          }
        // A block both renders see without noise (background) agrees only if equal: its
        // variance floor is float rounding of the means.
        const double floor = 1e-12 * n * n;
        z.push_back((difference / n) / std::sqrt((variance + floor) / (n * n)));
      }
  return z;
}

bool depth_differs(float a, float b) {
  return std::abs(a - b) > 0.02f * std::max(std::abs(a), std::abs(b));
}

class PovConvert : public testing::TestWithParam<Shot> {};

TEST_P(PovConvert, ValidatesAndRendersAsThePovWithinNoise) {
  const Shot& shot = GetParam();
  if (shot.sample && !fs::exists(kSampleScenes / shot.sample))
    GTEST_SKIP() << "needs Debian's povray-examples (" << shot.sample << ")";
  const ShotFiles s = prepare(shot);
  convert(s);
  // Converted fully: nothing left out, nothing approximated with a warning.
  const std::string log = read_text(s.work / "convert.log");
  if (shot.expected_warning)
    EXPECT_NE(log.find(shot.expected_warning), std::string::npos) << log;
  else
    EXPECT_EQ(log.find("warning"), std::string::npos) << log;

  const fs::path modules = FILMBACK_NODE_MODULES;
  if (find_on_path("node") && fs::exists(modules / "gltf-validator")) {
    run_logged("node " + quoted(FILMBACK_VALIDATE_JS) + " " + quoted(modules) + " " +
                   quoted(s.work / "scene.gltf"),
               s.work / "validator.log");
    const std::string report = read_text(s.work / "validator.log");
    std::printf("%s: %s", shot.name, report.c_str());
    EXPECT_NE(report.find(" 0 errors, 0 warnings"), std::string::npos) << report;
  } else {
    std::printf(
        "%s: glTF validator not run: needs node and the npm package gltf-validator under %s"
        " (./setup.sh test installs it)\n",
        shot.name, modules.c_str());
  }

  const Image pov = render(s, s.pov, "pov", kSamples, 1);
  const Image pov_again = render(s, s.pov, "pov_again", kSamples, 2);
  const Image gltf = render(s, s.work / "scene.gltf", "gltf", kSamples, 3);
  const Image gltf_again = render(s, s.work / "scene.gltf", "gltf_again", kSamples, 4);
  const std::vector<double> z = block_z_scores(pov, pov_again, gltf, gltf_again);
  double mean_z2 = 0, worst = 0;
  int outliers = 0;
  for (double v : z) {
    mean_z2 += v * v / double(z.size());
    worst = std::max(worst, std::abs(v));
    outliers += std::abs(v) > kOutlierZ;
  }
  std::printf("%s: %zu block means, mean z^2 %.3f, worst |z| %.2f, %d beyond %.0f\n", shot.name,
              z.size(), mean_z2, worst, outliers, kOutlierZ);
  EXPECT_LE(mean_z2, kMeanZ2);
  EXPECT_LE(outliers, kOutlierShare * double(z.size()));
  if (!shot.opaque) return;

  // Silhouettes: the same rays (one sample per pixel, one seed) see the same surfaces.
  const std::string depth = " --integrator aov:show=depth";
  const Image pov_depth = render(s, s.pov, "pov_depth", 1, 7, depth);
  const Image gltf_depth = render(s, s.work / "scene.gltf", "gltf_depth", 1, 7, depth);
  const size_t zc = size_t(std::find(pov_depth.channels.begin(), pov_depth.channels.end(), "Z") -
                           pov_depth.channels.begin());
  ASSERT_LT(zc, pov_depth.channels.size()) << "no Z channel";
  int edges = 0, moved = 0;
  for (uint32_t y = 0; y < kConvertHeight; ++y)
    for (uint32_t x = 0; x < kConvertWidth; ++x) {
      const float d = pov_depth.at(x, y, zc);
      bool edge = false;
      for (auto [nx, ny] : {std::pair{x + 1, y}, {x, y + 1}})
        edge |=
            nx < kConvertWidth && ny < kConvertHeight && depth_differs(d, pov_depth.at(nx, ny, zc));
      edges += edge;
      moved += depth_differs(d, gltf_depth.at(x, y, zc));
    }
  std::printf("%s: depth differs in %d px, %d px on depth edges\n", shot.name, moved, edges);
  EXPECT_LE(moved, kDepthEdgeShare * edges);
}

INSTANTIATE_TEST_SUITE_P(Shots, PovConvert, testing::ValuesIn(kShots),
                         [](const testing::TestParamInfo<Shot>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace fb::test
