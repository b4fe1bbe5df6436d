#include "core/render/shutter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "core/util/error.h"

namespace fb {
namespace {

// The curves as their definitions state them, written independently of the implementation.
double trapezoid(double s, double ramp) {
  if (ramp == 0) return 1;
  return std::min({1.0, s / ramp, (1 - s) / ramp});
}

double table(double s, const std::vector<double>& w) {
  const double x = s * double(w.size() - 1);
  const size_t i = std::min(size_t(x), w.size() - 2);
  return w[i] + (x - double(i)) * (w[i + 1] - w[i]);
}

// Stratified samples u = (i + 1/2) / N through sample(), binned in s: each bin must hold the
// curve's share of the area, integrated by the midpoint rule (which is exact for a piecewise
// linear curve whose knots fall on sub-interval edges, and within 1e-8 otherwise), to within the
// one sample that stratification can move across a bin edge.
void expect_reproduces(const ShutterCurve& curve, const std::function<double(double)>& w,
                       const std::string& name) {
  constexpr int kSamples = 200000, kBins = 40, kSteps = 1000;
  std::vector<double> area(kBins, 0.0);
  double total = 0;
  for (int b = 0; b < kBins; ++b) {
    for (int k = 0; k < kSteps; ++k)
      area[b] += w((b + (k + 0.5) / kSteps) / kBins);
    total += area[b];
  }
  std::vector<int> count(kBins, 0);
  for (int i = 0; i < kSamples; ++i) {
    const double s = curve.sample((i + 0.5) / kSamples);
    ASSERT_GE(s, 0.0) << name;
    ASSERT_LE(s, 1.0) << name;
    ++count[std::min(int(s * kBins), kBins - 1)];
  }
  for (int b = 0; b < kBins; ++b)
    EXPECT_NEAR(double(count[b]) / kSamples, area[b] / total, 1.0 / kSamples + 1e-8)
        << name << ", bin " << b;
}

TEST(ShutterCurve, BoxIsTheIdentity) {
  const ShutterCurve box;
  EXPECT_EQ(box.description(), "box");
  for (double u : {0.0, 0x1p-24, 0.25, 0.3, 0.999999940395355})
    EXPECT_EQ(box.sample(u), u);
}

TEST(ShutterCurve, SamplesReproduceTheCurve) {
  for (double ramp : {0.0, 0.1, 0.25, 0.5}) {
    const std::string text = "trapezoid:ramp=" + number_text(ramp);
    expect_reproduces(
        ShutterCurve::parse(text, "--shutter-curve"), [&](double s) { return trapezoid(s, ramp); },
        text);
  }
  expect_reproduces(
      ShutterCurve::parse("trapezoid", "--shutter-curve"),
      [](double s) { return trapezoid(s, 0.25); }, "trapezoid (default ramp)");
  for (const std::vector<double>& w : std::vector<std::vector<double>>{
           {0, 1, 1, 0.5}, {1, 0, 0, 3}, {2, 2}, {0, 0, 5, 0, 0, 1, 1, 1}}) {
    std::string text = "table:values=";
    for (size_t i = 0; i < w.size(); ++i) {
      text += i ? ',' : '[';
      text += number_text(w[i]);
    }
    text += ']';
    expect_reproduces(
        ShutterCurve::parse(text, "--shutter-curve"), [&](double s) { return table(s, w); }, text);
  }
}

TEST(ShutterCurve, SampleInvertsTheCdf) {
  for (const char* text :
       {"box", "trapezoid:ramp=0.3", "table:values=[0,1,1,0.5]", "table:values=[1,0,0,3]"}) {
    const ShutterCurve curve = ShutterCurve::parse(text, "--shutter-curve");
    for (int i = 0; i <= 1000; ++i) {
      const double u = i / 1000.0;
      EXPECT_NEAR(curve.cdf(curve.sample(u)), u, 1e-12) << text << " at u = " << u;
    }
  }
}

TEST(ShutterCurve, BadTextIsAUsageErrorNamingTheOption) {
  for (const char* bad :
       {"circle", "box:ramp=0.1", "trapezoid:ramp=0.7", "trapezoid:ramp=-1", "trapezoid:width=1",
        "table", "table:values=[1]", "table:values=[0,0]", "table:values=[1,-1]",
        "table:values=[1,x]", "table:values=1,2", "table:values=[1,2"}) {
    try {
      ShutterCurve::parse(bad, "--shutter-curve");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find("--shutter-curve '"), std::string::npos) << e.what();
    }
  }
}

// A scene's sampled curve is used as it is: 1/3 stays 1/3 (printed with %g it was 0.333333, which
// moves the CDF by 1e-7). For w(s) = 1/3 + 2s/3 the area to s = 1/2 is 1/6 + 1/12 = 1/4 of the
// total 2/3: cdf(1/2) = 3/8.
TEST(ShutterCurve, TableFromTypedValuesIsExactAndRefusesWhatParseRefuses) {
  const std::optional<ShutterCurve> curve = ShutterCurve::table({1.0 / 3, 1});
  ASSERT_TRUE(curve);
  EXPECT_NEAR(curve->cdf(0.5), 3.0 / 8, 1e-15);
  EXPECT_FALSE(ShutterCurve::table({1}));
  EXPECT_FALSE(ShutterCurve::table({0, 0}));
  EXPECT_FALSE(ShutterCurve::table({1, -1}));
  EXPECT_FALSE(ShutterCurve::table(std::vector<double>(ShutterCurve::kMaxTableValues + 1, 1)));
}

// Cycles' rows (kernel/camera/camera.h): r = 1 - y / H with y counted from the bottom row, so the
// top row (y = H - 1) is read at 1 / H and the bottom one at 1; the duration d blends in the
// shutter's own time s.
TEST(RollingShutter, RowsAreReadTopToBottomAndTheDurationBlendsInTheShuttersTime) {
  const RollingShutter instant{0};
  EXPECT_DOUBLE_EQ(instant.fraction(0.9, 0, 4), 0.25);
  EXPECT_DOUBLE_EQ(instant.fraction(0.1, 3, 4), 1.0);
  EXPECT_DOUBLE_EQ(instant.fraction(0.5, -2, 4), 0.25);  // splatting's rows beyond the film
  EXPECT_DOUBLE_EQ(instant.fraction(0.5, 7, 4), 1.0);
  const RollingShutter global{1};
  EXPECT_DOUBLE_EQ(global.fraction(0.3, 0, 4), 0.3);
  const RollingShutter cycles{0.1};
  EXPECT_DOUBLE_EQ(cycles.fraction(0.8, 1, 4), 0.5 + 0.1 * (0.8 - 0.5) + 0.9 * (0.5 - 0.5));
  EXPECT_DOUBLE_EQ(cycles.fraction(0.0, 0, 4), 0.5 + 0.1 * -0.5 + 0.9 * (0.25 - 0.5));
}

}  // namespace
}  // namespace fb
