// The values of one quantity over the seeds of one configuration (a final
// return J, a cost ratio H / d, a cumulative training cost), summarised as a
// reviewer asks for them: mean, median and interquartile mean, each with its
// bootstrap interval (one stratum: the seeds), and a proportion of seeds (the
// probability of feasibility) with the Wilson score interval.
#pragma once

#include <cstddef>
#include <span>

#include "experiments/statistics/stratified_bootstrap.h"

namespace bsg::experiments {

struct SeedSummary {
  std::size_t seeds = 0;
  IntervalEstimate mean;
  IntervalEstimate median;
  IntervalEstimate iqm;
};

// Throws std::invalid_argument with fewer than two values (check_strata).
SeedSummary summarise_seeds(std::span<const double> values, const BootstrapOptions& options);

// The Wilson score interval of a proportion k / n (Wilson 1927; Brown, Cai and
// DasGupta 2001 recommend it for small n): unlike a bootstrap of 3 seeds that
// all met the limit, 3/3 gives [0.44, 1] at 95 %, not [1, 1].
// point = k / n. Throws std::invalid_argument if n == 0, k > n or c not in (0, 1).
IntervalEstimate wilson_interval(std::size_t successes, std::size_t trials, double confidence);

// z with Phi(z) = p, p in (0, 1): the standard normal quantile (bisection on erfc).
double standard_normal_quantile(double p);

}  // namespace bsg::experiments
