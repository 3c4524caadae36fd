#include "algos/off_policy/target_smoothing.h"

#include <algorithm>

namespace bsg::algos {

void smooth_target_actions(Eigen::Ref<Eigen::MatrixXd> actions, const Eigen::Ref<const Eigen::MatrixXd>& noise,
                           double policy_noise, double noise_clip) {
  for (Eigen::Index i = 0; i < actions.rows(); ++i) {
    for (Eigen::Index j = 0; j < actions.cols(); ++j) {
      const double eps = std::clamp(policy_noise * noise(i, j), -noise_clip, noise_clip);
      actions(i, j) = std::clamp(actions(i, j) + eps, -1.0, 1.0);
    }
  }
}

void smooth_target_actions(Eigen::Ref<Eigen::MatrixXd> actions, double policy_noise, double noise_clip, Rng& rng) {
  for (Eigen::Index i = 0; i < actions.rows(); ++i) {
    for (Eigen::Index j = 0; j < actions.cols(); ++j) {
      const double eps = std::clamp(policy_noise * standard_normal(rng), -noise_clip, noise_clip);
      actions(i, j) = std::clamp(actions(i, j) + eps, -1.0, 1.0);
    }
  }
}

}  // namespace bsg::algos
