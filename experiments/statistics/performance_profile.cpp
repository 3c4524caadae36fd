#include "experiments/statistics/performance_profile.h"

#include <stdexcept>
#include <string>

#include "experiments/statistics/robust_statistics.h"

namespace bsg::experiments {

std::vector<double> profile_fractions(const Strata& scores, std::span<const double> thresholds) {
  if (scores.empty()) throw std::invalid_argument("performance profile of no runs");
  std::vector<double> fractions(thresholds.size(), 0.0);
  for (const std::vector<double>& stratum : scores) {
    if (stratum.empty()) throw std::invalid_argument("performance profile: a stratum without runs");
    for (std::size_t i = 0; i < thresholds.size(); ++i) fractions[i] += fraction_above(stratum, thresholds[i]);
  }
  for (double& fraction : fractions) fraction /= static_cast<double>(scores.size());
  return fractions;
}

std::vector<IntervalEstimate> performance_profile(const Strata& scores, std::span<const double> thresholds,
                                                  const BootstrapOptions& options) {
  const std::vector<double> taus(thresholds.begin(), thresholds.end());
  return stratified_bootstrap_bands(
      scores, [&taus](const Strata& strata) { return profile_fractions(strata, taus); }, options);
}

std::vector<double> evenly_spaced(double low, double high, std::size_t count) {
  if (count < 2 || !(low < high)) {
    throw std::invalid_argument("evenly spaced thresholds need count >= 2 and low < high, got " +
                                std::to_string(count) + " from " + std::to_string(low) + " to " +
                                std::to_string(high));
  }
  std::vector<double> values(count);
  for (std::size_t i = 0; i < count; ++i) {
    values[i] = low + (high - low) * static_cast<double>(i) / static_cast<double>(count - 1);
  }
  values.back() = high;
  return values;
}

}  // namespace bsg::experiments
