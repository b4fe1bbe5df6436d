#include "core/cmd/bench_analysis.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fb {
namespace {

// Rows whose errors follow known power laws of the render time, RMSE = a t^-1/2, at 1..256 spp:
// every fit and time below follows by hand.
struct Law {
  double a = 0;
  std::optional<double> noise;
};

void add_rows(SceneReport& scene, const std::string& renderer, const std::string& configuration,
              double s_per_spp, double fixed_s, Law own, std::optional<Law> cycles) {
  for (uint32_t spp = 1; spp <= 256; spp *= 2) {
    RenderRow row;
    row.renderer = renderer;
    row.configuration = configuration;
    row.spp = spp;
    row.render_s = s_per_spp * spp;
    row.total_s = row.render_s + fixed_s;
    const auto measured = [&](const Law& law) {
      const double rmse = law.a / std::sqrt(row.render_s);
      return MeasuredError{{rmse, rmse * rmse, 10 * rmse}, law.noise};
    };
    row.own = measured(own);
    if (cycles) row.cycles_reference = measured(*cycles);
    scene.rows.push_back(row);
  }
}

// filmback "sobol" measured against both references, "box" only against its own, and Cycles,
// whose own reference is Cycles' reference.
SceneReport two_renderers() {
  SceneReport scene;
  // Cycles' reference's own RMSE: filmback's 256-spp render against it (0.3 / sqrt(2.56)) is
  // under 3x that, so it is not fitted on Cycles' reference; its 128-spp one is.
  const double cycles_noise = 0.3 / std::sqrt(2.56) / 2.9;
  add_rows(scene, "filmback", "sobol", 0.01, 0.05, {0.4, 1e-4}, Law{0.3, cycles_noise});
  add_rows(scene, "filmback", "box", 0.01, 0.05, {0.5, 1e-4}, std::nullopt);
  add_rows(scene, "cycles", "cycles", 0.02, 1.0, {0.2, 1e-4}, Law{0.2, 1e-4});
  return scene;
}

TEST(BenchAnalysis, CyclesReferenceIsPrimaryWhereMeasured) {
  SceneReport scene = two_renderers();
  EXPECT_EQ(primary_reference(scene), ReferenceKind::kCycles);
  for (RenderRow& row : scene.rows)
    row.cycles_reference.reset();
  EXPECT_EQ(primary_reference(scene), ReferenceKind::kOwn);
}

TEST(BenchAnalysis, FitsTakeTheErrorsAgainstTheReferenceAsked) {
  const SceneReport scene = two_renderers();
  const std::vector<ConfigurationFit> own = fit_configurations(scene, ReferenceKind::kOwn);
  ASSERT_EQ(own.size(), 3u);
  EXPECT_NEAR(std::exp(own[0].by_render_s->intercept), 0.4, 1e-9);
  EXPECT_EQ(own[0].fitted, 9u);

  // "box" has no error against Cycles' reference, so it has no fit there.
  const std::vector<ConfigurationFit> common = fit_configurations(scene, ReferenceKind::kCycles);
  ASSERT_EQ(common.size(), 2u);
  EXPECT_EQ(common[0].configuration, "sobol");
  EXPECT_EQ(common[1].renderer, "cycles");
  EXPECT_EQ(common[0].reference, ReferenceKind::kCycles);
  EXPECT_NEAR(common[0].by_render_s->slope, -0.5, 1e-9);
  EXPECT_NEAR(std::exp(common[0].by_render_s->intercept), 0.3, 1e-9);
  EXPECT_NEAR(common[0].relmse_by_render_s->slope, -1.0, 1e-9);
  EXPECT_EQ(common[0].fitted, 8u);  // the 256-spp render is within 3x the reference's noise
  EXPECT_NEAR(common[0].by_render_s->x_max, 1.28, 1e-12);
  EXPECT_NEAR(common[0].fixed_s, 0.05, 1e-12);
  EXPECT_NEAR(common[1].fixed_s, 1.0, 1e-12);
  // The target: the largest RMSE at the highest spp, filmback's 0.3 / sqrt(2.56).
  EXPECT_NEAR(default_target(common, std::nullopt).rmse, 0.3 / 1.6, 1e-12);
}

// Cycles at 256 spp (5.12 s render): RMSE 0.2 / sqrt(5.12). filmback's line 0.3 / sqrt(t) reaches
// it at t = 5.12 (0.3 / 0.2)² = 11.52 s against Cycles' reference, and 0.4 / sqrt(t) at
// 5.12 x 4 = 20.48 s against its own; its relMSE line (a² / t) at the same times.
TEST(BenchAnalysis, TimeToCyclesErrorOnEachReference) {
  const SceneReport scene = two_renderers();
  const std::vector<ConfigurationFit> common = fit_configurations(scene, ReferenceKind::kCycles);
  const RenderRow* cycles = cycles_reference_render(common);
  ASSERT_NE(cycles, nullptr);
  EXPECT_EQ(cycles->spp, kCyclesGoalSpp);
  const double goal = cycles->own.error.rmse;
  EXPECT_NEAR(goal, 0.2 / std::sqrt(5.12), 1e-12);

  const TimeToError t = time_to_error(common[0], goal);
  EXPECT_NEAR(*t.render_s, 11.52, 1e-9);
  EXPECT_NEAR(*t.total_s, 11.57, 1e-9);
  EXPECT_TRUE(t.extrapolated);  // beyond the 1.28 s of the last render fitted
  EXPECT_NEAR(*time_to_relmse(common[0], cycles->own.error.relmse).render_s, 11.52, 1e-9);

  const std::vector<ConfigurationFit> own = fit_configurations(scene, ReferenceKind::kOwn);
  EXPECT_NEAR(*time_to_error(own[0], goal).render_s, 20.48, 1e-9);
  // Cycles on its own line reaches its own error at its own time.
  EXPECT_NEAR(*time_to_error(common[1], goal).render_s, 5.12, 1e-9);
}

}  // namespace
}  // namespace fb
