// SAC's tanh-squashed Gaussian actor (Haarnoja et al. 2018, appendix C): the actor net outputs
// (mu, log sigma) per action dimension, log sigma clamped to [kLogStdMin, kLogStdMax]; an action is
//   u = mu + sigma eps, eps ~ N(0, I)   (reparameterised: the gradient flows through mu and sigma)
//   a = tanh(u)
//   log pi(a|s) = sum_j [ log N(u_j; mu_j, sigma_j) - log(1 - tanh(u_j)^2) ]
// with log(1 - tanh(u)^2) = 2 (log 2 - u - softplus(-2u)), the stable form of the log-determinant
// of the squashing's Jacobian (eq. 21 of the paper).
#pragma once

#include <Eigen/Core>

namespace bsg::algos {

inline constexpr double kLogStdMin = -20.0;  // SpinningUp's and OmniSafe's clamp
inline constexpr double kLogStdMax = 2.0;

// One batch of samples; every matrix N x |A|.
struct SquashedGaussianSample {
  Eigen::MatrixXd std;        // sigma = exp(clamped log sigma)
  Eigen::MatrixXd pre_tanh;   // u
  Eigen::MatrixXd actions;    // a = tanh(u)
  Eigen::VectorXd log_probs;  // log pi(a|s), N
};

// `outputs` N x 2|A| (mu | log sigma), `noise` N x |A| (eps). Resizes `sample` if needed.
void squashed_gaussian_sample(const Eigen::Ref<const Eigen::MatrixXd>& outputs,
                              const Eigen::Ref<const Eigen::MatrixXd>& noise, SquashedGaussianSample& sample);

// dL/d outputs (N x 2|A|) of a loss L(a, log pi) given dL/da (N x |A|) and dL/d log pi (N), for the
// sample drawn from `outputs` and `noise`. Clamped log sigma entries get no gradient.
void squashed_gaussian_backward(const Eigen::Ref<const Eigen::MatrixXd>& outputs,
                                const Eigen::Ref<const Eigen::MatrixXd>& noise, const SquashedGaussianSample& sample,
                                const Eigen::Ref<const Eigen::MatrixXd>& loss_action_gradient,
                                const Eigen::Ref<const Eigen::VectorXd>& loss_log_prob_gradient,
                                Eigen::Ref<Eigen::MatrixXd> loss_output_gradient);

// The deterministic action tanh(mu) of one sample's outputs (mu | log sigma).
void squashed_gaussian_mean_action(const Eigen::Ref<const Eigen::VectorXd>& outputs, Eigen::Ref<Eigen::VectorXd> action);

}  // namespace bsg::algos
