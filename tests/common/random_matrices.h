// Random matrices for the tests of networks and updates: one definition, so that
// test files compiled in one batch do not each define their own.
#pragma once

#include <Eigen/Core>

#include "common/random.h"

namespace bsg::testing {

// Entries uniform in [-bound, bound].
inline Eigen::MatrixXd uniform_matrix(Eigen::Index rows, Eigen::Index cols, double bound, Rng& rng) {
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = uniform(rng, -bound, bound);
  return m;
}

// Entries standard normal.
inline Eigen::MatrixXd normal_matrix(Eigen::Index rows, Eigen::Index cols, Rng& rng) {
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = standard_normal(rng);
  return m;
}

}  // namespace bsg::testing
