// The stratified bootstrap: resampling stays within strata, the percentile
// interval of a case small enough to enumerate, reproducibility from the seed,
// refusal of strata of one seed, and the coverage of the interval of a mean on
// synthetic normal data.
#include "experiments/statistics/stratified_bootstrap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace bsg::experiments {
namespace {

TEST(StratifiedBootstrap, AResampleKeepsEveryStratumsSizeAndDrawsOnlyFromIt) {
  const Strata strata{{1.0, 2.0}, {100.0, 200.0, 300.0}};
  Rng rng(7);
  for (int i = 0; i < 200; ++i) {
    const Strata resample = resample_strata(strata, rng);
    ASSERT_EQ(resample.size(), 2u);
    ASSERT_EQ(resample[0].size(), 2u);
    ASSERT_EQ(resample[1].size(), 3u);
    for (const double v : resample[0]) EXPECT_TRUE(v == 1.0 || v == 2.0);
    for (const double v : resample[1]) EXPECT_TRUE(v == 100.0 || v == 200.0 || v == 300.0);
  }
}

TEST(StratifiedBootstrap, StrataKeepTheirWeightSoThePooledMeanOfConstantStrataDoesNotMove) {
  // Resampling within strata {0, 0} and {10, 10} always gives 0, 0, 10, 10: the
  // pooled mean is 5 in every resample. (Resampling the four values together
  // would draw e.g. 0, 0, 0, 10 and spread the interval.)
  const IntervalEstimate estimate =
      stratified_bootstrap_interval({{0.0, 0.0}, {10.0, 10.0}}, pooled_statistic(PointStatistic::mean), {});
  EXPECT_DOUBLE_EQ(estimate.point, 5.0);
  EXPECT_DOUBLE_EQ(estimate.low, 5.0);
  EXPECT_DOUBLE_EQ(estimate.high, 5.0);
}

TEST(StratifiedBootstrap, PercentileIntervalOfTwoValuesIsTheirRange) {
  // The mean of a resample of {0, 1} is 0 (p 1/4), 0.5 (p 1/2) or 1 (p 1/4): its
  // 2.5 % and 97.5 % quantiles are 0 and 1 (with 4000 resamples, about 1000 of
  // them sit at each end, far more than the 100 below 2.5 %).
  BootstrapOptions options;
  options.resamples = 4000;
  const IntervalEstimate estimate =
      stratified_bootstrap_interval({{0.0, 1.0}}, pooled_statistic(PointStatistic::mean), options);
  EXPECT_DOUBLE_EQ(estimate.point, 0.5);
  EXPECT_DOUBLE_EQ(estimate.low, 0.0);
  EXPECT_DOUBLE_EQ(estimate.high, 1.0);
  // At 40 % the quantiles 0.3 and 0.7 both fall among the resamples at 0.5.
  options.confidence = 0.4;
  const IntervalEstimate narrow =
      stratified_bootstrap_interval({{0.0, 1.0}}, pooled_statistic(PointStatistic::mean), options);
  EXPECT_DOUBLE_EQ(narrow.low, 0.5);
  EXPECT_DOUBLE_EQ(narrow.high, 0.5);
}

TEST(StratifiedBootstrap, TheSameSeedGivesTheSameIntervalAndAnotherSeedAnother) {
  // Values far apart in scale, so that resample means hardly ever coincide.
  const Strata strata{{0.3, 1.7, 2.2, 5.1, 0.9, 13.3, 0.07}, {10.5, 12.0, 9.8, 31.4}};
  BootstrapOptions options;
  options.seed = 42;
  const IntervalEstimate a = stratified_bootstrap_interval(strata, pooled_statistic(PointStatistic::mean), options);
  const IntervalEstimate b = stratified_bootstrap_interval(strata, pooled_statistic(PointStatistic::mean), options);
  EXPECT_EQ(a.low, b.low);
  EXPECT_EQ(a.high, b.high);
  options.seed = 43;
  const IntervalEstimate c = stratified_bootstrap_interval(strata, pooled_statistic(PointStatistic::mean), options);
  EXPECT_TRUE(c.low != a.low || c.high != a.high);
}

TEST(StratifiedBootstrap, OneSeedIsRefusedNotGivenAnIntervalOfWidthZero) {
  try {
    stratified_bootstrap_interval({{1.0, 2.0}, {3.0}}, pooled_statistic(PointStatistic::mean), {});
    FAIL() << "a stratum of one value was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("stratum 1 has 1 value(s)"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("at least 2"), std::string::npos) << error.what();
  }
  EXPECT_THROW(stratified_bootstrap_interval({}, pooled_statistic(PointStatistic::mean), {}), std::invalid_argument);
}

TEST(StratifiedBootstrap, BadOptionsAreNamed) {
  BootstrapOptions options;
  options.resamples = 10;
  EXPECT_THROW(check_bootstrap_options(options), std::invalid_argument);
  options.resamples = 1000;
  options.confidence = 1.0;
  EXPECT_THROW(check_bootstrap_options(options), std::invalid_argument);
}

TEST(StratifiedBootstrap, DifferenceOfTwoGroupsExcludesZeroOnlyWhenTheyDiffer) {
  const StrataStatistic difference = difference_statistic(PointStatistic::mean);
  const IntervalEstimate apart = stratified_bootstrap_interval({{10.0, 11.0, 12.0}, {0.0, 1.0, 2.0}}, difference, {});
  EXPECT_DOUBLE_EQ(apart.point, 10.0);
  EXPECT_GT(apart.low, 0.0);  // at worst 10 - 2 = 8: every resample is positive
  const IntervalEstimate same = stratified_bootstrap_interval({{0.0, 1.0, 2.0}, {0.0, 1.0, 2.0}}, difference, {});
  EXPECT_LT(same.low, 0.0);
  EXPECT_GT(same.high, 0.0);
}

// Coverage: 1000 samples of 20 draws from N(0, 1), the 95 % percentile interval
// of the mean from 1000 resamples each, fixed seeds. The percentile interval
// rests on the plug-in variance (divided by n, not n - 1) and normal quantiles,
// so for n = 20 its coverage is close to P(|T_19| <= 1.96 sqrt(19 / 20)) =
// P(|T_19| <= 1.910) = 0.929, not 0.95 (Efron and Tibshirani 1993, ch. 13).
// Tolerance: 0.929 +- 0.03, about four binomial standard errors of 1000
// samples (sqrt(0.93 * 0.07 / 1000) = 0.008) plus the bootstrap's own noise.
TEST(StratifiedBootstrap, CoverageOfTheMeanOnNormalDataIsCloseToNominal) {
  Rng data_rng(2021);
  BootstrapOptions options;
  options.resamples = 1000;
  int covered = 0;
  const int samples = 1000;
  for (int s = 0; s < samples; ++s) {
    std::vector<double> sample(20);
    for (double& value : sample) value = standard_normal(data_rng);
    options.seed = static_cast<std::uint64_t>(s);
    const IntervalEstimate estimate =
        stratified_bootstrap_interval({sample}, pooled_statistic(PointStatistic::mean), options);
    if (estimate.low <= 0.0 && 0.0 <= estimate.high) ++covered;
  }
  const double coverage = static_cast<double>(covered) / samples;
  RecordProperty("coverage", std::to_string(coverage));  // in --gtest_output=xml
  EXPECT_NEAR(coverage, 0.929, 0.03) << covered << " of " << samples << " intervals held the true mean 0";
}

}  // namespace
}  // namespace bsg::experiments
