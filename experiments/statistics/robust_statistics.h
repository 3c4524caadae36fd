// Point statistics of a handful of runs (seeds): the mean, the median and the
// interquartile mean, and the empirical quantile behind percentile intervals.
//
// IQM (Agarwal et al. 2021, "Deep RL at the edge of the statistical
// precipice"): the mean of the middle half of the sorted values, defined as
// rliable computes it, scipy.stats.trim_mean(x, 0.25): floor(n / 4) values are
// cut from each end. With n < 4 nothing is cut and the IQM is the mean; with
// n = 4 or 5 the lowest and the highest are cut.
#pragma once

#include <span>
#include <string_view>

namespace bsg::experiments {

enum class PointStatistic { mean, median, iqm };
std::string_view to_string(PointStatistic statistic);

// Each throws std::invalid_argument when `values` is empty or holds a NaN.
double mean_of(std::span<const double> values);
double median_of(std::span<const double> values);
double interquartile_mean(std::span<const double> values);
double point_statistic(PointStatistic statistic, std::span<const double> values);

// The q-quantile, q in [0, 1], interpolated linearly between order statistics
// at position q (n - 1) (Hyndman and Fan's type 7, numpy's default).
double quantile_of(std::span<const double> values, double q);

// The fraction of `values` strictly above `threshold` (a performance profile's
// point, or the fraction of epochs over a cost limit).
double fraction_above(std::span<const double> values, double threshold);

}  // namespace bsg::experiments
