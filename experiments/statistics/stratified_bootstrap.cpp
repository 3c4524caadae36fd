#include "experiments/statistics/stratified_bootstrap.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg::experiments {

namespace {

IntervalEstimate percentile_interval(double point, std::vector<double>& replicates, double confidence) {
  const double tail = (1.0 - confidence) / 2.0;
  return {point, quantile_of(replicates, tail), quantile_of(replicates, 1.0 - tail)};
}

void check_finite_statistic(double value, const char* where) {
  if (std::isnan(value)) {
    throw std::invalid_argument(std::string("bootstrap: the statistic is NaN on the ") + where);
  }
}

}  // namespace

void check_bootstrap_options(const BootstrapOptions& options) {
  // Fewer resamples make the interval's own ends noisy (the 2.5 % quantile of
  // 100 values rests on 2-3 of them).
  if (options.resamples < 100) {
    throw std::invalid_argument("bootstrap resamples must be at least 100, got " + std::to_string(options.resamples));
  }
  if (!(options.confidence > 0.0 && options.confidence < 1.0)) {
    throw std::invalid_argument("bootstrap confidence must be in (0, 1), got " + std::to_string(options.confidence));
  }
}

void check_strata(const Strata& strata) {
  if (strata.empty()) throw std::invalid_argument("bootstrap: no stratum (no runs) to resample");
  for (std::size_t k = 0; k < strata.size(); ++k) {
    if (strata[k].size() < 2) {
      throw std::invalid_argument("bootstrap: stratum " + std::to_string(k) + " has " +
                                  std::to_string(strata[k].size()) +
                                  " value(s); an interval across seeds needs at least 2 (one seed would give "
                                  "an interval of width zero)");
    }
    for (const double value : strata[k]) {
      if (std::isnan(value)) throw std::invalid_argument("bootstrap: stratum " + std::to_string(k) + " holds a NaN");
    }
  }
}

Strata resample_strata(const Strata& strata, Rng& rng) {
  Strata resample(strata.size());
  for (std::size_t k = 0; k < strata.size(); ++k) {
    resample[k].reserve(strata[k].size());
    for (std::size_t i = 0; i < strata[k].size(); ++i) {
      resample[k].push_back(strata[k][uniform_index(rng, strata[k].size())]);
    }
  }
  return resample;
}

IntervalEstimate stratified_bootstrap_interval(const Strata& strata, const StrataStatistic& statistic,
                                               const BootstrapOptions& options) {
  const std::vector<IntervalEstimate> band = stratified_bootstrap_bands(
      strata, [&](const Strata& s) { return std::vector<double>{statistic(s)}; }, options);
  return band.front();
}

std::vector<IntervalEstimate> stratified_bootstrap_bands(const Strata& strata, const StrataCurve& statistic,
                                                         const BootstrapOptions& options) {
  check_bootstrap_options(options);
  check_strata(strata);
  const std::vector<double> point = statistic(strata);
  for (const double value : point) check_finite_statistic(value, "data");
  std::vector<std::vector<double>> replicates(point.size(), std::vector<double>(options.resamples));
  Rng rng(options.seed);
  for (std::size_t b = 0; b < options.resamples; ++b) {
    const std::vector<double> values = statistic(resample_strata(strata, rng));
    if (values.size() != point.size()) throw std::logic_error("bootstrap: the statistic changed its length");
    for (std::size_t i = 0; i < values.size(); ++i) {
      check_finite_statistic(values[i], "resample");
      replicates[i][b] = values[i];
    }
  }
  std::vector<IntervalEstimate> band;
  band.reserve(point.size());
  for (std::size_t i = 0; i < point.size(); ++i) {
    band.push_back(percentile_interval(point[i], replicates[i], options.confidence));
  }
  return band;
}

std::vector<double> pooled_values(const Strata& strata) {
  std::vector<double> values;
  for (const std::vector<double>& stratum : strata) values.insert(values.end(), stratum.begin(), stratum.end());
  return values;
}

StrataStatistic pooled_statistic(PointStatistic statistic) {
  return [statistic](const Strata& strata) { return point_statistic(statistic, pooled_values(strata)); };
}

StrataStatistic difference_statistic(PointStatistic statistic) {
  return [statistic](const Strata& strata) {
    if (strata.size() != 2) throw std::invalid_argument("a difference needs exactly two groups");
    return point_statistic(statistic, strata[0]) - point_statistic(statistic, strata[1]);
  };
}

}  // namespace bsg::experiments
