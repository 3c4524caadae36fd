// The mean of a sample of episodes with its standard deviation and the
// variance of the mean, for the statistical comparisons of two samples
// (Welch's z) in the environment tests.
#pragma once

#include <cmath>
#include <vector>

namespace bsg::testing {

struct MeanAndError {
  double mean = 0;
  double sd = 0;                // sample standard deviation (n - 1)
  double variance_of_mean = 0;  // s²/n
};

inline MeanAndError mean_and_error(const std::vector<double>& x) {
  const double n = static_cast<double>(x.size());
  MeanAndError result;
  for (double v : x) result.mean += v;
  result.mean /= n;
  double ss = 0;
  for (double v : x) ss += (v - result.mean) * (v - result.mean);
  result.sd = std::sqrt(ss / (n - 1));
  result.variance_of_mean = ss / (n - 1) / n;
  return result;
}

}  // namespace bsg::testing
