#include "experiments/statistics/robust_statistics.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace bsg::experiments {

namespace {

std::vector<double> sorted_copy(std::span<const double> values, const char* what) {
  if (values.empty()) throw std::invalid_argument(std::string(what) + " of no values");
  for (const double value : values) {
    if (std::isnan(value)) throw std::invalid_argument(std::string(what) + " of values holding a NaN");
  }
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  return sorted;
}

double mean_of_sorted(const std::vector<double>& sorted, std::size_t cut) {
  const std::size_t kept = sorted.size() - 2 * cut;
  return std::accumulate(sorted.begin() + static_cast<std::ptrdiff_t>(cut),
                         sorted.end() - static_cast<std::ptrdiff_t>(cut), 0.0) /
         static_cast<double>(kept);
}

}  // namespace

std::string_view to_string(PointStatistic statistic) {
  switch (statistic) {
    case PointStatistic::mean: return "mean";
    case PointStatistic::median: return "median";
    case PointStatistic::iqm: return "iqm";
  }
  return "?";
}

double mean_of(std::span<const double> values) {
  return mean_of_sorted(sorted_copy(values, "mean"), 0);
}

double median_of(std::span<const double> values) {
  return quantile_of(values, 0.5);
}

double interquartile_mean(std::span<const double> values) {
  const std::vector<double> sorted = sorted_copy(values, "interquartile mean");
  return mean_of_sorted(sorted, sorted.size() / 4);  // trim_mean(x, 0.25): floor(n / 4) from each end
}

double point_statistic(PointStatistic statistic, std::span<const double> values) {
  switch (statistic) {
    case PointStatistic::mean: return mean_of(values);
    case PointStatistic::median: return median_of(values);
    case PointStatistic::iqm: return interquartile_mean(values);
  }
  throw std::invalid_argument("unknown point statistic");
}

double quantile_of(std::span<const double> values, double q) {
  if (!(q >= 0.0 && q <= 1.0)) throw std::invalid_argument("quantile: q must be in [0, 1], got " + std::to_string(q));
  const std::vector<double> sorted = sorted_copy(values, "quantile");
  const double position = q * static_cast<double>(sorted.size() - 1);  // type 7: h = (n - 1) q
  const std::size_t below = static_cast<std::size_t>(std::floor(position));
  if (below + 1 >= sorted.size()) return sorted.back();
  const double weight = position - static_cast<double>(below);
  return sorted[below] + weight * (sorted[below + 1] - sorted[below]);
}

double fraction_above(std::span<const double> values, double threshold) {
  if (values.empty()) throw std::invalid_argument("fraction above a threshold of no values");
  const auto above = std::count_if(values.begin(), values.end(), [&](double v) { return v > threshold; });
  return static_cast<double>(above) / static_cast<double>(values.size());
}

}  // namespace bsg::experiments
