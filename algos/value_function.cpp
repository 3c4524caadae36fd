#include "algos/value_function.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace bsg {
namespace {

std::vector<int> value_layer_sizes(int observation_size, const std::vector<int>& hidden_sizes) {
  std::vector<int> sizes{observation_size};
  sizes.insert(sizes.end(), hidden_sizes.begin(), hidden_sizes.end());
  sizes.push_back(1);  // V(s) is a scalar
  return sizes;
}

}  // namespace

ValueFunction::ValueFunction(int observation_size, const std::vector<int>& hidden_sizes, Rng& rng,
                             MlpInitOptions init, AdamOptions adam)
    : net_(value_layer_sizes(observation_size, hidden_sizes), rng, init),
      optimizer_(net_.num_parameters(), adam),
      gradient_(net_.num_parameters()) {}

double ValueFunction::predict(const Eigen::Ref<const Eigen::VectorXd>& observation,
                              MlpSampleWorkspace& workspace) const {
  double value = 0.0;
  net_.forward(observation, Eigen::Map<Eigen::VectorXd>(&value, 1), workspace);
  return value;
}

void ValueFunction::predict_batch(const Eigen::Ref<const Eigen::MatrixXd>& observations,
                                  Eigen::Ref<Eigen::VectorXd> values) {
  if (values.size() != observations.rows()) {
    throw std::invalid_argument("ValueFunction::predict_batch: values has " + std::to_string(values.size()) +
                                " entries for " + std::to_string(observations.rows()) + " observations");
  }
  values = net_.forward_batch(observations, workspace_).col(0);
}

double ValueFunction::loss(const Eigen::Ref<const Eigen::MatrixXd>& observations,
                           const Eigen::Ref<const Eigen::VectorXd>& targets) {
  if (targets.size() != observations.rows() || targets.size() == 0) {
    throw std::invalid_argument("ValueFunction::loss: targets has " + std::to_string(targets.size()) +
                                " entries for " + std::to_string(observations.rows()) + " observations");
  }
  const Eigen::MatrixXd& predictions = net_.forward_batch(observations, workspace_);
  return (predictions.col(0) - targets).squaredNorm() / static_cast<double>(targets.size());
}

ValueFitStats ValueFunction::fit(const Eigen::Ref<const Eigen::MatrixXd>& observations,
                                 const Eigen::Ref<const Eigen::VectorXd>& targets, Rng& rng, const MpiContext& mpi,
                                 const ValueFitOptions& options) {
  const Eigen::Index n = observations.rows();
  if (targets.size() != n) {
    throw std::invalid_argument("ValueFunction::fit: targets has " + std::to_string(targets.size()) + " entries for " +
                                std::to_string(n) + " observations");
  }
  if (options.iterations <= 0 || options.num_mini_batches <= 0) {
    throw std::invalid_argument("ValueFunction::fit: iterations (" + std::to_string(options.iterations) +
                                ") and num_mini_batches (" + std::to_string(options.num_mini_batches) +
                                ") must be positive");
  }
  const Eigen::Index mini_batch_size = n / options.num_mini_batches;  // m = floor(N / 16)
  if (mini_batch_size < std::max<Eigen::Index>(1, options.min_mini_batch_size)) {
    throw std::invalid_argument("ValueFunction::fit: minibatch size floor(" + std::to_string(n) + " / " +
                                std::to_string(options.num_mini_batches) + ") = " + std::to_string(mini_batch_size) +
                                " is below min_mini_batch_size " + std::to_string(options.min_mini_batch_size) +
                                " (more local steps or fewer minibatches needed)");
  }
  ValueFitStats stats;
  stats.loss_before = loss(observations, targets);
  permutation_.resize(static_cast<std::size_t>(n));
  double loss_sum = 0.0;
  for (int pass = 0; pass < options.iterations; ++pass) {
    // Fisher–Yates shuffle with the rank's RNG (not NumPy's permutation stream).
    std::iota(permutation_.begin(), permutation_.end(), Eigen::Index{0});
    for (Eigen::Index i = n - 1; i > 0; --i) {
      const auto j = static_cast<Eigen::Index>(uniform_index(rng, static_cast<std::uint64_t>(i + 1)));
      std::swap(permutation_[static_cast<std::size_t>(i)], permutation_[static_cast<std::size_t>(j)]);
    }
    for (Eigen::Index start = 0; start < n; start += mini_batch_size) {
      const Eigen::Index rows = std::min(mini_batch_size, n - start);
      if (minibatch_observations_.rows() != rows || minibatch_observations_.cols() != observations.cols()) {
        minibatch_observations_.resize(rows, observations.cols());
        minibatch_targets_.resize(rows);
        output_gradients_.resize(rows, 1);
      }
      for (Eigen::Index i = 0; i < rows; ++i) {
        const Eigen::Index index = permutation_[static_cast<std::size_t>(start + i)];
        minibatch_observations_.row(i) = observations.row(index);
        minibatch_targets_[i] = targets[index];
      }
      const Eigen::MatrixXd& predictions = net_.forward_batch(minibatch_observations_, workspace_);
      output_gradients_.col(0) = predictions.col(0) - minibatch_targets_;  // V(s) - R
      loss_sum += output_gradients_.squaredNorm() / static_cast<double>(rows);  // mean (V - R)^2
      output_gradients_ *= 2.0 / static_cast<double>(rows);                    // d loss / dV
      net_.backward_batch(output_gradients_, workspace_, gradient_);
      mpi.average_in_place(gradient_);
      optimizer_.step(net_.mutable_parameters(), gradient_);
      ++stats.adam_steps;
    }
  }
  stats.mean_minibatch_loss = loss_sum / stats.adam_steps;
  return stats;
}

}  // namespace bsg
