// Filter plugins through the ABI, against the properties pbrt's filters_test checks (zero past
// the radius, unit integral by quadrature, samples whose weighted distribution is the filter),
// each filter's defining formula, and whole renders in both reconstructions (docs/filters.md).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>
#include <random>
#include <tuple>
#include <vector>

#include "core/render/render_job.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"

namespace fb {
namespace {

std::string test_name(std::string text) {
  for (char& c : text)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return text;
}

class FilterTest : public ::testing::TestWithParam<std::string> {};

TEST_P(FilterTest, IsZeroPastItsRadius) {
  const auto filter = test::make_filter(GetParam());
  float r[2];
  filter->radius(r);
  for (float t : {1.0001f, 1.1f, 2.f, 10.f}) {
    EXPECT_EQ(filter->evaluate(r[0] * t, 0.f), 0.f);
    EXPECT_EQ(filter->evaluate(0.f, -r[1] * t), 0.f);
    EXPECT_EQ(filter->evaluate(r[0] * t, r[1] * t), 0.f);
  }
}

TEST_P(FilterTest, IntegratesToOneByQuadrature) {
  const auto filter = test::make_filter(GetParam());
  float r[2];
  filter->radius(r);
  // Midpoint rule on a fine grid over the support (error ~ (h/r)^2 for smooth filters; the box
  // has its edges on grid lines). The issue asks for 1e-3; this holds 1e-4.
  const int n = 2000;
  double sum = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      sum += filter->evaluate(-r[0] + (i + 0.5f) * 2 * r[0] / n, -r[1] + (j + 0.5f) * 2 * r[1] / n);
  const double integral = sum * (2.0 * r[0] / n) * (2.0 * r[1] / n);
  EXPECT_NEAR(integral, 1.0, 1e-4);
  EXPECT_NEAR(filter->integral(), integral, 1e-4);
}

struct Sampled {
  std::vector<fb_filter_sample> samples;
  float r[2];
};

Sampled draw(const FilterInstance& filter, size_t n) {
  Sampled s;
  filter.radius(s.r);
  std::vector<float> u(2 * n);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.f, 0.99999994f);
  for (float& x : u)
    x = uniform(rng);
  s.samples.resize(n);
  filter.sample(u, s.samples.data());
  return s;
}

TEST_P(FilterTest, SampleWeightsAreUnbiasedForTheFilter) {
  // E[w g(X)] over sampled X equals the integral of h g for any test function g. The tolerance is
  // 4 standard errors of the sample mean (zero for exactly sampled filters, 2.5e-3 for Lanczos'
  // signed weights) plus 1e-4 for the quadrature of the exact value.
  const auto filter = test::make_filter(GetParam());
  constexpr size_t n = 400000;
  const Sampled s = draw(*filter, n);
  const float* r = s.r;
  auto g = [&](double x, double y) { return 1.0 + x * x / (r[0] * r[0]) + 0.5 * y; };
  double estimate = 0, estimate2 = 0, weight_sum = 0, weight2_sum = 0;
  for (const fb_filter_sample& sample : s.samples) {
    ASSERT_LE(std::abs(sample.x), r[0]);
    ASSERT_LE(std::abs(sample.y), r[1]);
    const double wg = sample.weight * g(sample.x, sample.y);
    estimate += wg, estimate2 += wg * wg;
    weight_sum += sample.weight, weight2_sum += double(sample.weight) * sample.weight;
  }
  const auto standard_error = [](double sum, double sum2) {
    return std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)) / n);
  };
  double exact = 0;  // quadrature of h g
  const int m = 1000;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      const double x = -r[0] + (i + 0.5) * 2 * r[0] / m, y = -r[1] + (j + 0.5) * 2 * r[1] / m;
      exact += filter->evaluate(float(x), float(y)) * g(x, y);
    }
  exact *= (2.0 * r[0] / m) * (2.0 * r[1] / m);
  EXPECT_NEAR(weight_sum / n, 1.0, 4 * standard_error(weight_sum, weight2_sum) + 1e-4);
  EXPECT_NEAR(estimate / n, exact, 4 * standard_error(estimate, estimate2) + 1e-4);
}

