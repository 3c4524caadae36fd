// Performance profiles (Dolan and Moré 2002, in the form of Agarwal et al.
// 2021, section 4.2, "score distributions"): for each threshold tau, the
// fraction of runs whose score exceeds tau. Each stratum (environment) counts
// with the same weight: the profile is the mean over strata of the fraction of
// the stratum's runs above tau (the pooled fraction when every stratum holds as
// many runs, as in rliable). Bands are pointwise stratified bootstrap intervals.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "experiments/statistics/stratified_bootstrap.h"

namespace bsg::experiments {

// The profile's values at each threshold; throws std::invalid_argument on an
// empty stratum list or an empty stratum.
std::vector<double> profile_fractions(const Strata& scores, std::span<const double> thresholds);

// The profile with pointwise intervals (check_strata's rules apply: at least
// two runs per stratum).
std::vector<IntervalEstimate> performance_profile(const Strata& scores, std::span<const double> thresholds,
                                                  const BootstrapOptions& options);

// `count` thresholds from `low` to `high`, both included (count >= 2, low < high).
std::vector<double> evenly_spaced(double low, double high, std::size_t count);

}  // namespace bsg::experiments
