// Adam optimiser with PyTorch's update rule (docs/algorithms.md#pdo, #value-fits): the value nets use
// lr = 1e-3, PDO's Lagrange multiplier a one-element instance. The state (first
// and second moments, step count) persists across calls and can be saved.
//
// Parameters:
//   learning_rate  1e-3
//   beta1, beta2   0.9, 0.999
//   epsilon        1e-8
#pragma once

#include <Eigen/Core>

namespace bsg {

struct AdamOptions {
  double learning_rate = 1e-3;
  double beta1 = 0.9;
  double beta2 = 0.999;
  double epsilon = 1e-8;
};

class Adam {
 public:
  Adam(Eigen::Index num_parameters, AdamOptions options = {});

  // One step on `parameters` along the loss gradient `gradient` (descent).
  void step(Eigen::Ref<Eigen::VectorXd> parameters, const Eigen::Ref<const Eigen::VectorXd>& gradient);

  const AdamOptions& options() const { return options_; }
  Eigen::Index num_parameters() const { return first_moment_.size(); }
  const Eigen::VectorXd& first_moment() const { return first_moment_; }
  const Eigen::VectorXd& second_moment() const { return second_moment_; }
  long long step_count() const { return step_count_; }

  // Restores a saved state (e.g. from a checkpoint); sizes must match.
  void set_state(const Eigen::Ref<const Eigen::VectorXd>& first_moment,
                 const Eigen::Ref<const Eigen::VectorXd>& second_moment, long long step_count);

 private:
  AdamOptions options_;
  Eigen::VectorXd first_moment_;   // m
  Eigen::VectorXd second_moment_;  // v
  long long step_count_ = 0;       // t
};

}  // namespace bsg
