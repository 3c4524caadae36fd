#include "algos/offline/offline_learner_parts.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bsg::algos {

std::vector<int> mlp_layers(int input, const std::vector<int>& hidden, int output) {
  std::vector<int> sizes{input};
  sizes.insert(sizes.end(), hidden.begin(), hidden.end());
  sizes.push_back(output);
  return sizes;
}

void fill_standard_normal(Rng& rng, Eigen::MatrixXd& noise, Eigen::Index rows, Eigen::Index cols) {
  noise.resize(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i) {
    for (Eigen::Index j = 0; j < cols; ++j) noise(i, j) = standard_normal(rng);
  }
}

void check_batch_fits(const OfflineBatch& batch, int observation_size, int action_size, std::string_view learner) {
  const Eigen::Index n = batch.observations.rows();
  if (n < 1 || batch.observations.cols() != observation_size || batch.actions.cols() != action_size ||
      batch.actions.rows() != n || batch.next_observations.rows() != n ||
      batch.next_observations.cols() != observation_size || batch.rewards.size() != n || batch.costs.size() != n ||
      batch.terminals.size() != n) {
    throw std::invalid_argument(std::string(learner) + ": a batch of " + std::to_string(n) +
                                " rows does not fit its networks");
  }
}

double per_step_cost_threshold(double cost_limit, double gamma, int episode_length) {
  if (gamma == 1.0) return cost_limit;  // the limit of (1 - gamma^T) / (1 - gamma) is T
  return cost_limit * (1.0 - std::pow(gamma, episode_length)) / (1.0 - gamma) / episode_length;
}

}  // namespace bsg::algos
