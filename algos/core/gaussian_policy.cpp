#include "algos/core/gaussian_policy.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace bsg::algos {
namespace {

std::vector<int> layer_sizes_of(int observation_size, int action_size, const std::vector<int>& hidden_sizes) {
  std::vector<int> sizes{observation_size};
  sizes.insert(sizes.end(), hidden_sizes.begin(), hidden_sizes.end());
  sizes.push_back(action_size);
  return sizes;
}

std::string shape(const Eigen::Ref<const Eigen::MatrixXd>& m) {
  return std::to_string(m.rows()) + " x " + std::to_string(m.cols());
}

const double kHalfLog2Pi = 0.5 * std::log(2.0 * std::numbers::pi);

// sigma_k = 0.499 (1 - k/n) + 0.01: 0.509 at k = 0, 0.01 at k = n.
double linear_std(int k, int n) { return 0.499 * (1.0 - static_cast<double>(k) / n) + 0.01; }

}  // namespace

GaussianPolicy::GaussianPolicy(int observation_size, int action_size, const std::vector<int>& hidden_sizes,
                               Rng& rng, MlpOptions init)
    : mean_net_(layer_sizes_of(observation_size, action_size, hidden_sizes), rng, init) {}

double GaussianPolicy::std() const { return has_learned_std() ? log_stds_.array().exp().mean() : std_; }

double GaussianPolicy::log_std() const { return has_learned_std() ? log_stds_.mean() : std::log(std_); }

void GaussianPolicy::learn_log_std(double initial_std) {
  if (!(initial_std > 0.0) || !std::isfinite(initial_std)) {
    throw std::invalid_argument("GaussianPolicy::learn_log_std: the initial std must be positive and finite, got " +
                                std::to_string(initial_std));
  }
  log_stds_ = Eigen::VectorXd::Constant(action_size(), std::log(initial_std));
}

void GaussianPolicy::set_log_stds(const Eigen::Ref<const Eigen::VectorXd>& log_stds) {
  if (!has_learned_std()) throw std::invalid_argument("GaussianPolicy::set_log_stds: the policy's sigma is not learned");
  if (log_stds.size() != action_size() || !log_stds.allFinite()) {
    throw std::invalid_argument("GaussianPolicy::set_log_stds: expected " + std::to_string(action_size()) +
                                " finite entries, got " + std::to_string(log_stds.size()));
  }
  log_stds_ = log_stds;
}

void GaussianPolicy::set_std(double std) {
  if (has_learned_std()) throw std::invalid_argument("GaussianPolicy::set_std: the policy learns its log sigma");
  if (!(std > 0.0) || !std::isfinite(std)) {
    throw std::invalid_argument("GaussianPolicy::set_std: std must be positive and finite, got " +
                                std::to_string(std));
  }
  std_ = std;
}

double GaussianPolicy::annealed_std(int epoch, int epochs) {
  if (epochs <= 0 || epoch < 0 || epoch >= epochs) {
    throw std::invalid_argument("GaussianPolicy::annealed_std: epoch " + std::to_string(epoch) +
                                " must lie in [0, epochs = " + std::to_string(epochs) + ")");
  }
  return linear_std(epoch, epochs);
}

double GaussianPolicy::annealed_std(int epoch, int epochs, int anneal_epochs) {
  if (anneal_epochs < 0 || anneal_epochs > epochs) {
    throw std::invalid_argument("GaussianPolicy::annealed_std: anneal_epochs " + std::to_string(anneal_epochs) +
                                " must lie in [0, epochs = " + std::to_string(epochs) + "]");
  }
  if (anneal_epochs == 0) return annealed_std(epoch, epochs);
  annealed_std(epoch, epochs);  // the same check of epoch
  return linear_std(std::min(epoch, anneal_epochs), anneal_epochs);
}

void GaussianPolicy::mean_action(const Eigen::Ref<const Eigen::VectorXd>& observation,
                                 Eigen::Ref<Eigen::VectorXd> action, MlpSampleWorkspace& workspace) const {
  mean_net_.forward(observation, action, workspace);
}

double GaussianPolicy::sample_action(const Eigen::Ref<const Eigen::VectorXd>& observation,
                                     Eigen::Ref<Eigen::VectorXd> action, Rng& rng,
                                     MlpSampleWorkspace& workspace) const {
  mean_net_.forward(observation, action, workspace);
  double squared_noise = 0.0;
  if (has_learned_std()) {
    for (Eigen::Index j = 0; j < action.size(); ++j) {
      const double noise = standard_normal(rng);  // eps_j
      squared_noise += noise * noise;
      action[j] += std::exp(log_stds_[j]) * noise;  // a_j = mu_j + sigma_j eps_j
    }
    return -0.5 * squared_noise - log_stds_.sum() - action.size() * kHalfLog2Pi;
  }
  for (Eigen::Index j = 0; j < action.size(); ++j) {
    const double noise = standard_normal(rng);  // eps_j
    squared_noise += noise * noise;
    action[j] += std_ * noise;  // a = mu + sigma eps
  }
  // log pi(a|s) with (a - mu)/sigma = eps
  return -0.5 * squared_noise - action.size() * (log_std() + kHalfLog2Pi);
}

