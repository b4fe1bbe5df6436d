// Filter plugins through the ABI, against the properties pbrt's filters_test checks: zero past
// the radius, unit integral by quadrature, and samples whose weighted distribution is the filter.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "support/plugins.h"

namespace fb {
namespace {

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
  // has its edges on grid lines).
  const int n = 2000;
  double sum = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      sum += filter->evaluate(-r[0] + (i + 0.5f) * 2 * r[0] / n, -r[1] + (j + 0.5f) * 2 * r[1] / n);
  const double integral = sum * (2.0 * r[0] / n) * (2.0 * r[1] / n);
  EXPECT_NEAR(integral, 1.0, 1e-4);
  EXPECT_NEAR(filter->integral(), integral, 1e-4);
}

TEST_P(FilterTest, SampleWeightsAreUnbiasedForTheFilter) {
  // E[w g(X)] over sampled X equals the integral of h g for any test function g.
  const auto filter = test::make_filter(GetParam());
  float r[2];
  filter->radius(r);
  const size_t n = 400000;
  std::vector<float> u(2 * n);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.f, 0.99999994f);
  for (float& x : u)
    x = uniform(rng);
  std::vector<fb_filter_sample> samples(n);
  filter->sample(u, samples.data());
  auto g = [&](double x, double y) { return 1.0 + x * x / (r[0] * r[0]) + 0.5 * y; };
  double estimate = 0, weight_sum = 0;
  for (const fb_filter_sample& s : samples) {
    ASSERT_LE(std::abs(s.x), r[0]);
    ASSERT_LE(std::abs(s.y), r[1]);
    estimate += s.weight * g(s.x, s.y);
    weight_sum += s.weight;
  }
  estimate /= n;
  double exact = 0;  // quadrature of h g
  const int m = 1000;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      const double x = -r[0] + (i + 0.5) * 2 * r[0] / m, y = -r[1] + (j + 0.5) * 2 * r[1] / m;
      exact += filter->evaluate(float(x), float(y)) * g(x, y);
    }
  exact *= (2.0 * r[0] / m) * (2.0 * r[1] / m);
  EXPECT_NEAR(weight_sum / n, 1.0, 2e-3);
  EXPECT_NEAR(estimate, exact, 5e-3);
}

INSTANTIATE_TEST_SUITE_P(Plugins, FilterTest,
                         ::testing::Values("box", "box:radius=1.5", "gaussian",
                                           "gaussian:radius=2,sigma=0.8"),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace fb