TEST_P(FilterTest, WeightsHaveTheSignOfTheFilterAndANearlyConstantSize) {
  // Sampling proportional to |h| makes |w| = integral of |h| everywhere; the tabulated samplers'
  // linear pieces miss that by at most 0.2 % (measured; docs/filters.md), well inside 1 %, where
  // the constant pieces of the first table reached 6.4 times. A sample in a negative lobe must
  // subtract.
  const auto filter = test::make_filter(GetParam());
  const Sampled s = draw(*filter, 100000);
  double abs_sum = 0, max_abs = 0;
  size_t negative = 0;
  for (const fb_filter_sample& sample : s.samples) {
    const float h = filter->evaluate(sample.x, sample.y);
    if (h != 0.f) {
      ASSERT_EQ(sample.weight < 0.f, h < 0.f) << sample.x << "," << sample.y;
    }
    abs_sum += std::abs(sample.weight);
    max_abs = std::max(max_abs, double(std::abs(sample.weight)));
    negative += sample.weight < 0.f;
  }
  EXPECT_LE(max_abs, 1.01 * abs_sum / s.samples.size());
  if (negative == 0) {
    EXPECT_NEAR(abs_sum / s.samples.size(), 1.0, 1e-3);
  }
}

INSTANTIATE_TEST_SUITE_P(Plugins, FilterTest,
                         ::testing::Values("box", "box:radius=1.5", "gaussian",
                                           "gaussian:radius=2,sigma=0.8", "triangle",
                                           "triangle:radius=2.5", "mitchell", "mitchell:b=0,c=0.5",
                                           "mitchell:radius=3,b=1,c=0", "lanczos",
                                           "lanczos:radius=4,tau=3", "lanczos:radius=2,tau=2",
                                           "blackman_harris", "blackman_harris:width=2.5"),
                         [](const auto& info) { return test_name(info.param); });

// Each filter's profile h(x, 0) / h(0, 0) against the formula that defines it.
double profile(const FilterInstance& filter, double x) {
  return filter.evaluate(float(x), 0.f) / filter.evaluate(0.f, 0.f);
}

TEST(FilterProfile, TriangleIsTheTent) {
  const auto filter = test::make_filter("triangle:radius=2");
  for (double x : {0.25, 0.5, 1.0, 1.5, 1.9})
    EXPECT_NEAR(profile(*filter, x), 1 - x / 2, 1e-6) << x;
  EXPECT_NEAR(filter->evaluate(0.5f, -1.f), (1.5 * 1.0) / 16, 1e-7);  // (r - |x|)(r - |y|) / r^4
}

TEST(FilterProfile, MitchellCubicsSumToOneOverIntegerShifts) {
  // Mitchell & Netravali's family is a partition of unity for every B, C: sum_i k(x + i) = 1.
  // With radius 2 the filter is k(x) k(y) itself, so sum_i h(x + i, 0) = k(0) = (6 - 2B) / 6.
  for (auto [spec, b] : {std::pair{"mitchell", 1 / 3.0},
                         {"mitchell:b=0,c=0.5", 0.0},
                         {"mitchell:b=1,c=0", 1.0},
                         {"mitchell:b=0.2,c=0.7", 0.2}}) {
    const auto filter = test::make_filter(spec);
    for (double x : {0.0, 0.1, 0.37, 0.5, 0.81}) {
      double sum = 0;
      for (int i = -3; i <= 3; ++i)
        sum += filter->evaluate(float(x + i), 0.f);
      EXPECT_NEAR(sum, (6 - 2 * b) / 6, 1e-6) << spec << " at " << x;
    }
  }
  // Catmull-Rom (B = 0, C = 1/2) interpolates: 1 at 0, 0 at the other integers.
  const auto catmull_rom = test::make_filter("mitchell:b=0,c=0.5");
  EXPECT_NEAR(catmull_rom->evaluate(0.f, 0.f), 1.0, 1e-6);
  EXPECT_NEAR(catmull_rom->evaluate(1.f, 0.f), 0.0, 1e-7);
  EXPECT_LT(catmull_rom->evaluate(1.5f, 0.f), 0.f);  // its negative lobe
}

