// The stratified bootstrap and its percentile interval (Efron and Tibshirani
// 1993, ch. 13; Agarwal et al. 2021, "Deep RL at the edge of the statistical
// precipice", section 4, as their rliable library computes it): the runs of
// each stratum (an environment, or the seeds of one configuration) are
// resampled with replacement to the stratum's own size, the statistic is
// computed on every resample, and the interval is the (1 - c) / 2 and
// (1 + c) / 2 quantiles of those values. Resampling within strata keeps every
// environment's weight fixed, so an aggregate over environments does not
// mistake the spread between environments for uncertainty.
//
// Reproducible: one seed gives the same resamples everywhere (common/random.h
// draws the indices by hand). A stratum with fewer than two values is refused:
// a single seed would give an interval of width zero that says nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "common/random.h"
#include "experiments/statistics/robust_statistics.h"

namespace bsg::experiments {

struct BootstrapOptions {
  std::size_t resamples = 2000;  // B
  double confidence = 0.95;      // c, the interval's nominal coverage
  std::uint64_t seed = 0;        // of the resampling engine
};

// Throws std::invalid_argument naming the option: resamples < 100, c not in (0, 1).
void check_bootstrap_options(const BootstrapOptions& options);

// A point estimate with its percentile interval [low, high].
struct IntervalEstimate {
  double point = 0.0;
  double low = 0.0;
  double high = 0.0;
};

using Strata = std::vector<std::vector<double>>;
using StrataStatistic = std::function<double(const Strata&)>;
using StrataCurve = std::function<std::vector<double>(const Strata&)>;

// Throws std::invalid_argument when there is no stratum, a stratum has fewer
// than two values (naming it by index) or a value is NaN.
void check_strata(const Strata& strata);

// One resample: stratum k becomes n_k draws with replacement from stratum k.
Strata resample_strata(const Strata& strata, Rng& rng);

// The statistic on the data and its percentile interval over
// `options.resamples` stratified resamples. Throws std::invalid_argument
// (check_strata, check_bootstrap_options) or when the statistic is NaN.
IntervalEstimate stratified_bootstrap_interval(const Strata& strata, const StrataStatistic& statistic,
                                               const BootstrapOptions& options);

// The same, pointwise, for a statistic with several values (a performance
// profile over thresholds, a learning curve over epochs): the i-th interval
// comes from the i-th value of every resample.
std::vector<IntervalEstimate> stratified_bootstrap_bands(const Strata& strata, const StrataCurve& statistic,
                                                         const BootstrapOptions& options);

// All values of all strata in one list.
std::vector<double> pooled_values(const Strata& strata);
// A point statistic of the pooled values (rliable's aggregate IQM, mean, median).
StrataStatistic pooled_statistic(PointStatistic statistic);
// The statistic of stratum 0 minus that of stratum 1 (two groups resampled apart).
StrataStatistic difference_statistic(PointStatistic statistic);

}  // namespace bsg::experiments
