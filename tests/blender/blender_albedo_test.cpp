// Directional albedo of Blender's materials against Cycles (albedo_shot.py): spheres under a
// uniform white world seen by an orthographic camera, so that each pixel is the albedo
// integral of f cos at the pixel's angle; the world reached only by BSDF sampling. filmback's
// side is core/shading's Surface for the same node inputs (read from the manifest), its albedo
// the mean sample() weight (the estimator Cycles uses here), tabulated over cos(theta) and
// averaged over each pixel's area as Cycles' 1 px box filter does. Compared per material, per
// channel and per bin of cos(theta) (8 bins): the bar is 1 %. The noise floor, the
// standard error of each bin's Cycles mean from the scatter of its pixels, is printed with the
// table (docs/blender.md, "Blender materials").
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/image/image_io.h"
#include "core/shading/surface.h"
#include "tests/blender/blender_shot.h"
#include "tests/support/commands.h"

namespace fb::test {
namespace {

namespace fs = std::filesystem;

constexpr int kBins = 8;     // of cos(theta)
constexpr int kTable = 256;  // cos(theta) entries of filmback's albedo table
constexpr int kTableSamples = 4096;
constexpr int kSubPixels = 4;  // per pixel side, for the box filter

Rgb rgb(const Record& r, const std::string& key) {
  std::istringstream in(r.text(key));
  Rgb c;
  char comma;
  in >> c.x >> comma >> c.y >> comma >> c.z;
  return c;
}

// The Surface the sphere's node makes at normal n, seen from +z.
void make_surface(const Record& r, Vec3f n, Surface& s) {
  s.begin({{0.f, 0.f, 1.f}, n, n, false, /*camera_ray=*/true});
  const Rgb white{1.f, 1.f, 1.f};
  const std::string& node = r.text("node");
  if (node == "principled") {
    PrincipledInputs p;
    p.base_color = rgb(r, "base_color");
    p.specular = float(r.number("specular"));
    p.roughness = float(r.number("roughness"));
    p.metallic = float(r.number("metallic"));
    p.specular_tint = float(r.number("specular_tint"));
    p.sheen = float(r.number("sheen"));
    p.sheen_tint = float(r.number("sheen_tint"));
    p.clearcoat = float(r.number("clearcoat"));
    p.clearcoat_roughness = float(r.number("clearcoat_roughness"));
    p.distribution =
        r.text("distribution") == "MULTI_GGX" ? Distribution::kMultiGgx : Distribution::kGgx;
    s.add_principled(p, white);
  } else if (node == "diffuse") {
    s.add_diffuse(rgb(r, "color"), float(r.number("roughness")), {}, white);
  } else if (node == "glossy") {
    const std::string& d = r.text("distribution");
    const Distribution distribution = d == "MULTI_GGX"  ? Distribution::kMultiGgx
                                      : d == "BECKMANN" ? Distribution::kBeckmann
                                                        : Distribution::kGgx;
    s.add_glossy(distribution, rgb(r, "color"), float(r.number("roughness")), {}, white);
  } else {
    throw std::runtime_error("manifest: unknown node " + node);
  }
}

// filmback's albedo at cos(theta) = (i + 0.5) / kTable: the mean sample() weight, the normal
// tilted about y (the materials are isotropic).
std::vector<Rgb> albedo_table(const Record& r) {
  std::vector<Rgb> table(kTable);
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  Surface s;
  for (int i = 0; i < kTable; ++i) {
    const float c = (i + 0.5f) / kTable;
    make_surface(r, {std::sqrt(1.f - c * c), 0.f, c}, s);
    Rgb sum{};
    for (int n = 0; n < kTableSamples; ++n) {
      // Stratified in the closure choice and the direction's first number.
      const float v[3] = {(n % 64 + u(rng)) / 64.f, (n / 64 + u(rng)) / 64.f, u(rng)};
      SurfaceSample ss;
      if (s.sample(v, ss)) sum += ss.weight;
    }
    table[i] = sum / float(kTableSamples);
  }
  return table;
}

Rgb lookup(const std::vector<Rgb>& table, float c) {
  const float x = std::clamp(c * kTable - 0.5f, 0.f, kTable - 1.f);
  const int i = std::min(int(x), kTable - 2);
  const float t = x - i;
  return table[i] * (1.f - t) + table[i + 1] * t;
}

struct Bin {
  double cycles[3] = {0, 0, 0}, filmback[3] = {0, 0, 0}, residual2[3] = {0, 0, 0};
  int pixels = 0;
};

using BlenderAlbedo = WithBlender<>;

TEST_F(BlenderAlbedo, DirectionalAlbedoMatchesCycles) {
  const fs::path work = fs::path(FILMBACK_BLENDER_WORK_DIR) / "albedo";
  fs::remove_all(work);
  fs::create_directories(work);
  run_logged(quoted(blender) + " -b --factory-startup --python-exit-code 1 --python " +
                 quoted(FILMBACK_ALBEDO_SHOT_PY) + " -- " + quoted(work),
             work / "blender.log");
  const Image cycles = read_image(work / "cycles.exr");
  std::printf("%-30s %-10s %s\n", "material", "cos bin", "filmback/Cycles - 1 (R G B), noise");
  for (const Record& r : read_manifest(work / "manifest.txt")) {
    if (r.kind != "sphere") continue;
    const std::vector<Rgb> table = albedo_table(r);
    const double cx = r.number("centre_x_px"), cy = r.number("centre_y_px");
    const double radius = r.number("radius_px");
    std::array<Bin, kBins> bins{};
    for (int y = int(cy - radius); y <= int(cy + radius); ++y)
      for (int x = int(cx - radius); x <= int(cx + radius); ++x) {
        // Whole pixels on the sphere only: the pixel's farthest corner inside the disk.
        const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
        if (std::hypot(dx, dy) + std::sqrt(0.5) >= radius) continue;
        Rgb f{};
        for (int a = 0; a < kSubPixels; ++a)
          for (int b = 0; b < kSubPixels; ++b) {
            const double sx = (x + (a + 0.5) / kSubPixels - cx) / radius;
            const double sy = (y + (b + 0.5) / kSubPixels - cy) / radius;
            f += lookup(table, float(std::sqrt(std::max(0.0, 1 - sx * sx - sy * sy))));
          }
        f = f / float(kSubPixels * kSubPixels);
        const double c = std::sqrt(std::max(0.0, 1 - (dx * dx + dy * dy) / (radius * radius)));
        Bin& bin = bins[std::min(kBins - 1, int(c * kBins))];
        ++bin.pixels;
        for (int ch = 0; ch < 3; ++ch) {
          const double v = cycles.at(uint32_t(x), uint32_t(y), ch);
          bin.cycles[ch] += v;
          bin.filmback[ch] += f[ch];
          bin.residual2[ch] += (v - f[ch]) * (v - f[ch]);
        }
      }
    for (int i = 0; i < kBins; ++i) {
      const Bin& bin = bins[i];
      if (bin.pixels < 16) continue;
      double diff[3], noise = 0;
      for (int ch = 0; ch < 3; ++ch) {
        diff[ch] = bin.filmback[ch] / bin.cycles[ch] - 1;
        // The standard error of the Cycles mean, relative.
        noise = std::max(noise, std::sqrt(bin.residual2[ch] / bin.pixels) /
                                    std::sqrt(double(bin.pixels)) / (bin.cycles[ch] / bin.pixels));
      }
      std::printf("%-30s %.3f-%.3f %+7.2f%% %+7.2f%% %+7.2f%%  +-%.2f%% (%d px)\n",
                  r.text("name").c_str(), double(i) / kBins, double(i + 1) / kBins, 100 * diff[0],
                  100 * diff[1], 100 * diff[2], 100 * noise, bin.pixels);
      const double worst = std::max({std::abs(diff[0]), std::abs(diff[1]), std::abs(diff[2])});
      EXPECT_LT(worst, 0.01) << r.text("name") << " cos " << double(i) / kBins;
    }
  }
}

}  // namespace
}  // namespace fb::test