TEST(FilterProfile, LanczosIsTheWindowedSinc) {
  const auto filter = test::make_filter("lanczos");  // radius 3, tau 3
  for (double x : {1.0, 2.0})
    EXPECT_NEAR(profile(*filter, x), 0.0, 1e-7) << x;
  const double pi = std::numbers::pi;
  for (double x : {0.5, 1.5, 2.5})  // sinc(x) sinc(x / 3)
    EXPECT_NEAR(profile(*filter, x),
                std::sin(pi * x) / (pi * x) * std::sin(pi * x / 3) / (pi * x / 3), 1e-6)
        << x;
  EXPECT_LT(profile(*filter, 1.5), 0.0);
}

TEST(FilterProfile, BlackmanHarrisIsCyclesFilterWithHalfWidthWidth) {
  // Cycles: filter_func_blackman_harris(v, 2 w) over v in [-w, w]. At v = 0 the window is
  // a0 + a1 + a2 + a3 = 1, at v = +-w/2 it is a0 - a2, and at the ends a0 - a1 + a2 - a3.
  const double a0 = 0.35875, a1 = 0.48829, a2 = 0.14128, a3 = 0.01168;
  for (double w : {1.5, 2.5}) {
    const auto filter = test::make_filter("blackman_harris:width=" + std::to_string(w));
    EXPECT_NEAR(profile(*filter, w / 2), a0 - a2, 1e-6);
    EXPECT_NEAR(profile(*filter, -w), a0 - a1 + a2 - a3, 1e-6);
    EXPECT_NEAR(filter->evaluate(0.f, 0.f), 1 / std::pow(2 * w * a0, 2), 1e-6);  // N = 2 w a0
    EXPECT_EQ(filter->evaluate(float(w) * 1.001f, 0.f), 0.f);
  }
}

// Whole renders: an emissive wall, filling the view or ending at a vertical edge, seen through
// each filter in both reconstructions.
using test::GltfBuilder;

struct WallShot {
  static constexpr uint32_t kWidth = 48, kHeight = 32;
  static constexpr double kYfov = 1.0, kDepth = 5.0;
  Rgb emission{0.25f, 1.5f, 3.f};
  Scene scene;
  // A wall at depth 5 m covering x < edge_m (all of the view if edge_m is large).
  explicit WallShot(double edge_m = 100) {
    GltfBuilder gltf;
    GltfBuilder::Node wall;
    const float z = float(-kDepth), e = float(edge_m);
    wall.mesh = gltf.mesh({{-100, -100, z}, {e, -100, z}, {e, 100, z}, {-100, 100, z}},
                          {0, 1, 2, 0, 2, 3}, gltf.material({0, 0, 0}, emission / 4.f, 4.0));
    gltf.node(wall);
    GltfBuilder::Node camera;
    camera.camera = gltf.perspective_camera(kYfov, double(kWidth) / kHeight, 0.1, 100);
    gltf.node(camera);
    Diagnostics diagnostics;
    scene = import_gltf(gltf.write(test::scratch_dir() / "wall.gltf"), diagnostics);
  }
  // The raster x at which world x lies on the wall: px = W/2 + f x / depth.
  static double focal_px() { return (kHeight / 2.0) / std::tan(kYfov / 2); }
  static double world_x(double raster_x) { return (raster_x - kWidth / 2.0) * kDepth / focal_px(); }

  Image render(const std::string& filter, Reconstruction reconstruction, uint32_t spp,
               uint64_t seed = 1) const {
    RenderOptions options;
    options.width = kWidth, options.height = kHeight, options.samples_per_pixel = spp;
    options.filter = filter, options.reconstruction = reconstruction, options.seed = seed;
    options.integrator = "path:max_depth=0";
    options.show_progress = false;
    const RenderJob job(scene, options, test::loader());
    const RenderResult result = job.run();
    EXPECT_EQ(result.stats.dropped_samples, 0u);
    return result.image;
  }
};

