// The MLP's forward pass written from docs/algorithms.md#networks with explicit loops over the flat
// parameter vector ([W_1, b_1, W_2, b_2, ...], each W row-major): the oracle of the Mlp tests.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "common/activation.h"

namespace bsg::testing {

inline Eigen::VectorXd reference_forward(const std::vector<int>& sizes, const Eigen::VectorXd& theta,
                                         const Eigen::VectorXd& input, Activation activation = Activation::tanh) {
  Eigen::VectorXd x = input;
  Eigen::Index offset = 0;
  for (std::size_t layer = 0; layer + 1 < sizes.size(); ++layer) {
    const int in = sizes[layer];
    const int out = sizes[layer + 1];
    Eigen::VectorXd y(out);
    for (int o = 0; o < out; ++o) {
      double sum = theta[offset + out * in + o];  // b_o after the row-major W
      for (int i = 0; i < in; ++i) sum += theta[offset + o * in + i] * x[i];
      const bool hidden = layer + 2 < sizes.size();
      y[o] = !hidden ? sum : activation == Activation::relu ? std::max(0.0, sum) : std::tanh(sum);
    }
    offset += out * in + out;
    x = y;
  }
  return x;
}

}  // namespace bsg::testing
