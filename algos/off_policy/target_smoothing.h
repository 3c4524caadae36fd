// TD3's target policy smoothing (Fujimoto et al. 2018, eq. 14): the target action is
//   a' = clip(mu'(s') + clip(eps, -c, c), -1, 1),  eps ~ N(0, sigma^2)
// with sigma = policy_noise and c = noise_clip, so that Q' is averaged over a small neighbourhood
// of the target action rather than exploited at one point.
#pragma once

#include <Eigen/Core>

#include "common/random.h"

namespace bsg::algos {

// Adds the clipped noise to every entry of `actions` (N x |A|, the target actor's tanh outputs)
// and clips the result to [-1, 1].
void smooth_target_actions(Eigen::Ref<Eigen::MatrixXd> actions, double policy_noise, double noise_clip, Rng& rng);

// The same with given standard normal draws `noise` (same shape), for tests.
void smooth_target_actions(Eigen::Ref<Eigen::MatrixXd> actions, const Eigen::Ref<const Eigen::MatrixXd>& noise,
                           double policy_noise, double noise_clip);

}  // namespace bsg::algos
