// Mean, median, IQM and the type-7 quantile against values worked out by hand
// (the IQM as scipy.stats.trim_mean(x, 0.25), which rliable uses).
#include "experiments/statistics/robust_statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace bsg::experiments {
namespace {

TEST(RobustStatistics, InterquartileMeanCutsAQuarterOfTheValuesFromEachEnd) {
  // n = 8: floor(8 / 4) = 2 cut from each end -> mean of 3, 4, 5, 6 = 4.5.
  EXPECT_DOUBLE_EQ(interquartile_mean(std::vector<double>{8, 1, 7, 2, 6, 3, 5, 4}), 4.5);
  // n = 5: one cut from each end of 1, 2, 3, 10, 100 -> (2 + 3 + 10) / 3 = 5.
  EXPECT_DOUBLE_EQ(interquartile_mean(std::vector<double>{10, 1, 100, 2, 3}), 5.0);
  // n = 3: floor(3 / 4) = 0, nothing is cut: the mean (1 + 2 + 9) / 3 = 4.
  EXPECT_DOUBLE_EQ(interquartile_mean(std::vector<double>{1, 2, 9}), 4.0);
  // n = 4: the lowest and the highest go: (2 + 3) / 2.
  EXPECT_DOUBLE_EQ(interquartile_mean(std::vector<double>{-50, 2, 3, 70}), 2.5);
}

TEST(RobustStatistics, MedianAndMeanOfSmallSets) {
  EXPECT_DOUBLE_EQ(median_of(std::vector<double>{3, 1, 2}), 2.0);
  EXPECT_DOUBLE_EQ(median_of(std::vector<double>{4, 1, 3, 2}), 2.5);
  EXPECT_DOUBLE_EQ(mean_of(std::vector<double>{4, 1, 3, 2}), 2.5);
  EXPECT_DOUBLE_EQ(point_statistic(PointStatistic::iqm, std::vector<double>{1, 2, 9}), 4.0);
}

TEST(RobustStatistics, QuantileInterpolatesBetweenOrderStatisticsAsNumpyDoes) {
  // numpy.percentile([1, 2, 3, 4], 25) = 1.75: position 0.25 * 3 = 0.75 between 1 and 2.
  EXPECT_DOUBLE_EQ(quantile_of(std::vector<double>{4, 3, 2, 1}, 0.25), 1.75);
  EXPECT_DOUBLE_EQ(quantile_of(std::vector<double>{4, 3, 2, 1}, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(quantile_of(std::vector<double>{4, 3, 2, 1}, 1.0), 4.0);
  EXPECT_DOUBLE_EQ(quantile_of(std::vector<double>{10, 20}, 0.975), 19.75);
  EXPECT_THROW(quantile_of(std::vector<double>{1, 2}, 1.5), std::invalid_argument);
}

TEST(RobustStatistics, FractionAboveIsStrict) {
  EXPECT_DOUBLE_EQ(fraction_above(std::vector<double>{1, 2, 3, 4}, 2.0), 0.5);
  EXPECT_DOUBLE_EQ(fraction_above(std::vector<double>{1, 2, 3, 4}, 0.0), 1.0);
}

TEST(RobustStatistics, EmptyInputAndNaNAreRefused) {
  EXPECT_THROW(mean_of(std::vector<double>{}), std::invalid_argument);
  EXPECT_THROW(interquartile_mean(std::vector<double>{1.0, std::numeric_limits<double>::quiet_NaN()}),
               std::invalid_argument);
  EXPECT_THROW(fraction_above(std::vector<double>{}, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace bsg::experiments