class FilterRenderTest : public ::testing::TestWithParam<std::tuple<std::string, Reconstruction>> {
};

TEST_P(FilterRenderTest, ConstantImageStaysConstant) {
  // Both estimators divide by the sum of the weights they applied (sum w L / sum w), so a
  // constant L comes back exactly up to rounding: float weights times float radiance are exact in
  // double, the double sums round at 1e-16 times sum |w| / |sum w| (below 1e3 even at 4 spp of
  // Lanczos' signed weights), and the result is rounded to float (6e-8). 1e-6 bounds all of it; a
  // pixel the splats missed, or a weight applied to L and not to the sum, shows as an error of
  // order 1.
  const auto& [filter, reconstruction] = GetParam();
  static const WallShot shot;
  const Image image = shot.render(filter, reconstruction, 4);
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(image.at(x, y, c), shot.emission[c], 1e-6 * shot.emission[c]) << x << "," << y;
}

TEST_P(FilterRenderTest, EdgeIsTheFiltersStepResponse) {
  // The wall ends at raster x = e, so pixel column i sees L times the filter's 1-D profile
  // integrated over t < e - (i + 0.5): the step response, found here by quadrature of evaluate().
  // A sampling or splatting offset of a fraction of a pixel moves the whole profile. Each column's
  // mean over the 32 rows is checked within 4 standard errors (from the rows' spread) plus 0.002
  // L for the ratio estimator's O(1/n) bias; columns the filter does not reach are exact.
  const auto& [filter, reconstruction] = GetParam();
  const double edge_px = 20.3;
  static const WallShot shot(WallShot::world_x(edge_px));
  const Image image = shot.render(filter, reconstruction, 256);
  const auto plugin = test::make_filter(filter);
  float r[2];
  plugin->radius(r);
  const int n = 20000;
  std::vector<double> cumulative(n + 1, 0.0);  // of h(t, 0) over [-r, -r + 2r k / n]
  for (int k = 0; k < n; ++k)
    cumulative[k + 1] =
        cumulative[k] + plugin->evaluate(float(-r[0] + (k + 0.5) * 2 * r[0] / n), 0.f);
  const auto step = [&](double t) {
    const double k = std::clamp((t + r[0]) / (2 * r[0]) * n, 0.0, double(n));
    return cumulative[size_t(std::floor(k))] / cumulative[n];  // grid error < 2r / n of the mass
  };
  const float emission = shot.emission[1];
  for (uint32_t x = 0; x < image.width; ++x) {
    double sum = 0, sum2 = 0;
    for (uint32_t y = 0; y < image.height; ++y) {
      const double v = image.at(x, y, 1);
      sum += v, sum2 += v * v;
    }
    const double rows = image.height, mean = sum / rows;
    const double standard_error = std::sqrt(std::max(0.0, sum2 / rows - mean * mean) / rows);
    const double expected = emission * step(edge_px - (x + 0.5));
    EXPECT_NEAR(mean, expected, 4 * standard_error + 2e-3 * emission) << "column " << x;
    EXPECT_LT(standard_error, 0.02 * emission) << "column " << x << ": too noisy to test";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Plugins, FilterRenderTest,
    ::testing::Combine(::testing::Values("box", "triangle", "gaussian", "mitchell", "lanczos",
                                         "blackman_harris"),
                       ::testing::Values(Reconstruction::kImportance, Reconstruction::kSplat)),
    [](const auto& info) {
      return test_name(std::get<0>(info.param)) + "_" +
             reconstruction_name(std::get<1>(info.param));
    });

TEST(SplatRender, IsBitIdenticalForAnyThreadCount) {
  // Samples splat across tile borders; the tiles' sums are merged in tile order.
  const WallShot shot(WallShot::world_x(16.4));  // an edge beside the border of the first tiles
  std::vector<float> pixels[2];
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    pixels[threads - 1] = shot.render("lanczos", Reconstruction::kSplat, 3, 5).pixels;
  }
  EXPECT_EQ(pixels[0], pixels[1]);
}

}  // namespace
}  // namespace fb
