#include "experiments/statistics/seed_summary.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace bsg::experiments {

SeedSummary summarise_seeds(std::span<const double> values, const BootstrapOptions& options) {
  const Strata strata{std::vector<double>(values.begin(), values.end())};
  SeedSummary summary;
  summary.seeds = values.size();
  summary.mean = stratified_bootstrap_interval(strata, pooled_statistic(PointStatistic::mean), options);
  summary.median = stratified_bootstrap_interval(strata, pooled_statistic(PointStatistic::median), options);
  summary.iqm = stratified_bootstrap_interval(strata, pooled_statistic(PointStatistic::iqm), options);
  return summary;
}

double standard_normal_quantile(double p) {
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("normal quantile: p must be in (0, 1), got " + std::to_string(p));
  // Phi(z) = erfc(-z / sqrt 2) / 2 rises with z; 200 halvings of [-40, 40] reach double precision.
  double low = -40.0;
  double high = 40.0;
  for (int i = 0; i < 200 && high - low > 1e-15; ++i) {
    const double middle = 0.5 * (low + high);
    (0.5 * std::erfc(-middle / std::sqrt(2.0)) < p ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

IntervalEstimate wilson_interval(std::size_t successes, std::size_t trials, double confidence) {
  if (trials == 0) throw std::invalid_argument("a proportion of no trials");
  if (successes > trials) throw std::invalid_argument("a proportion with more successes than trials");
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw std::invalid_argument("confidence must be in (0, 1), got " + std::to_string(confidence));
  }
  const double n = static_cast<double>(trials);
  const double p = static_cast<double>(successes) / n;
  const double z = standard_normal_quantile(0.5 + confidence / 2.0);
  // (p + z^2 / 2n -+ z sqrt(p (1 - p) / n + z^2 / 4n^2)) / (1 + z^2 / n)
  const double centre = p + z * z / (2.0 * n);
  const double spread = z * std::sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n));
  const double scale = 1.0 + z * z / n;
  return {p, std::max(0.0, (centre - spread) / scale), std::min(1.0, (centre + spread) / scale)};
}

}  // namespace bsg::experiments
