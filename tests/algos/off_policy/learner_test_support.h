// What the off-policy learner tests share: random matrices, a small float64
// configuration of any off-policy algorithm, and targets moved away from the
// online networks.
#pragma once

#include <Eigen/Core>

#include "algos/off_policy/off_policy_learner.h"
#include "common/random.h"
#include "common/run_config.h"

namespace bsg::algos::learner_test {

// Entries uniform in [-scale, scale].
inline Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, Rng& rng, double scale = 1.0) {
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = scale * uniform(rng, -1.0, 1.0);
  return m;
}

// Hidden layers 6 and 5, float64, alpha 0.3, and TD3 updating its actor every step.
inline RunConfig config_for(Algorithm alg) {
  RunConfig config;
  config.alg = alg;
  config.hidden_sizes = {6, 5};
  config.dtype = Dtype::float64;
  config.off_policy.alpha_init = 0.3;
  config.off_policy.policy_delay = 1;
  return config;
}

// Random (not initial) targets so that they differ from the online nets.
inline void perturb_targets(OffPolicyLearner& learner, Rng& rng) {
  for (Mlp* net : learner.all_networks()) {
    net->set_parameters(net->parameters() + random_matrix(net->num_parameters(), 1, rng, 0.3));
  }
}

}  // namespace bsg::algos::learner_test
