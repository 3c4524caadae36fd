#include "algos/core/squashed_gaussian.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace bsg::algos {
namespace {

double softplus(double x) { return x > 0 ? x + std::log1p(std::exp(-x)) : std::log1p(std::exp(x)); }

}  // namespace

void squashed_gaussian_sample(const Eigen::Ref<const Eigen::MatrixXd>& outputs,
                              const Eigen::Ref<const Eigen::MatrixXd>& noise, SquashedGaussianSample& sample) {
  const Eigen::Index rows = noise.rows();
  const Eigen::Index dims = noise.cols();
  if (sample.actions.rows() != rows || sample.actions.cols() != dims) {
    sample.std.resize(rows, dims);
    sample.pre_tanh.resize(rows, dims);
    sample.actions.resize(rows, dims);
    sample.log_probs.resize(rows);
  }
  const double half_log_two_pi = 0.5 * std::log(2.0 * std::numbers::pi);
  for (Eigen::Index i = 0; i < rows; ++i) {
    double log_prob = 0.0;
    for (Eigen::Index j = 0; j < dims; ++j) {
      const double log_std = std::clamp(outputs(i, dims + j), kLogStdMin, kLogStdMax);
      const double sigma = std::exp(log_std);
      const double eps = noise(i, j);
      const double u = outputs(i, j) + sigma * eps;  // u = mu + sigma eps
      sample.std(i, j) = sigma;
      sample.pre_tanh(i, j) = u;
      sample.actions(i, j) = std::tanh(u);
      // log N(u; mu, sigma) - log(1 - tanh(u)^2)
      log_prob += -0.5 * eps * eps - log_std - half_log_two_pi - 2.0 * (std::numbers::ln2 - u - softplus(-2.0 * u));
    }
    sample.log_probs(i) = log_prob;
  }
}

void squashed_gaussian_backward(const Eigen::Ref<const Eigen::MatrixXd>& outputs,
                                const Eigen::Ref<const Eigen::MatrixXd>& noise, const SquashedGaussianSample& sample,
                                const Eigen::Ref<const Eigen::MatrixXd>& loss_action_gradient,
                                const Eigen::Ref<const Eigen::VectorXd>& loss_log_prob_gradient,
                                Eigen::Ref<Eigen::MatrixXd> loss_output_gradient) {
  const Eigen::Index rows = noise.rows();
  const Eigen::Index dims = noise.cols();
  for (Eigen::Index i = 0; i < rows; ++i) {
    const double dlogp = loss_log_prob_gradient(i);
    for (Eigen::Index j = 0; j < dims; ++j) {
      const double a = sample.actions(i, j);
      // dL/du = dL/da (1 - a^2) + dL/dlogp d(-log(1 - tanh(u)^2))/du, the latter 2 tanh(u)
      const double du = loss_action_gradient(i, j) * (1.0 - a * a) + dlogp * 2.0 * a;
      loss_output_gradient(i, j) = du;  // du/dmu = 1
      const double log_std = outputs(i, dims + j);
      const bool clamped = log_std < kLogStdMin || log_std > kLogStdMax;
      // du/dlog sigma = sigma eps; log N(u; mu, sigma) with u reparameterised adds -1 per dimension
      loss_output_gradient(i, dims + j) = clamped ? 0.0 : du * sample.std(i, j) * noise(i, j) - dlogp;
    }
  }
}

void squashed_gaussian_mean_action(const Eigen::Ref<const Eigen::VectorXd>& outputs, Eigen::Ref<Eigen::VectorXd> action) {
  action = outputs.head(action.size()).array().tanh();
}

}  // namespace bsg::algos
