// The Wilson interval and the normal quantile against hand computation, and a
// seed summary against the statistics of its values.
#include "experiments/statistics/seed_summary.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace bsg::experiments {
namespace {

TEST(SeedSummary, NormalQuantileMatchesTheTables) {
  EXPECT_NEAR(standard_normal_quantile(0.975), 1.959963985, 1e-9);
  EXPECT_NEAR(standard_normal_quantile(0.5), 0.0, 1e-12);
  EXPECT_NEAR(standard_normal_quantile(0.05), -1.644853627, 1e-9);
}

TEST(SeedSummary, WilsonIntervalOfThreeOutOfThreeIsNotAPoint) {
  // k = n = 3, z = 1.959964: centre 1 + z^2/6 = 1.640243, spread z^2/6 = 0.640243,
  // scale 1 + z^2/3 = 2.280486: [1 / 2.280486, 1] = [0.438503, 1].
  const IntervalEstimate all = wilson_interval(3, 3, 0.95);
  EXPECT_DOUBLE_EQ(all.point, 1.0);
  EXPECT_NEAR(all.low, 0.438503, 1e-6);
  EXPECT_DOUBLE_EQ(all.high, 1.0);
  const IntervalEstimate none = wilson_interval(0, 3, 0.95);
  EXPECT_DOUBLE_EQ(none.low, 0.0);
  EXPECT_NEAR(none.high, 1.0 - 0.438503, 1e-6);
  // k = 1, n = 2, z^2 = 3.8414588: centre 0.5 + z^2/4 = 1.4603647, spread z sqrt(1/8 + z^2/16) =
  // 1.9599640 x 0.6042278 = 1.1842646, scale 1 + z^2/2 = 2.9207294: [0.0945312, 0.9054688].
  const IntervalEstimate half = wilson_interval(1, 2, 0.95);
  EXPECT_NEAR(half.low, 0.0945312, 1e-6);
  EXPECT_NEAR(half.high, 0.9054688, 1e-6);
  EXPECT_THROW(wilson_interval(0, 0, 0.95), std::invalid_argument);
  EXPECT_THROW(wilson_interval(4, 3, 0.95), std::invalid_argument);
}

TEST(SeedSummary, PointsAreTheStatisticsOfTheSeeds) {
  const SeedSummary summary = summarise_seeds(std::vector<double>{10, 1, 100, 2, 3}, {});
  EXPECT_EQ(summary.seeds, 5u);
  EXPECT_DOUBLE_EQ(summary.mean.point, 23.2);
  EXPECT_DOUBLE_EQ(summary.median.point, 3.0);
  EXPECT_DOUBLE_EQ(summary.iqm.point, 5.0);
  EXPECT_LE(summary.iqm.low, summary.iqm.high);
  EXPECT_THROW(summarise_seeds(std::vector<double>{1.0}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::experiments
