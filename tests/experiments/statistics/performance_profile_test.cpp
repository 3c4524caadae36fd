// Performance profiles on hand-made scores.
#include "experiments/statistics/performance_profile.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace bsg::experiments {
namespace {

TEST(PerformanceProfile, EachStratumCountsWithTheSameWeight) {
  // Stratum 1 {0.5, 1.5}: above 0 all, above 1 half, above 2.5 none.
  // Stratum 2 {1, 2, 3, 4}: above 0 all, above 1 three quarters (1 is not above 1), above 2.5 half.
  // Profile: (1 + 1) / 2 = 1, (0.5 + 0.75) / 2 = 0.625, (0 + 0.5) / 2 = 0.25.
  const Strata scores{{0.5, 1.5}, {1.0, 2.0, 3.0, 4.0}};
  const std::vector<double> taus{0.0, 1.0, 2.5};
  const std::vector<double> profile = profile_fractions(scores, taus);
  ASSERT_EQ(profile.size(), 3u);
  EXPECT_DOUBLE_EQ(profile[0], 1.0);
  EXPECT_DOUBLE_EQ(profile[1], 0.625);
  EXPECT_DOUBLE_EQ(profile[2], 0.25);
  const std::vector<IntervalEstimate> band = performance_profile(scores, taus, {});
  ASSERT_EQ(band.size(), 3u);
  EXPECT_DOUBLE_EQ(band[1].point, 0.625);
  // Every resample keeps stratum 1 above 0: the band at tau = 0 is [1, 1].
  EXPECT_DOUBLE_EQ(band[0].low, 1.0);
  EXPECT_LE(band[1].low, 0.625);
  EXPECT_GE(band[1].high, 0.625);
  EXPECT_GE(band[2].low, 0.0);
  EXPECT_LE(band[2].high, 0.5);  // at most stratum 2 all above 2.5 (1) and stratum 1 none (0): 0.5
}

TEST(PerformanceProfile, EvenlySpacedThresholdsIncludeBothEnds) {
  const std::vector<double> taus = evenly_spaced(-1.0, 1.0, 5);
  ASSERT_EQ(taus.size(), 5u);
  EXPECT_DOUBLE_EQ(taus[0], -1.0);
  EXPECT_DOUBLE_EQ(taus[2], 0.0);
  EXPECT_DOUBLE_EQ(taus[4], 1.0);
  EXPECT_THROW(evenly_spaced(1.0, 1.0, 5), std::invalid_argument);
  EXPECT_THROW(evenly_spaced(0.0, 1.0, 1), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::experiments
