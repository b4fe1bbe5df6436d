#include "core/cmd/bench_seeds.h"

#include <gtest/gtest.h>

namespace fb {
namespace {

RenderRow row(double rmse, double render_s, std::optional<double> against_cycles) {
  RenderRow r;
  r.configuration = "sobol, box";
  r.spp = 16;
  r.own.error.rmse = rmse;
  r.render_s = render_s;
  r.total_s = render_s + 1;
  if (against_cycles) r.cycles_reference = MeasuredError{{}, std::nullopt};
  if (against_cycles) r.cycles_reference->error.rmse = *against_cycles;
  return r;
}

// A firefly in one seed (RMSE 9) moves the median by nothing and shows in the spread.
TEST(BenchSeeds, MedianSeedWithSpreadKeepsAFireflyOut) {
  const RenderRow r = combine_seeds({row(0.2, 3, 0.4), row(9, 1, 0.3), row(0.1, 2, 8)});
  EXPECT_EQ(r.seeds, 3u);
  EXPECT_DOUBLE_EQ(r.own.error.rmse, 0.2);
  EXPECT_DOUBLE_EQ(r.rmse_spread.first, 0.1);
  EXPECT_DOUBLE_EQ(r.rmse_spread.second, 9);
  EXPECT_DOUBLE_EQ(r.render_s, 2);
  EXPECT_DOUBLE_EQ(r.total_s, 3);
  // Against Cycles' reference the median is taken on its own RMSE: another seed's.
  ASSERT_TRUE(r.cycles_reference && r.cycles_reference_rmse_spread);
  EXPECT_DOUBLE_EQ(r.cycles_reference->error.rmse, 0.4);
  EXPECT_DOUBLE_EQ(r.cycles_reference_rmse_spread->second, 8);
}

TEST(BenchSeeds, EvenCountTakesTheLowerMiddleErrorAndTheMeanMiddleTime) {
  const RenderRow r =
      combine_seeds({row(0.4, 4, {}), row(0.3, 1, {}), row(0.2, 2, {}), row(0.1, 3, {})});
  EXPECT_DOUBLE_EQ(r.own.error.rmse, 0.2);
  EXPECT_DOUBLE_EQ(r.render_s, 2.5);
  EXPECT_FALSE(r.cycles_reference);
}

TEST(BenchSeeds, ConfigurationNamesSayTheThreshold) {
  EXPECT_EQ(configuration_name("cycles", 0), "cycles");
  EXPECT_EQ(configuration_name("sobol, box", 0.01), "sobol, box, adaptive 0.01");
}

}  // namespace
}  // namespace fb
