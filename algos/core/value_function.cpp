#include "algos/core/value_function.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "algos/core/shuffle.h"

namespace bsg::algos {
namespace {

std::vector<int> value_layer_sizes(int observation_size, const std::vector<int>& hidden_sizes) {
  std::vector<int> sizes{observation_size};
  sizes.insert(sizes.end(), hidden_sizes.begin(), hidden_sizes.end());
  sizes.push_back(1);  // V(s) is a scalar
  return sizes;
}

}  // namespace

ValueFunction::ValueFunction(int observation_size, const std::vector<int>& hidden_sizes, Rng& rng,
                             MlpOptions init, AdamOptions adam)
    : net_(value_layer_sizes(observation_size, hidden_sizes), rng, init), optimizer_(net_.num_parameters(), adam) {}

void ValueFunction::scale_output(double factor) {
  if (!std::isfinite(factor) || factor <= 0.0) {
    throw std::invalid_argument("ValueFunction::scale_output: factor must be finite and positive, got " +
                                std::to_string(factor));
  }
  const int last = net_.num_layers() - 1;
  const Eigen::Index weights = net_.weights(last).size();
  Eigen::Map<Eigen::VectorXd> parameters = net_.mutable_parameters();
  parameters.segment(net_.weight_offset(last), weights) *= factor;
  parameters.segment(net_.bias_offset(last), net_.output_size()) *= factor;
}

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
  net_.evaluate_batch(observations, Eigen::Map<Eigen::MatrixXd>(values.data(), values.size(), 1), workspace_);
}

double ValueFunction::loss(const Eigen::Ref<const Eigen::MatrixXd>& observations,
                           const Eigen::Ref<const Eigen::VectorXd>& targets) {
  if (targets.size() != observations.rows() || targets.size() == 0) {
    throw std::invalid_argument("ValueFunction::loss: targets has " + std::to_string(targets.size()) +
                                " entries for " + std::to_string(observations.rows()) + " observations");
  }
  if (predictions_.size() != targets.size()) predictions_.resize(targets.size());
  predict_batch(observations, predictions_);
  return (predictions_ - targets).squaredNorm() / static_cast<double>(targets.size());
}

double ValueFunction::loss_and_gradient(const Eigen::Ref<const Eigen::MatrixXd>& observations,
                                        const Eigen::Ref<const Eigen::VectorXd>& targets,
                                        Eigen::Ref<Eigen::VectorXd> gradient) {
  const Eigen::Index rows = observations.rows();
  if (targets.size() != rows || rows == 0) {
    throw std::invalid_argument("ValueFunction::loss_and_gradient: targets has " + std::to_string(targets.size()) +
                                " entries for " + std::to_string(rows) + " observations");
  }
  double squared_error = 0.0;
  const auto output_gradient = [&](Eigen::Index first, const Eigen::Ref<const Eigen::MatrixXd>& values,
                                   Eigen::Ref<Eigen::MatrixXd> output_gradients) {
    output_gradients.col(0) = values.col(0) - targets.segment(first, values.rows());  // V(s) - R
    squared_error += output_gradients.squaredNorm();
    output_gradients *= 2.0 / static_cast<double>(rows);  // d/dV of mean (V - R)^2
  };
  net_.gradient_batch(observations, output_gradient, workspace_, gradient);
  return squared_error / static_cast<double>(rows);
}

ValueFitStats ValueFunction::fit(const Eigen::Ref<const Eigen::MatrixXd>& observations,
                                 const Eigen::Ref<const Eigen::VectorXd>& targets, Rng& rng, const MpiContext& mpi,
                                 const ValueFitOptions& options) {
  const ValueFitJob job{*this, targets};
  return fit_value_functions(std::span<const ValueFitJob>(&job, 1), observations, rng, mpi, options).front();
}

std::vector<ValueFitStats> fit_value_functions(std::span<const ValueFitJob> jobs,
                                               const Eigen::Ref<const Eigen::MatrixXd>& observations, Rng& rng,
                                               const MpiContext& mpi, const ValueFitOptions& options) {
  const Eigen::Index n = observations.rows();
  for (const ValueFitJob& job : jobs) {
    if (job.targets.size() != n) {
      throw std::invalid_argument("ValueFunction::fit: targets has " + std::to_string(job.targets.size()) +
                                  " entries for " + std::to_string(n) + " observations");
    }
    if (job.value.net().input_size() != observations.cols()) {
      throw std::invalid_argument("ValueFunction::fit: observations have " + std::to_string(observations.cols()) +
                                  " columns, the value net expects " + std::to_string(job.value.net().input_size()));
    }
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
  std::vector<ValueFitStats> stats(jobs.size());
  std::vector<Eigen::Index> offsets;  // of each job's gradient in the fused allreduce buffer
  Eigen::Index total_parameters = 0;
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    stats[j].loss_before = jobs[j].value.loss(observations, jobs[j].targets);
    offsets.push_back(total_parameters);
    total_parameters += jobs[j].value.net().num_parameters();
  }
  Eigen::VectorXd gradients(total_parameters);
  Eigen::MatrixXd minibatch_observations(mini_batch_size, observations.cols());
  Eigen::MatrixXd minibatch_targets(mini_batch_size, static_cast<Eigen::Index>(jobs.size()));
  std::vector<double> loss_sums(jobs.size(), 0.0);
  std::vector<Eigen::Index> permutation(static_cast<std::size_t>(n));
  int adam_steps = 0;
  for (int pass = 0; pass < options.iterations; ++pass) {
    shuffle_permutation(permutation, rng);
    for (Eigen::Index start = 0; start < n; start += mini_batch_size) {
      const Eigen::Index rows = std::min(mini_batch_size, n - start);
      for (Eigen::Index i = 0; i < rows; ++i) {
        const Eigen::Index index = permutation[static_cast<std::size_t>(start + i)];
        minibatch_observations.row(i) = observations.row(index);
        for (std::size_t j = 0; j < jobs.size(); ++j) {
          minibatch_targets(i, static_cast<Eigen::Index>(j)) = jobs[j].targets[index];
        }
      }
      for (std::size_t j = 0; j < jobs.size(); ++j) {
        ValueFunction& value = jobs[j].value;
        loss_sums[j] += value.loss_and_gradient(  // mean (V - R)^2 and its gradient
            minibatch_observations.topRows(rows), minibatch_targets.col(static_cast<Eigen::Index>(j)).head(rows),
            gradients.segment(offsets[j], value.net().num_parameters()));
      }
      mpi.average_in_place(gradients);  // one allreduce for all the networks
      for (std::size_t j = 0; j < jobs.size(); ++j) {
        ValueFunction& value = jobs[j].value;
        value.optimizer().step(value.net().mutable_parameters(),
                               gradients.segment(offsets[j], value.net().num_parameters()));
      }
      ++adam_steps;
    }
  }
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    stats[j].adam_steps = adam_steps;
    stats[j].mean_minibatch_loss = loss_sums[j] / adam_steps;
  }
  return stats;
}

}  // namespace bsg::algos
