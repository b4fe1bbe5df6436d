// The root solver (core/math/polynomial.h) up to degree 15 on the cases that break naive ones:
// many roots, roots close together, multiple roots, roots spread over many orders of magnitude.
// Each polynomial is built from its roots, so the roots it must find are known; where the
// product's coefficients are rounded, the tolerance is the error of evaluating it near the root
// over its slope there (the root's condition), stated case by case.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/math/polynomial.h"

namespace fb {
namespace {

// The coefficients (lowest first) of the product of (t - root) over the roots.
std::vector<double> from_roots(const std::vector<double>& roots) {
  std::vector<double> c{1};
  for (double root : roots) {
    std::vector<double> next(c.size() + 1, 0);
    for (size_t i = 0; i < c.size(); ++i) {
      next[i + 1] += c[i];
      next[i] -= root * c[i];
    }
    c = next;
  }
  return c;
}

std::vector<double> solve(const std::vector<double>& c, double lo, double hi) {
  std::vector<double> roots(c.size());
  const int n = sign_changes(c.data(), int(c.size()) - 1, lo, hi, roots.data());
  roots.resize(n);
  return roots;
}

TEST(PolynomialRoots, WilkinsonDegreeFifteenHasEveryIntegerRoot) {
  // (t - 1) ... (t - 15): integer coefficients below 2^53, so exact in doubles; its roots are
  // exactly 1 to 15. Near root k, Horner's rule errs by at most ~2 degree ulps of
  // sum_i |c_i| k^i, and the slope there is prod_{j != k} |k - j|: their ratio (with a factor 2
  // of margin) bounds how far the found root can be, computed for each root.
  std::vector<double> expected;
  for (int k = 1; k <= 15; ++k)
    expected.push_back(k);
  const std::vector<double> c = from_roots(expected);
  const std::vector<double> roots = solve(c, 0, 20);
  ASSERT_EQ(roots.size(), expected.size());
  for (size_t i = 0; i < roots.size(); ++i) {
    const double k = expected[i];
    double terms = 0, slope = 1;
    for (size_t j = 0; j < c.size(); ++j)
      terms += std::abs(c[j]) * std::pow(k, double(j));
    for (double other : expected)
      if (other != k) slope *= std::abs(k - other);
    const double bound = 2 * 2 * 15 * 1.1e-16 * terms / slope;
    EXPECT_NEAR(roots[i], k, bound) << "root " << k;
  }
}

TEST(PolynomialRoots, CloseRootsAreToldApart) {
  // Two roots 1e-6 apart among others: both found, in order, each to within the rounding of the
  // coefficients (1e-16 over a slope of ~1e-6 times the others' distances: ~1e-9).
  const std::vector<double> expected{-3, 0.5, 1, 1 + 1e-6, 2, 7};
  const std::vector<double> roots = solve(from_roots(expected), -10, 10);
  ASSERT_EQ(roots.size(), expected.size());
  for (size_t i = 0; i < roots.size(); ++i)
    EXPECT_NEAR(roots[i], expected[i], 1e-9) << i;
  EXPECT_LT(roots[2], roots[3]);
}

TEST(PolynomialRoots, MultipleRootsReportOnlySignChanges) {
  // (t - 1)^2 (t - 2)^3 (t + 1) (t - 4)^4: the double and fourfold roots only touch zero; the
  // triple root and the simple one change the sign. A triple root's position is good to the cube
  // root of the rounding (~1e-5).
  const std::vector<double> c = from_roots({1, 1, 2, 2, 2, -1, 4, 4, 4, 4});
  const std::vector<double> roots = solve(c, -5, 5);
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_NEAR(roots[0], -1, 1e-12);
  EXPECT_NEAR(roots[1], 2, 1e-4);
}

TEST(PolynomialRoots, RootsOverTwelveOrdersOfMagnitude) {
  // Roots from 1e-6 to 1e6, coefficients from 1 to ~1e12: roots this far apart are well
  // conditioned, each found to a relative 1e-12.
  const std::vector<double> expected{1e-6, 1e-4, 1e-2, 1, 1e2, 1e4, 1e6};
  const std::vector<double> roots = solve(from_roots(expected), -1e-7, 1e7);
  ASSERT_EQ(roots.size(), expected.size());
  for (size_t i = 0; i < roots.size(); ++i)
    EXPECT_NEAR(roots[i], expected[i], 1e-12 * expected[i]) << i;
}

TEST(PolynomialRoots, OnlyTheRootsInsideTheIntervalAndNoneOfAConstant) {
  const std::vector<double> c = from_roots({-2, -1, 0.25, 3, 5, 8, 9, 11, 12, 13, 14});
  const std::vector<double> roots = solve(c, 0, 6);
  ASSERT_EQ(roots.size(), 3u);
  EXPECT_NEAR(roots[0], 0.25, 1e-10);
  EXPECT_NEAR(roots[2], 5, 1e-10);
  const double constant[1] = {2};
  double none[1];
  EXPECT_EQ(sign_changes(constant, 0, -1, 1, none), 0);
}

TEST(PolynomialRoots, RestrictionToARayOfADegreeFifteenPolynomial) {
  // x^15 + x^5 y^4 z^6 - 3 y^2 + 1 along o + t d: the substitution agrees with evaluating the
  // polynomial at points of the ray (to the rounding of terms of ~|o + t d|^15 ~ 1e4).
  const Polynomial3 p{{1, 15, 0, 0}, {1, 5, 4, 6}, {-3, 0, 2, 0}, {1, 0, 0, 0}};
  const Vec3d o{0.3, -0.8, 0.6}, d{0.5, 0.25, -0.4};
  double c[kMaxPolynomialDegree + 1];
  restrict_to_ray(p, o, d, c);
  for (double t : {-1.5, -0.25, 0.0, 0.7, 1.5}) {
    const double expected = evaluate_polynomial3(p, o + d * t);
    EXPECT_NEAR(evaluate_polynomial(c, kMaxPolynomialDegree, t), expected,
                1e-12 * (1 + std::abs(expected)))
        << t;
  }
  EXPECT_EQ(polynomial3_degree(p), 15);
}

}  // namespace
}  // namespace fb