double GaussianPolicy::log_prob(const Eigen::Ref<const Eigen::VectorXd>& mean,
                                const Eigen::Ref<const Eigen::VectorXd>& action) const {
  if (mean.size() != action_size() || action.size() != action_size()) {
    throw std::invalid_argument("GaussianPolicy::log_prob: mean has " + std::to_string(mean.size()) +
                                " and action " + std::to_string(action.size()) + " entries, expected " +
                                std::to_string(action_size()));
  }
  if (has_learned_std()) {
    return -0.5 * ((action - mean).array() * (-log_stds_.array()).exp()).square().sum() - log_stds_.sum() -
           action_size() * kHalfLog2Pi;
  }
  return -0.5 * (action - mean).squaredNorm() / (std_ * std_) - action_size() * (log_std() + kHalfLog2Pi);
}

void GaussianPolicy::log_prob_batch(const Eigen::Ref<const Eigen::MatrixXd>& means,
                                    const Eigen::Ref<const Eigen::MatrixXd>& actions,
                                    Eigen::Ref<Eigen::VectorXd> log_probs) const {
  if (means.cols() != action_size() || actions.rows() != means.rows() || actions.cols() != means.cols() ||
      log_probs.size() != means.rows()) {
    throw std::invalid_argument("GaussianPolicy::log_prob_batch: means " + shape(means) + ", actions " +
                                shape(actions) + " and log_probs of " + std::to_string(log_probs.size()) +
                                " do not match N x " + std::to_string(action_size()) + " / N");
  }
  if (has_learned_std()) {
    const Eigen::RowVectorXd inverse_stds = (-log_stds_.array()).exp().matrix().transpose();
    log_probs = -0.5 * ((actions - means).array().rowwise() * inverse_stds.array()).square().rowwise().sum().matrix();
    log_probs.array() -= log_stds_.sum() + action_size() * kHalfLog2Pi;
    return;
  }
  const double constant = action_size() * (log_std() + kHalfLog2Pi);
  log_probs = -0.5 / (std_ * std_) * (actions - means).rowwise().squaredNorm();
  log_probs.array() -= constant;
}

double GaussianPolicy::entropy_per_dimension() const { return 0.5 + kHalfLog2Pi + log_std(); }

double GaussianPolicy::mean_kl(const Eigen::Ref<const Eigen::MatrixXd>& old_means,
                               const Eigen::Ref<const Eigen::MatrixXd>& new_means) const {
  if (old_means.cols() != action_size() || new_means.rows() != old_means.rows() ||
      new_means.cols() != old_means.cols()) {
    throw std::invalid_argument("GaussianPolicy::mean_kl: old_means " + shape(old_means) + " and new_means " +
                                shape(new_means) + " must both be N x " + std::to_string(action_size()));
  }
  if (old_means.rows() == 0) throw std::invalid_argument("GaussianPolicy::mean_kl: empty batch");
  // KL_bar = 1/(N d_a) sum (mu_old - mu)^2 / (2 sigma^2)   (Q8: mean over dims too)
  if (has_learned_std()) {
    const Eigen::RowVectorXd inverse_stds = (-log_stds_.array()).exp().matrix().transpose();
    return ((old_means - new_means).array().rowwise() * inverse_stds.array()).square().sum() / 2.0 /
           static_cast<double>(old_means.size());
  }
  return (old_means - new_means).squaredNorm() / (2.0 * std_ * std_) / static_cast<double>(old_means.size());
}

double GaussianPolicy::mean_kl(const Eigen::Ref<const Eigen::MatrixXd>& old_means,
                               const Eigen::Ref<const Eigen::MatrixXd>& new_means,
                               const Eigen::VectorXd& old_log_stds) const {
  if (!has_learned_std() || old_log_stds.size() != action_size()) {
    throw std::invalid_argument("GaussianPolicy::mean_kl: old log sigmas need a learned log sigma of " +
                                std::to_string(action_size()) + " entries, got " + std::to_string(old_log_stds.size()));
  }
  const double means_part = mean_kl(old_means, new_means);  // checks the shapes
  const Eigen::ArrayXd old_variances = (2.0 * old_log_stds.array()).exp();
  const Eigen::ArrayXd variances = (2.0 * log_stds_.array()).exp();
  // the sigma part does not depend on the sample: its mean over samples and dimensions is its mean over dimensions
  return means_part + (log_stds_.array() - old_log_stds.array() + old_variances / (2.0 * variances) - 0.5).mean();
}

}  // namespace bsg::algos
